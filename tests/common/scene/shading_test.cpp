#include "common/scene/shading.h"

#include <cmath>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

namespace glint {
namespace {

// Values worked out by hand from the thesis's formulas.
const glm::vec3 kN(0.0f, 0.0f, 1.0f);
const glm::vec3 kL = glm::normalize(glm::vec3(1.0f, 0.0f, 1.0f));  // N . L = 1/sqrt(2)
const glm::vec3 kC(1.0f, 0.5f, 0.25f);

TEST(Phong, Ambient) {
  const glm::vec3 a = phongAmbient(kC, 0.1f);
  EXPECT_FLOAT_EQ(a.x, 0.1f);
  EXPECT_FLOAT_EQ(a.y, 0.05f);
  EXPECT_FLOAT_EQ(a.z, 0.025f);
}

TEST(Phong, DiffuseIsLambert) {
  const glm::vec3 d = phongDiffuse(glm::vec3(1.0f), kC, 0.8f, kN, kL);
  EXPECT_NEAR(d.x, 0.8f * 0.70710678f, 1e-6f);
  EXPECT_NEAR(d.y, 0.4f * 0.70710678f, 1e-6f);
  EXPECT_NEAR(d.z, 0.2f * 0.70710678f, 1e-6f);
  EXPECT_EQ(phongDiffuse(glm::vec3(1.0f), kC, 0.8f, kN, -kL), glm::vec3(0.0f));  // light behind
}

// (V . R)^h is power()'s, the same bits on every machine: with N = L = z,
// R = z and V . R is V's z exactly. These operands are ones where glibc's
// FMA powf (chosen at run time on CPUs with FMA) rounds one ulp off.
TEST(Phong, SpecularPowerIsTheNearestFloatOnEveryMachine) {
  const glm::vec3 z(0.0f, 0.0f, 1.0f);
  volatile float vr = 0x1.b5d6ep-1f;  // volatile: not worked out by the compiler
  volatile float h = 0x1.5afb9cp+7f;
  const glm::vec3 s = phongSpecular(glm::vec3(1.0f), 1.0f, h, z, z, glm::vec3(0.0f, 0.0f, vr));
  EXPECT_EQ(s.x, 0x1.c8e114p-40f);
}

TEST(Phong, SpecularUsesReflectedLightDirection) {
  // R = 2 (N.L) N - L = (-1/sqrt2, 0, 1/sqrt2); with V = N, V.R = 1/sqrt2; h = 2 -> 0.5.
  const glm::vec3 s = phongSpecular(glm::vec3(1.0f, 2.0f, 4.0f), 0.5f, 2.0f, kN, kL, kN);
  EXPECT_NEAR(s.x, 0.25f, 1e-6f);
  EXPECT_NEAR(s.y, 0.5f, 1e-6f);
  EXPECT_NEAR(s.z, 1.0f, 1e-6f);
  // Viewer on the mirror direction: V.R = 1, the full r_S.
  const glm::vec3 r(-kL.x, 0.0f, kL.z);
  EXPECT_NEAR(phongSpecular(glm::vec3(1.0f), 0.5f, 50.0f, kN, kL, r).x, 0.5f, 1e-5f);
  // Viewer away from R: nothing.
  EXPECT_EQ(phongSpecular(glm::vec3(1.0f), 0.5f, 2.0f, kN, kL, kL * glm::vec3(1, 1, -1)), glm::vec3(0.0f));
}

TEST(Phong, AttenuationIsOpenGLsFormula) {
  // 2 / (1 + 0.5 * 2 + 0.25 * 4) = 2 / 3.
  EXPECT_NEAR(attenuate(glm::vec3(2.0f), {1.0f, 0.5f, 0.25f}, 2.0f).x, 2.0f / 3.0f, 1e-6f);
  // The thesis's I_L = C / (a d^2) is the pure quadratic case.
  EXPECT_NEAR(attenuate(glm::vec3(1.0f), {0.0f, 0.0f, 0.5f}, 4.0f).x, 1.0f / 8.0f, 1e-6f);
}

}  // namespace
}  // namespace glint

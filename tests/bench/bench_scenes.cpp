#include "tests/bench/bench_scenes.h"

#include <cmath>
#include <random>

#include <glm/geometric.hpp>

namespace glint::bench {
namespace {

float height(float x, float z) {
  return 2.0f * std::sin(0.21f * x) * std::cos(0.37f * z) + 0.7f * std::sin(1.3f * x + 0.4f * z) +
         0.2f * std::cos(3.1f * z - 2.3f * x);
}

}  // namespace

Geometry terrain(int gridWidth, int gridDepth) {
  MeshInput mesh;
  mesh.positions.reserve(static_cast<std::size_t>(gridWidth + 1) * static_cast<std::size_t>(gridDepth + 1));
  for (int j = 0; j <= gridDepth; ++j) {
    for (int i = 0; i <= gridWidth; ++i) {
      const float x = -50.0f + 100.0f * static_cast<float>(i) / static_cast<float>(gridWidth);
      const float z = -25.0f + 50.0f * static_cast<float>(j) / static_cast<float>(gridDepth);
      mesh.positions.emplace_back(x, height(x, z), z);
    }
  }
  const auto row = static_cast<std::uint32_t>(gridWidth + 1);
  mesh.indices.reserve(static_cast<std::size_t>(gridWidth) * static_cast<std::size_t>(gridDepth) * 6);
  for (int j = 0; j < gridDepth; ++j) {
    for (int i = 0; i < gridWidth; ++i) {
      const std::uint32_t a = static_cast<std::uint32_t>(j) * row + static_cast<std::uint32_t>(i);
      mesh.indices.insert(mesh.indices.end(), {a, a + 1, a + row, a + 1, a + row + 1, a + row});
    }
  }
  Geometry g;
  g.addMesh(std::move(mesh));
  return g;
}

MeshInput rippledSphere(int n) {
  MeshInput mesh;
  for (int i = 0; i <= n; ++i) {
    const double theta = M_PI * i / n;
    for (int j = 0; j < n; ++j) {
      const double phi = 2 * M_PI * j / n, r = 1 + 0.05 * std::sin(7 * theta) * std::cos(9 * phi);
      mesh.positions.emplace_back(r * std::sin(theta) * std::cos(phi), r * std::cos(theta),
                                  r * std::sin(theta) * std::sin(phi));
    }
  }
  const auto row = static_cast<std::uint32_t>(n);
  for (std::uint32_t i = 0; i < row; ++i) {
    for (std::uint32_t j = 0; j < row; ++j) {
      const std::uint32_t a = i * row + j, b = i * row + (j + 1) % row, c = a + row, d = b + row;
      mesh.indices.insert(mesh.indices.end(), {a, c, b, b, c, d});
    }
  }
  return mesh;
}

std::vector<Ray> terrainRays(int count, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> x(-50.0f, 50.0f), z(-25.0f, 25.0f), up(10.0f, 40.0f);
  std::uniform_real_distribution<float> aside(-10.0f, 10.0f);
  std::vector<Ray> rays;
  rays.reserve(static_cast<std::size_t>(count));
  for (int i = 0; i < count; ++i) {
    const glm::vec3 target(x(rng), 0.0f, z(rng));
    const glm::vec3 origin = target + glm::vec3(aside(rng), up(rng), aside(rng));
    rays.emplace_back(origin, glm::normalize(target - origin));
  }
  return rays;
}

std::vector<Ray> roomRays(int count, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> x(-2.9f, 2.9f), y(0.1f, 2.9f), z(-2.9f, 5.9f);
  std::normal_distribution<float> dir;
  std::vector<Ray> rays;
  rays.reserve(static_cast<std::size_t>(count));
  for (int i = 0; i < count; ++i) {
    rays.emplace_back(glm::vec3(x(rng), y(rng), z(rng)), glm::normalize(glm::vec3(dir(rng), dir(rng), dir(rng))));
  }
  return rays;
}

}  // namespace glint::bench

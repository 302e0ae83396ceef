#pragma once

#include <optional>

#include <glm/vec3.hpp>

namespace glint {

// Mirror direction of unit d about unit n.
glm::vec3 reflect(const glm::vec3& d, const glm::vec3& n);

// A mirror bounce of unit d off a surface with unit shading normal ns and
// unit geometric normal ng (both facing d's origin): d reflected about ns,
// or about ng where that would leave below the surface (an interpolated
// normal tilted away from the geometry).
glm::vec3 mirrorDirection(const glm::vec3& d, const glm::vec3& ns, const glm::vec3& ng);

// Snell's law for unit d arriving at a surface with unit normal n facing it
// (dot(d, n) < 0) and eta = n1 / n2. Returns the unit refracted direction, or
// nothing at total internal reflection.
std::optional<glm::vec3> refract(const glm::vec3& d, const glm::vec3& n, float eta);

// The share of light a smooth dielectric reflects (Fresnel's equations for
// unpolarised light) for light arriving at cosine cosIn (> 0) to the normal,
// eta = n1 / n2; 1 at total internal reflection.
float fresnelDielectric(float cosIn, float eta);
// Origin for a ray leaving surface point p on the side of unit normal n
// (Wächter and Binder, "A Fast and Robust Method for Avoiding
// Self-Intersection", Ray Tracing Gems chapter 6): p moves a fixed number of
// ulps along n (256 per unit of n), which scales with the coordinates' own
// rounding error; near the origin, where ulps are tiny, by 1/65536 instead.
glm::vec3 offsetRayOrigin(const glm::vec3& p, const glm::vec3& n);

// The same for a computed hit point whose coordinates may each be off by up
// to `error`: p first moves along n past that error (as pbrt-v4's
// OffsetRayOrigin does), then by the ulps above. The ulp offset alone scales
// with each coordinate's own magnitude, which is too little where a small
// coordinate belongs to a large or distant primitive.
glm::vec3 offsetRayOrigin(const glm::vec3& p, float error, const glm::vec3& n);

}  // namespace glint

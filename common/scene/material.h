#pragma once

#include <string>

#include <glm/vec3.hpp>

namespace glint {

// A material's "raytrace" key: under the auto mask rule, true forces the
// material into the mask and false keeps it out.
enum class RaytraceRule { kAuto, kAlways, kNever };

// The thesis's material; defaults are the scene format's.
struct Material {
  std::string name;
  glm::vec3 color{1.0f};  // times the texture: the surface colour C
  int texture = -1;       // index into Scene::textures, or -1
  // Light of the surface's own, added to what it reflects (it lights
  // nothing else): emission times the emission texture, an image.
  glm::vec3 emission{0.0f};
  int emissionTexture = -1;  // index into Scene::textures, or -1
  float ambient = 0.0f;   // r_A
  float diffuse = 1.0f;   // r_D
  float specular = 0.0f;  // r_S
  float shininess = 1.0f;  // h
  float reflectivity = 0.0f;
  // Width of the reflection lobe around the mirror direction, in [0, 1]:
  // GGX's alpha is roughness^2; 0 is a perfect mirror.
  float roughness = 0.0f;
  float transparency = 0.0f;
  float ior = 1.0f;
  RaytraceRule raytrace = RaytraceRule::kAuto;
};

}  // namespace glint

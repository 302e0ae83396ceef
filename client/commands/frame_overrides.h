#pragma once

#include <optional>
#include <string>

#include <glm/vec3.hpp>

#include "common/scene/scene.h"

namespace glint {

// The options that change what a scene's frame and mask are, the same for
// every command that renders (render, view, accuracy), declared once
// (client/cli.cpp, addFrameOptions); unset ones keep the scene file's value.
struct FrameOverrides {
  std::optional<MaskRule> mask;
  std::optional<float> maskThreshold;  // the scene's min_reflectivity
  std::optional<int> shadowMap;        // the scene's mask.shadow_map
  int tileSize = 64;                   // the work unit of a thread or a server request
  std::optional<int> samples;
  std::optional<SamplePattern> pattern;
  std::optional<float> adaptiveThreshold;
  std::optional<float> perceptualThreshold;
  std::optional<int> lightSamples;
  std::optional<FilterType> filter;
  std::optional<std::uint32_t> seed;
  std::optional<int> maxDepth;
  std::optional<Transport> transport;
  std::optional<int> maxBounces;
  std::optional<float> minWeight;
  std::optional<glm::vec3> eye;  // --eye, --look-at, --up: the camera's
  std::optional<glm::vec3> lookAt;
  std::optional<glm::vec3> up;
  std::optional<float> fovY;  // --fov, degrees
  bool fit = false;           // --fit: the camera moved to frame every object
  std::optional<int> width;   // --size
  std::optional<int> height;
  std::optional<Encoding> encoding;  // 8-bit outputs
  std::optional<float> exposure;     // EV
  std::optional<FieldSettings> field;  // --field
};

// The scene with the overrides applied, its frame checked (an error names
// the option). Under path transport, the hybrid frame draws indirect light
// where the scene or --field asks for an irradiance field and the scene's
// emitters are few flat ones (EmitterPatches); elsewhere every pixel is
// traced (the mask rule becomes all), and the note it returns says why
// (empty when there is nothing to say).
[[nodiscard]] std::string applyFrameOverrides(const FrameOverrides& overrides, Scene& scene);

// "note: NOTE" on stderr, when the note is not empty.
void printNote(const std::string& note);

}  // namespace glint

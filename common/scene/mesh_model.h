#pragma once

#include <optional>
#include <string>
#include <vector>

#include "common/scene/camera.h"
#include "common/geometry/geometry.h"
#include "common/scene/light.h"
#include "common/scene/material.h"
#include "common/scene/texture.h"

namespace glint {

// A mesh file as the scene takes it, whatever its format: triangle meshes,
// one per material the file uses. MeshInput::material indexes `materials`
// (the file's, mapped onto Glint's fields); `textures` are the materials'
// images, and Material::texture indexes them.
struct MeshModel {
  std::vector<MeshInput> meshes;
  std::vector<Material> materials;
  std::vector<Texture> textures;
  std::vector<std::string> warnings;  // files the mesh file names that are missing
  std::optional<CameraSpec> camera;   // a glTF file's first perspective camera
  std::vector<Light> lights;          // a glTF file's KHR_lights_punctual lights
};

// Refuses, with an InputError starting with `place`, what the renderer
// cannot take from an imported file, whether an importer read it (glint) or
// it arrived as a blob (glintd), so that both give one verdict: a material's
// colour or emission not finite or negative, a vertex colour not finite, a
// light's colour not finite or negative or its position not finite.
void checkImportedModel(const MeshModel& model, const std::string& place);

}  // namespace glint

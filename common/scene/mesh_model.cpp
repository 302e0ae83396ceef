#include "common/scene/mesh_model.h"

#include <glm/vector_relational.hpp>

#include "common/base/error.h"
#include "common/math/finite.h"

namespace glint {
namespace {

bool finiteAndNotNegative(const glm::vec3& v) {
  return allFinite(v) && !glm::any(glm::lessThan(v, glm::vec3(0.0f)));
}

}  // namespace

void checkImportedModel(const MeshModel& model, const std::string& place) {
  for (const Material& m : model.materials) {
    if (!finiteAndNotNegative(m.color) || !finiteAndNotNegative(m.emission)) {
      throw InputError(place + ": material '" + m.name +
                       "' has a colour or emission that is negative or beyond a float's range (3.4e38)");
    }
  }
  for (std::size_t i = 0; i < model.meshes.size(); ++i) {
    for (const glm::vec3& c : model.meshes[i].colors) {
      if (!allFinite(c))
        throw InputError(place + ": mesh " + std::to_string(i) + " has a vertex colour that is not a number");
    }
  }
  for (std::size_t i = 0; i < model.lights.size(); ++i) {
    const Light& l = model.lights[i];
    if (!finiteAndNotNegative(l.color) || !allFinite(l.position)) {
      throw InputError(place + ": light " + std::to_string(i) +
                       " has a colour that is negative or a colour or position beyond a float's range");
    }
  }
}

}  // namespace glint

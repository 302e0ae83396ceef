#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "common/scene/light.h"

namespace glint {

// The KHR_lights_punctual lights of a glTF 2.0 file's nodes, placed by each
// node and its parents: a light at the node's origin shining down its -Z.
// point -> point, spot -> spot (innerConeAngle, outerConeAngle: the cones'
// half-angles), directional -> directional; color x intensity is the colour,
// and point and spot lights fall off as the inverse square (attenuation
// [0, 0, 1]; a `range` is not applied). A light entry that is not an object
// of a known type, or has a non-finite value, is an InputError starting with
// `place`.
std::vector<Light> gltfLights(std::string_view bytes, const std::string& place);

}  // namespace glint

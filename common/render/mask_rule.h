#pragma once

#include "common/scene/material.h"
#include "common/scene/scene.h"

namespace glint {

// Whether the ray tracer fills the pixels of a material, by the scene's mask
// rule (scene format, "mask"): under auto and perceptual, reflectivity above
// min_reflectivity or transparency above min_transparency, unless the
// material says "raytrace": false; "raytrace": true always. all and none
// ignore the materials.
bool materialMasked(const Material& material, const MaskSettings& mask);

// Whether the ray tracer fills the pixels that show no object: under auto
// and perceptual, where the scene has an environment image (OpenGL clears
// them to the flat background); all traces every pixel, none none.
bool backgroundMasked(const Scene& scene, const MaskSettings& mask);

}  // namespace glint

#include "client/commands/frame_overrides.h"

#include <cstdio>
#include <string>

#include "common/base/error.h"
#include "common/render/effects.h"
#include "common/render/emitter_patches.h"
#include "common/scene/load_limits.h"

namespace glint {

std::string applyFrameOverrides(const FrameOverrides& o, Scene& scene) {
  FrameSettings& f = scene.frame;
  if (o.eye) f.camera.eye = *o.eye;
  if (o.lookAt) f.camera.lookAt = *o.lookAt;
  if (o.up) f.camera.up = *o.up;
  if (o.fovY) f.camera.fovY = *o.fovY;
  if (o.width) f.width = *o.width;
  if (o.height) f.height = *o.height;
  if (o.pattern) f.sampling.pattern = *o.pattern;
  if (o.adaptiveThreshold) f.sampling.adaptiveThreshold = *o.adaptiveThreshold;
  if (o.perceptualThreshold) f.sampling.perceptualThreshold = *o.perceptualThreshold;
  if (o.samples) f.sampling.samples = *o.samples;
  if (o.lightSamples) f.sampling.lightSamples = *o.lightSamples;
  if (o.filter) f.sampling.filter = *o.filter;
  if (o.seed) f.sampling.seed = *o.seed;
  if (o.maxDepth) f.tracing.maxDepth = *o.maxDepth;
  if (o.minWeight) f.tracing.minWeight = *o.minWeight;
  if (o.transport) f.tracing.transport = *o.transport;
  if (o.maxBounces) f.tracing.maxBounces = *o.maxBounces;
  if (o.encoding) f.output.encoding = *o.encoding;
  if (o.exposure) f.output.exposure = *o.exposure;
  // The scene file's frame was checked when it was loaded: a problem now
  // comes from the options.
  const std::string samples = "--samples " + std::to_string(f.sampling.samples);
  try {
    checkFrame(f, LoadLimits{}.maxImagePixels,
               {.size = "--size",
                .camera = "camera.",
                .samples = samples.c_str(),
                .seed = "--seed",
                .maxDepth = "--max-depth",
                .maxBounces = "--max-bounces",
                .minWeight = "--min-weight",
                .adaptiveThreshold = "--adaptive-threshold",
                .perceptualThreshold = "--perceptual-threshold",
                .lightSamples = "--light-samples",
                .exposure = "--exposure"});
  } catch (const InputError& e) {
    throw UsageError(e.what());
  }
  if (o.fit) {
    const Bounds3 bounds = scene.geometry.bounds();
    if (bounds.empty()) throw InputError("--fit: the scene has no object to frame");
    f.camera = fitCamera(f.camera, bounds, static_cast<float>(f.width) / static_cast<float>(f.height));
  }
  if (o.mask) scene.mask.rule = *o.mask;
  if (o.maskThreshold) scene.mask.minReflectivity = *o.maskThreshold;
  if (o.shadowMap) scene.mask.shadowMap = *o.shadowMap;
  if (o.field) f.tracing.field = *o.field;
  if (f.tracing.transport != Transport::kPath || scene.mask.rule == MaskRule::kAll) return {};
  const bool drawable = EmitterPatches::of(scene, EffectPlan::derive(scene, f), 0).has_value();
  if (f.tracing.field && drawable) return {};
  scene.mask.rule = MaskRule::kAll;
  const char* why = !f.tracing.field ? "for the hybrid frame to draw the light between surfaces from an irradiance "
                                       "field, give --field or the scene's tracing.field"
                                     : "the hybrid frame draws the irradiance field's light only for a few flat "
                                       "emitters of plain emission";
  return std::string("path transport: every pixel is traced (") + why + ")";
}

void printNote(const std::string& note) {
  if (!note.empty()) std::fprintf(stderr, "note: %s\n", note.c_str());
}

}  // namespace glint

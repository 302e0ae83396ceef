#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <vector>

#include <glm/vec3.hpp>

#include "common/render/prepared_scene.h"
#include "common/scene/camera.h"
#include "common/render/effects.h"
#include "common/render/filter.h"
#include "common/render/ray_stats.h"
#include "common/render/sampling.h"
#include "common/scene/scene.h"
#include "common/render/tile.h"
#include "common/render/path_tracer.h"
#include "common/render/tracer.h"

namespace glint {

// Everything needed to trace pixels of one frame: the prepared scene, the
// frame's settings, the effect plan, the camera and the filter. Cheap to make
// (the BVH belongs to the prepared scene) and immutable, so any number of
// threads may render tiles of it at once.
class Renderer {
 public:
  Renderer(const PreparedScene& prepared, const FrameSettings& frame);
  // With a given plan (the one above derives it from the scene and frame).
  // With the scene's irradiance field (path transport only): a sample is
  // traced as Whitted's with the field's indirect light (as the hybrid
  // frame's raster shades it), and as a path where the field cannot decide.
  Renderer(const PreparedScene& prepared, const FrameSettings& frame, const EffectPlan& plan,
           const IrradianceField* field = nullptr);
  // Its tracer refers to its own plan: a copy would trace with the original's.
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  // Told, on the tracing thread, as each row of a tile is traced: how many
  // of its pixels were (a frame's progress finer than its tiles).
  using RowTraced = std::function<void(std::size_t pixels)>;

  // The tile interface, called the same way in-process, by the server and by
  // the GL client: traces the pixels of `rect` whose mask bit is set (every
  // pixel for an empty mask) and appends their RGB8 values to `rgb` in scan
  // order, 3 bytes per pixel.
  void renderTile(const TileRect& rect, std::span<const std::uint8_t> mask, std::vector<std::uint8_t>& rgb,
                  RayStats& stats, const RowTraced& rowTraced = {}) const;
  // The same pixels as linear colour (before clamping and rounding).
  void renderTileLinear(const TileRect& rect, std::span<const std::uint8_t> mask, std::vector<glm::vec3>& out,
                        RayStats& stats, const RowTraced& rowTraced = {}) const;

  // Linear colour of pixel (x, y): the filtered average of its samples
  // (regular, jittered and sobol patterns; the adaptive ones need their
  // neighbours: renderTileLinear).
  glm::vec3 pixel(int x, int y, RayStats& stats) const;

  // A pixel's samples so far: their filter-weighted and plain sums.
  struct PixelSamples {
    glm::vec3 sum{0.0f};
    glm::vec3 unweighted{0.0f};
    float weightSum = 0.0f;
    int finite = 0;
  };
  // Traces samples first to end - 1 of pixel (x, y) into p (regular,
  // jittered and sobol patterns). Samples added in passes, in order, sum as pixel()
  // sums them all at once: resolve() then gives pixel()'s value, bit for bit.
  void addSamples(int x, int y, int first, int end, PixelSamples& p, RayStats& stats) const;
  // The pixel's colour from its samples (the background when none is finite).
  glm::vec3 resolve(const PixelSamples& p) const;

  const Scene& scene() const { return prepared_.scene(); }
  const FrameSettings& frame() const { return frame_; }
  const EffectPlan& plan() const { return plan_; }
  const Camera& camera() const { return camera_; }

 private:
  // A camera ray and the filter's weight for its radiance.
  struct CameraSample {
    Ray ray;
    float weight;
    SampleKey key;
  };
  CameraSample cameraSample(int x, int y, const SampleLayout::Pixel& key, int sample) const;
  // The camera's ray through film position `film` (through the lens point
  // the key draws, under depth of field).
  Ray cameraRay(const glm::vec2& film, const SampleKey& key) const;
  // One ray through the pixel's centre into p, with weight 1.
  void addCentreSample(int x, int y, PixelSamples& p, RayStats& stats) const;
  // The radiance of a camera sample, by the frame's transport.
  glm::vec3 radiance(const Ray& ray, const SampleKey& key, RayStats& stats) const {
    if (!path_) return tracer_.radiance(ray, key, stats);
    return withField_ ? fieldRadiance(ray, key, stats) : path_->radiance(ray, key, stats);
  }
  glm::vec3 fieldRadiance(const Ray& ray, const SampleKey& key, RayStats& stats) const;
  void renderAdaptive(const TileRect& rect, std::span<const std::uint8_t> mask, std::vector<glm::vec3>& out,
                      RayStats& stats) const;

  const PreparedScene& prepared_;
  FrameSettings frame_;
  EffectPlan plan_;
  Camera camera_;
  Filter filter_;
  SampleLayout sampleLayout_;
  Tracer tracer_;
  std::optional<PathTracer> path_;  // under path transport, which then makes every sample
  bool withField_;                  // but where the tracer reads the field
};

}  // namespace glint

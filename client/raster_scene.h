#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include <glm/mat4x4.hpp>

#include "client/gl_api.h"
#include "client/multisample_target.h"
#include "client/shadow_maps.h"
#include "common/bounds.h"
#include "common/effects.h"
#include "common/scene.h"

namespace glint::gl {

// What draw() leaves in a pixel's stencil: the pixel is OpenGL's, the
// tracer's because the mask names its material, or the tracer's because the
// shadow maps cannot decide whether a light reaches it (rule auto only).
enum StencilMark : std::uint8_t { kRasterPixel = 0, kMaskedPixel = 1, kShadowEdgePixel = 2 };

// A scene uploaded to OpenGL once: triangle batches and sphere impostors,
// grouped by material, the shader programs, the texture atlas and, drawn on
// the first frame that needs them, the lights' shadow maps. draw() renders
// one frame and marks each pixel's stencil (StencilMark). Masked objects are
// drawn by programs that write depth and stencil but shade nothing (black):
// the tracer's pixels replace theirs. Where an anti-aliased pass follows, the
// other objects' programs in draw() write the marks without the colour.
class RasterScene {
 public:
  RasterScene(const Api& api, const Scene& scene);
  ~RasterScene();
  RasterScene(const RasterScene&) = delete;
  RasterScene& operator=(const RasterScene&) = delete;

  // Whether drawAntialiased() will draw `frame`: it takes more than one
  // sample a pixel and GL offers multisampling (its target made here).
  bool prepareAntialiased(const FrameSettings& frame);
  // Draws the frame and marks each pixel's stencil (StencilMark). With
  // `colour` false the objects OpenGL draws get their depth and marks but no
  // colour (black): the anti-aliased pass draws it. Returns the milliseconds
  // spent drawing shadow maps (0 but on the first frame that needs them, or
  // another map size).
  double draw(const FrameSettings& frame, const MaskSettings& mask, bool colour = true);
  // Draws the frame again multisampled (prepareAntialiased() true), every
  // object shaded (an edge next to a masked object blends in GL's estimate
  // of it, not black), and resolves it into the default framebuffer's
  // colour; the stencil and depth of draw() stay. `marks` holds draw()'s
  // StencilMark of each pixel of the frame, rows from the top (as the hybrid
  // frame reads the stencil back): a marked pixel is not shaded (its samples
  // are discarded and resolve to the background), since the tracer
  // replaces it.
  void drawAntialiased(const FrameSettings& frame, std::span<const std::uint8_t> marks);
  // A line for the user where frames under `mask` fall short of the
  // tracer's shadows: without ARB_shader_stencil_export a fragment cannot
  // mark its pixel for tracing, and pixels whose shadow the maps cannot
  // decide keep the maps' estimate. Empty otherwise.
  std::string shadowEdgeNote(const MaskSettings& mask) const;

 private:
  struct Batch {
    unsigned vao = 0;
    unsigned vbo = 0;
    int vertices = 0;
    std::uint32_t material = 0;
    bool spheres = false;
  };
  void newBatch(std::uint32_t material, bool spheres, const void* vertices, std::size_t count,
                std::size_t vertexBytes);
  void uploadMeshes();
  void uploadSpheres();
  void uploadTextures();
  // The frame's view and projection, and its far plane: depth is written as
  // the distance from the eye / far (linear, exact per fragment), so that
  // depth precision does not fall with distance as the projection's does.
  struct Projection {
    glm::mat4 viewProjection;
    float far;
  };
  void setUniforms(unsigned program, const FrameSettings& frame, const Projection& projection, bool antialiased);
  void uploadMarks(const FrameSettings& frame, std::span<const std::uint8_t> marks);
  void setViewUniforms(unsigned program, const glm::mat4& viewProjection, const glm::vec3& eye, float far);
  // The shadow maps `mask` calls for, drawn if they are not yet; false when
  // it calls for none.
  bool prepareShadows(const MaskSettings& mask);
  void drawDepth(const glm::mat4& viewProjection, const glm::vec3& eye, float far);
  // The viewport, the background, `clear` cleared, the depth test on.
  void beginPass(const FrameSettings& frame, GLbitfield clear);
  // The passes over the batches: draw()'s with the colour or with the marks
  // alone, and drawAntialiased()'s.
  enum class Pass { kColourAndMarks, kMarks, kAntialiased };
  // Every batch; masked materials with the programs that shade nothing,
  // except in the anti-aliased pass, which shades every object; in kMarks,
  // the others with the programs that only mark.
  void drawBatches(const FrameSettings& frame, const MaskSettings& mask, Pass pass);
  Projection projection(const FrameSettings& frame) const;

  const Api& gl_;
  const Scene& scene_;
  const EffectPlan plan_;
  bool stencilExport_ = false;
  bool shadows_ = false;           // the current frame reads the shadow maps
  int undecidedStencil_ = 0;       // the current frame's StencilMark for undecided shadows
  // What a program's fragments write besides depth: the colour and the
  // shadow marks; the marks alone; nothing (masked objects).
  enum Shading { kColour, kMarksOnly, kTraced, kShadings };
  unsigned programs_[2][kShadings] = {};  // [spheres][Shading]
  unsigned atlas_ = 0;
  unsigned stencilMarks_ = 0;  // the anti-aliased pass's copy of draw()'s marks
  std::vector<float> textureRows_;  // atlas row of each texture
  std::vector<Batch> batches_;
  Bounds3 bounds_;  // every primitive's, for the far plane
  MultisampleTarget multisample_;
  ShadowMaps shadowMaps_;
};

}  // namespace glint::gl

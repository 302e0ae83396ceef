#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include <glm/mat4x4.hpp>

#include "client/raster/field_light.h"
#include "client/raster/gl_api.h"
#include "client/raster/light_proof.h"
#include "client/raster/penumbra_proof.h"
#include "client/raster/raster_shaders.h"
#include "client/raster/raster_target.h"
#include "client/raster/shadow_rects.h"
#include "client/raster/shadow_maps.h"
#include "common/geometry/bounds.h"
#include "common/render/effects.h"
#include "common/scene/camera.h"
#include "common/scene/scene.h"

namespace glint::gl {

// A scene uploaded to OpenGL once: triangle batches and sphere impostors,
// grouped by material, one float texture per image texture and, drawn on
// the first frame that needs them, the lights' shadow maps. draw() renders
// one frame at one sample a pixel into its RasterTarget: the colour, each
// pixel's surface (object and PixelMark) and depth. Masked objects are
// drawn by programs that write depth and surface but shade nothing: the
// tracer's pixels replace theirs. Programs are made on first use, one per
// ShaderVariant.
class RasterScene {
 public:
  RasterScene(const Api& api, const Scene& scene);
  ~RasterScene();
  RasterScene(const RasterScene&) = delete;
  RasterScene& operator=(const RasterScene&) = delete;

  // Path transport's light from an irradiance field in place of ambient (the
  // tracer's Tracer::fieldLight), for every frame drawn after (a later call
  // replaces the field); the field must outlive the scene. The emitters' direct light is drawn unshadowed
  // and their penumbra proved (penumbra()). Throws InputError when the
  // scene's emitters are not few flat ones (EmitterPatches).
  void useField(const IrradianceField& field);
  // Draws the frame into target() and marks each pixel (PixelMark). Returns
  // the milliseconds spent drawing shadow maps (0 but on the first frame
  // that needs them, or another map size).
  double draw(const FrameSettings& frame, const MaskSettings& mask);
  const RasterTarget& target() const { return target_; }

  // Where the area and sphere lights are seen whole (their unshadowed light, which the
  // raster draws, is the tracer's).
  const PenumbraProof& penumbra() const { return penumbra_; }
  // Whether the object a surface value names (object << kPixelMarkBits) is
  // lit by the lights: its material has a diffuse or specular term.
  bool objectLit(std::uint32_t object) const;
  // The near plane of the frame's depth (depth = near / distance along the
  // view axis).
  float nearPlane(const FrameSettings& frame) const { return projection(frame).far * kNearShare; }
  // The points pixels' centres show at the depths the target holds for them,
  // for one frame (made once a frame, asked once a pixel).
  struct PixelPoints {
    Camera camera;
    glm::vec3 forward;
    float near;
    glm::vec3 at(int x, int y, float depth) const;
  };
  PixelPoints pixelPoints(const FrameSettings& frame) const;

 private:
  struct Batch {
    unsigned vao = 0;
    unsigned vbo = 0;
    int vertices = 0;
    std::uint32_t material = 0;
    bool spheres = false;
    std::vector<Bounds3> boxes;              // the spheres' impostor boxes, 36 vertices each
    std::vector<std::uint32_t> prims;        // its primitives (Geometry's ids), ascending: 3 or 36 vertices each
    std::vector<ShadowSpot> spots;           // where a light may be blocked on its primitives (LightProof)
    unsigned elements = 0;                   // element buffer of its draws in rectangles, made on first use
    unsigned colors = 0;                     // its vertices' colours (a mesh's, when the scene has any)
  };
  void newBatch(std::uint32_t material, bool spheres, const void* vertices, std::size_t count,
                std::size_t vertexBytes);
  void uploadMeshes();
  void uploadColors(Batch& batch, const std::vector<glm::vec3>& colors);
  void uploadSpheres();
  void uploadTextures();
  // Hands each spot to the batch that draws its primitive.
  void assignSpots(const LightProof& proof);
  // The frame's view and projection, and its far plane. The frame's depth is
  // reversed and infinite (near / the distance along the view axis, 1 at the
  // near plane, 0 at infinity, in a float: the same relative precision at
  // every distance); the near plane clips nothing (depth clamping). The
  // shadow maps use the far plane for their own, linear depth.
  static constexpr float kNearShare = 1e-6f;  // the near plane's distance, of the far plane's
  struct Projection {
    glm::mat4 viewProjection;
    glm::vec3 eye;
    float far;
    glm::vec3 depthAxis{0.0f};  // a directional light's map: depth along it (ShadowMaps::DepthPass)
  };
  Projection projection(const FrameSettings& frame) const;
  unsigned program(const ShaderVariant& variant);
  // The shader kind that reads a material's texture (an index, or -1).
  TextureKind textureKind(int texture) const;
  ShaderVariant variantOf(const Batch& batch, const FrameSettings& frame, const MaskSettings& mask) const;
  void setFrameUniforms(unsigned program, const FrameSettings& frame, const Projection& projection,
                        const MaskSettings& mask);
  void setMaterialUniforms(unsigned program, const Material& material);
  // The point lights', and the count and texture unit of the area lights'
  // points and the sphere lights' centres (uploadAreaPoints).
  void setLightUniforms(unsigned program);
  // The frame's area lights' points and sphere lights' centres into their
  // texture (once a frame, before the draws read them).
  void uploadAreaPoints(const FrameSettings& frame);
  // A texture's uv transform (identity for none) into a mat3x2 uniform.
  void setUvTransform(int location, const std::optional<UvTransform>& transform);
  void setViewUniforms(unsigned program, const Projection& projection);
  // The shadow maps `mask` calls for, drawn if they are not yet; false when
  // it calls for none.
  bool prepareShadows(const MaskSettings& mask);
  void drawDepth(const Projection& projection);
  // A sphere batch's impostor boxes are drawn by their near faces, unless
  // `eye` is inside one of them.
  // With `elements`, only that range of its element buffer.
  struct Elements {
    std::size_t first = 0;
    std::size_t count = 0;
  };
  void drawBatch(const Batch& batch, const glm::vec3& eye, const Elements* elements = nullptr);
  // What a frame's draws share; `framed` holds the programs whose frame
  // uniforms are set.
  struct FrameDraw {
    const FrameSettings& frame;
    const MaskSettings& mask;
    Projection projection;
    std::set<int> framed;
  };
  // Draws the batch with the program of `variant`. A batch that reads the
  // shadow maps reads them only on the primitives with a spot that counts
  // and only in the rectangles such spots may show in (shadowLayout); it is
  // drawn without them elsewhere.
  void drawShaded(Batch& batch, const ShaderVariant& variant, FrameDraw& draw);
  // The vertices of the batch's primitives that `layout` does not name
  // (first), then for each rectangle those of the named ones whose window
  // box overlaps it, written to the batch's element buffer.
  std::vector<Elements> binPrimitives(Batch& batch, const ShadowLayout& layout, const FrameDraw& draw);
  void drawProgram(const Batch& batch, const ShaderVariant& variant, FrameDraw& draw,
                   const Elements* elements = nullptr);

  const Api& gl_;
  const Scene& scene_;
  const EffectPlan plan_;
  bool shadows_ = false;  // the current frame reads the shadow maps
  std::map<int, unsigned> programs_;  // by ShaderVariant::key()
  std::vector<unsigned> images_;      // per texture: its GL texture (image textures), else 0
  struct AreaPoints {
    unsigned texture = 0;  // uAreaPoints, made on first use
    int count = 0;         // the current frame's points
  } areaPoints_;
  std::vector<Batch> batches_;
  Bounds3 bounds_;  // every primitive's, for the far plane
  RasterTarget target_;
  ShadowMaps shadowMaps_;
  // The scene's point, spot and directional lights, in order: the shader's
  // lights and, for point and spot lights, their maps.
  std::vector<Light> punctualLights_;
  std::vector<bool> punctualCasts_;  // per light: it casts shadows (the plan's lights)
  bool spotLights_ = false;          // the scene has spot lights (ShaderVariant::spotLights)
  bool directionalLights_ = false;   // and directional ones
  PenumbraProof penumbra_;
  std::unique_ptr<FieldLight> field_;  // none: ambient
};

}  // namespace glint::gl

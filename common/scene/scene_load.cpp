#include "common/scene/scene_load.h"

#include <cmath>
#include <map>
#include <sstream>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>
#include <glm/vector_relational.hpp>

#include "common/base/error.h"
#include "common/base/json_reader.h"
#include "common/math/circular.h"
#include "common/math/power.h"
#include "common/scene/camera.h"
#include "common/scene/frame_limits.h"
#include "common/image/image_decode.h"
#include "common/scene/mesh_import.h"
#include "common/scene/model_scene.h"
#include "common/scene/smooth_normals.h"
#include "common/scene/transform.h"

namespace glint {
namespace {

// The scene format's kinds of object (docs/scene-format.md).
enum class ObjectKind { kSphere, kTriangle, kQuad, kMesh };

}  // namespace

template <>
struct EnumWords<ObjectKind> {
  static constexpr std::array<std::pair<ObjectKind, std::string_view>, 4> kWords{{{ObjectKind::kSphere, "sphere"},
                                                                                  {ObjectKind::kTriangle, "triangle"},
                                                                                  {ObjectKind::kQuad, "quad"},
                                                                                  {ObjectKind::kMesh, "mesh"}}};
};

namespace {

constexpr float kMax = std::numeric_limits<float>::max();

// Reads one of an enum's words (common/base/enum_words.h).
template <typename Enum>
Enum choice(const JsonReader& r) {
  const std::string s = r.string();
  if (const std::optional<Enum> value = enumFromWord<Enum>(s)) return *value;
  r.fail("'" + s + "' is not one of: " + enumWordsJoined<Enum>());
}

class SceneLoader {
 public:
  SceneLoader(FileSource& files, SceneBudget& budget)
      : files_(files), budget_(budget), limits_(budget.limits()), images_(files, budget) {}

  Scene load(const nlohmann::json& doc) {
    const JsonReader root(doc, "");
    root.allowKeys({"glint", "image", "camera", "sampling", "tracing", "mask", "background", "environment",
                    "textures", "materials", "lights", "objects"});
    readVersion(root["glint"]);
    readImage(root["image"]);
    readCamera(root["camera"]);
    if (auto s = root.find("sampling")) readSampling(*s);
    if (auto t = root.find("tracing")) readTracing(*t);
    checkFrame();
    if (auto m = root.find("mask")) readMask(*m);
    scene_.background = root.vec3("background", glm::vec3(0.0f));
    if (auto e = root.find("environment")) readEnvironment(*e);
    if (auto t = root.find("textures")) readTextures(*t);
    if (auto m = root.find("materials")) readMaterials(*m);
    if (auto l = root.find("lights")) readLights(*l);
    const JsonReader objects = root["objects"];
    for (std::size_t i = 0; i < objects.arraySize(); ++i) readObject(objects.at(i));
    if (auto fit = root["camera"].find("fit"); fit && fit->boolean()) fitToScene(*fit);
    return std::move(scene_);
  }

 private:
  void readImage(const JsonReader& r) {
    r.allowKeys({"width", "height", "encoding", "exposure"});
    scene_.frame.width = r["width"].integer(1, FrameLimits::kMaxEdge);
    scene_.frame.height = r["height"].integer(1, FrameLimits::kMaxEdge);
    if (auto e = r.find("encoding")) scene_.frame.output.encoding = choice<Encoding>(*e);
    scene_.frame.output.exposure = r.number("exposure", 0.0f, -FrameLimits::kMaxExposure, FrameLimits::kMaxExposure);
  }

  void readCamera(const JsonReader& r) {
    r.allowKeys({"eye", "look_at", "up", "fov_y", "file", "fit", "aperture", "focus_distance"});
    CameraSpec& c = scene_.frame.camera;
    if (auto f = r.find("file")) {
      readCameraFile(r, *f);
    } else {
      c.eye = r["eye"].vec3();
      c.lookAt = r["look_at"].vec3();
      c.up = r.vec3("up", {0.0f, 1.0f, 0.0f});
      c.fovY = r.number("fov_y", 45.0f, 0.0f, kMaxFovY, true);
    }
    readLens(r, c);
  }

  // The format's version: this build reads version 1, the only one.
  static void readVersion(const JsonReader& r) {
    constexpr int kVersion = 1;
    if (!r.isNumber() || r.number() != static_cast<float>(kVersion)) {
      r.fail("this build of Glint reads scene format version " + std::to_string(kVersion) + " (\"glint\": " +
             std::to_string(kVersion) + ")");
    }
  }

  // The thin lens: focused at look_at unless told (the camera check names an
  // eye at look_at).
  static void readLens(const JsonReader& r, CameraSpec& c) {
    c.aperture = r.number("aperture", 0.0f, 0.0f, kMax);
    const float toTarget = glm::length(c.lookAt - c.eye);
    c.focusDistance = r.number("focus_distance", toTarget > 0.0f ? toTarget : 1.0f, 0.0f, kMax, true);
  }

  // An equirectangular HDR or EXR image, its values times 2^exposure,
  // turned about +y by rotation degrees.
  void readEnvironment(const JsonReader& r) {
    r.allowKeys({"file", "exposure", "rotation"});
    const float exposure = r.number("exposure", 0.0f, -FrameLimits::kMaxExposure, FrameLimits::kMaxExposure);
    const float rotation = r.number("rotation", 0.0f, -360.0f, 360.0f);
    const JsonReader file = r["file"];
    const std::string path = normalisePath(file.string());
    FloatPixels pixels = decodeLinearImage(files_.read(path, file.path()), file.path(), budget_);
    scene_.environment = std::make_shared<const Environment>(pixels.width, pixels.height, std::move(pixels.rgb),
                                                             twoToThe(exposure), glm::radians(rotation));
  }

  // "fit": true: the camera moved along its direction to frame every object.
  void fitToScene(const JsonReader& fit) {
    const Bounds3 bounds = scene_.geometry.bounds();
    if (bounds.empty()) {
      const std::size_t dropped = scene_.geometry.droppedTriangles();
      fit.fail("the scene has no object to frame" +
               (dropped ? " (" + std::to_string(dropped) + " triangles were dropped: " + Geometry::kDroppedWhy + ")"
                        : std::string()));
    }
    FrameSettings& f = scene_.frame;
    f.camera = fitCamera(f.camera, bounds, static_cast<float>(f.width) / static_cast<float>(f.height));
  }

  // The first perspective camera of a glTF file (imported as a mesh file is).
  void readCameraFile(const JsonReader& r, const JsonReader& f) {
    for (const char* key : {"eye", "look_at", "up", "fov_y"}) {
      if (r.has(key)) r[key].fail("the camera comes from its file; give either file or eye and look_at");
    }
    const std::string path = normalisePath(f.string());
    const MeshModel model = importMeshFile(files_, path, f.path(), budget_, false);
    if (!model.camera) f.fail("'" + path + "' has no perspective camera (glTF files carry cameras)");
    scene_.frame.camera = *model.camera;
  }

  void readSampling(const JsonReader& r) {
    r.allowKeys({"pattern", "samples", "filter", "seed", "adaptive_threshold", "perceptual_threshold",
                 "light_samples"});
    SamplingSettings& s = scene_.frame.sampling;
    if (auto p = r.find("pattern")) {
      s.pattern = choice<SamplePattern>(*p);
    }
    if (auto n = r.find("samples")) s.samples = n->integer(1, FrameLimits::kMaxSamples);
    if (auto f = r.find("filter")) {
      s.filter = choice<FilterType>(*f);
    }
    if (auto seed = r.find("seed")) s.seed = static_cast<std::uint32_t>(seed->integer(0, FrameLimits::kMaxSeed));
    if (auto t = r.find("adaptive_threshold")) s.adaptiveThreshold = t->number(0.0f, 1.0f, true);
    if (auto t = r.find("perceptual_threshold")) s.perceptualThreshold = t->number(0.0f, 1.0f, true);
    if (auto n = r.find("light_samples")) s.lightSamples = n->integer(0, FrameLimits::kMaxLightSamples);
  }

  // The frame's settings together (the size against the pixel limit, the
  // camera, the sample count for its pattern), as the decoder and the command
  // line check them.
  void checkFrame() const {
    glint::checkFrame(scene_.frame, limits_.maxImagePixels,
                      {.size = "image",
                       .camera = "camera.",
                       .samples = "sampling.samples",
                       .seed = "sampling.seed",
                       .maxDepth = "tracing.max_depth",
                       .maxBounces = "tracing.max_bounces",
                       .minWeight = "tracing.min_weight",
                       .adaptiveThreshold = "sampling.adaptive_threshold",
                       .perceptualThreshold = "sampling.perceptual_threshold",
                       .lightSamples = "sampling.light_samples",
                       .exposure = "image.exposure"});
  }

  void readTracing(const JsonReader& r) {
    r.allowKeys({"max_depth", "min_weight", "transport", "max_bounces", "field"});
    TracingSettings& t = scene_.frame.tracing;
    if (auto d = r.find("max_depth")) t.maxDepth = d->integer(1, FrameLimits::kMaxDepth);
    t.minWeight = r.number("min_weight", 0.01f, 0.0f, 1.0f);
    if (auto m = r.find("transport")) t.transport = choice<Transport>(*m);
    if (auto b = r.find("max_bounces")) t.maxBounces = b->integer(0, FrameLimits::kMaxBounces);
    if (auto f = r.find("field")) readField(*f);
  }

  void readField(const JsonReader& r) {
    r.allowKeys({"probes", "rays"});
    FieldSettings& f = scene_.frame.tracing.field.emplace();
    if (auto p = r.find("probes")) f.probes = p->integer(FieldSettings::kMinProbes, FieldSettings::kMaxProbes);
    if (auto n = r.find("rays")) {
      f.rays = n->integer(FieldSettings::kMinRays, FieldSettings::kMaxRays);
      if (const auto problem = FieldSettings::raysProblem(f.rays)) n->fail(*problem);
    }
  }

  void readMask(const JsonReader& r) {
    r.allowKeys({"rule", "min_reflectivity", "min_transparency", "shadow_map"});
    if (auto rule = r.find("rule")) {
      scene_.mask.rule = choice<MaskRule>(*rule);
    }
    scene_.mask.minReflectivity = r.number("min_reflectivity", 0.2f, 0.0f, 1.0f);
    scene_.mask.minTransparency = r.number("min_transparency", 0.0f, 0.0f, 1.0f);
    if (auto size = r.find("shadow_map")) scene_.mask.shadowMap = size->integer(0, MaskSettings::kMaxShadowMap);
  }

  void readTextures(const JsonReader& r) {
    r.requireObject();
    for (const auto& [name, value] : r.raw().items()) {
      const JsonReader t(value, r.path() + "." + name);
      Texture tex;
      const JsonReader type = t["type"];
      tex.type = choice<TextureType>(type);
      switch (tex.type) {
        case TextureType::kSolid:
          t.allowKeys({"type", "color"});
          tex.colors[0] = t["color"].vec3();
          break;
        case TextureType::kChecker: {
          t.allowKeys({"type", "colors", "scale"});
          const JsonReader colors = t["colors"];
          if (colors.arraySize() != 2) colors.fail("must be an array of 2 colours");
          tex.colors[0] = colors.at(0).vec3();
          tex.colors[1] = colors.at(1).vec3();
          tex.scale = t.number("scale", 1.0f, 0.0f, kMax, true);
          break;
        }
        case TextureType::kImage: {
          t.allowKeys({"type", "file", "filter", "wrap"});
          tex.image = image(t["file"]);
          if (auto f = t.find("filter")) {
            tex.filter = choice<ImageFilter>(*f);
          }
          if (auto w = t.find("wrap")) tex.wrap = wrapModes(*w);
          break;
        }
      }
      textureIndex_[name] = static_cast<int>(scene_.textures.size());
      scene_.textures.push_back(std::move(tex));
    }
  }

  // "wrap": one mode for u and v, or [u's, v's].
  static std::array<TextureWrap, 2> wrapModes(const JsonReader& w) {
    if (!w.isArray()) return {choice<TextureWrap>(w), choice<TextureWrap>(w)};
    if (w.arraySize() != 2) w.fail("must be a wrap mode or an array of two (along u, along v)");
    return {choice<TextureWrap>(w.at(0)), choice<TextureWrap>(w.at(1))};
  }

  // The image a texture's "file" names, decoded (and charged) once however
  // many textures, or mesh files' materials, name it.
  std::shared_ptr<const Image> image(const JsonReader& file) {
    return images_.get(normalisePath(file.string()), file.path());
  }

  std::uint32_t textureNamed(const JsonReader& t) const {
    const std::string texName = t.string();
    const auto it = textureIndex_.find(texName);
    if (it == textureIndex_.end()) t.fail("no texture named '" + texName + "' in textures");
    return it->second;
  }

  // A solid texture is only a colour: folded into `colour`, no lookups at
  // render time (-1); any other is its index.
  int foldSolid(std::uint32_t texture, glm::vec3& colour) const {
    const Texture& tex = scene_.textures[texture];
    if (tex.type != TextureType::kSolid) return static_cast<int>(texture);
    colour *= tex.colors[0];
    return -1;
  }

  // A colour (a material's, its emission, a light's): three numbers, none
  // negative (no light is taken away).
  static glm::vec3 colour(const JsonReader& r, const char* key, const glm::vec3& fallback) {
    const glm::vec3 c = r.vec3(key, fallback);
    if (glm::any(glm::lessThan(c, glm::vec3(0.0f)))) r.find(key)->fail("must not be negative");
    return c;
  }

  // emission times emission_texture (either alone is the emission; default
  // none): an image, or a solid colour folded in.
  void readEmission(const JsonReader& m, Material& mat) const {
    const auto t = m.find("emission_texture");
    mat.emission = colour(m, "emission", glm::vec3(t ? 1.0f : 0.0f));
    if (!t) return;
    const std::uint32_t texture = textureNamed(*t);
    if (scene_.textures[texture].type == TextureType::kChecker) {
      t->fail("must name an image or solid texture, not a checker");
    }
    mat.emissionTexture = foldSolid(texture, mat.emission);
  }

  void readMaterials(const JsonReader& r) {
    r.requireObject();
    for (const auto& [name, value] : r.raw().items()) {
      const JsonReader m(value, r.path() + "." + name);
      m.allowKeys({"color", "texture", "emission", "emission_texture", "ambient", "diffuse", "specular",
                   "shininess", "reflectivity", "roughness", "transparency", "ior", "raytrace"});
      Material mat;
      mat.name = name;
      mat.color = colour(m, "color", glm::vec3(1.0f));
      if (auto t = m.find("texture")) mat.texture = foldSolid(textureNamed(*t), mat.color);
      readEmission(m, mat);
      mat.ambient = m.number("ambient", 0.0f, 0.0f);
      mat.diffuse = m.number("diffuse", 1.0f, 0.0f);
      mat.specular = m.number("specular", 0.0f, 0.0f);
      mat.shininess = m.number("shininess", 1.0f, 0.0f);
      mat.reflectivity = m.number("reflectivity", 0.0f, 0.0f, 1.0f);
      mat.roughness = m.number("roughness", 0.0f, 0.0f, 1.0f);
      mat.transparency = m.number("transparency", 0.0f, 0.0f, 1.0f);
      mat.ior = m.number("ior", 1.0f, 0.0f, kMax, true);
      if (auto rt = m.find("raytrace")) {
        if (rt->isBoolean()) {
          mat.raytrace = rt->boolean() ? RaytraceRule::kAlways : RaytraceRule::kNever;
        } else if (!rt->isString() || rt->string() != "auto") {
          rt->fail("must be true, false or \"auto\"");
        }
      }
      materialIndex_[name] = static_cast<std::uint32_t>(scene_.materials.size());
      scene_.materials.push_back(std::move(mat));
    }
  }

  void readLights(const JsonReader& r) {
    for (std::size_t i = 0; i < r.arraySize(); ++i) {
      const JsonReader l = r.at(i);
      Light light;
      light.type = choice<LightType>(l["type"]);
      switch (light.type) {
        case LightType::kPoint:
          l.allowKeys({"type", "position", "color", "attenuation"});
          break;
        case LightType::kArea:
          l.allowKeys({"type", "position", "u", "v", "color", "attenuation", "samples"});
          readArea(l, light);
          break;
        case LightType::kSpot:
          l.allowKeys({"type", "position", "direction", "inner_angle", "outer_angle", "color", "attenuation"});
          readSpot(l, light);
          break;
        case LightType::kDirectional:
          l.allowKeys({"type", "direction", "color"});
          light.direction = unitDirection(l["direction"]);
          break;
        case LightType::kSphere:
          l.allowKeys({"type", "position", "radius", "color", "attenuation", "samples"});
          light.radius = l["radius"].number(0.0f, kMax, true);
          readSamples(l, light);
          break;
      }
      if (light.type != LightType::kDirectional) light.position = l["position"].vec3();
      light.color = colour(l, "color", glm::vec3(1.0f));
      if (auto a = l.find("attenuation")) {
        light.attenuation = a->vec3();
        for (int k = 0; k < 3; ++k) {
          if (light.attenuation[k] < 0.0f) a->at(static_cast<std::size_t>(k)).fail("must be >= 0");
        }
        if (light.attenuation == glm::vec3(0.0f)) a->fail("at least one of c, l, q must be positive");
      }
      scene_.lights.push_back(light);
    }
  }

  // An area light's edges (a parallelogram of some area) and sample count.
  static void readArea(const JsonReader& l, Light& light) {
    light.u = l["u"].vec3();
    light.v = l["v"].vec3();
    // The squared area in double says whether the edges are parallel; in
    // float, the renderer's type, whether it can be computed at all.
    const glm::dvec3 exact = glm::cross(glm::dvec3(light.u), glm::dvec3(light.v));
    const double area = std::sqrt(glm::dot(exact, exact));
    if (!(area > 0.0)) l["v"].fail("must not be parallel to u (the light needs an area)");
    const glm::vec3 normal = glm::cross(light.u, light.v);
    const float area2 = glm::dot(normal, normal);
    if (!(area2 > 0.0f) || !std::isfinite(area2)) {
      std::ostringstream why;
      why << "with u spans an area of " << area << ", " << (area > 1.0 ? "above" : "below")
          << " what a float holds squared (1e-19 to 1e19): scale the light and the scene";
      l["v"].fail(why.str());
    }
    readSamples(l, light);
  }

  // A soft light's shadow rays per query.
  static void readSamples(const JsonReader& l, Light& light) {
    if (auto n = l.find("samples")) light.samples = n->integer(1, FrameLimits::kMaxLightSamples);
  }

  // A spot light's axis and cones (half-angles in degrees, glTF's defaults).
  static void readSpot(const JsonReader& l, Light& light) {
    light.direction = unitDirection(l["direction"]);
    const float inner = l.number("inner_angle", 0.0f, 0.0f, 90.0f);
    const float outer = l.number("outer_angle", 45.0f, 0.0f, 90.0f, true);
    if (inner > outer) l["inner_angle"].fail("must not exceed outer_angle");
    light.cosInner = sineCosine(glm::radians(inner)).cos;
    light.cosOuter = sineCosine(glm::radians(outer)).cos;
  }

  static glm::vec3 unitDirection(const JsonReader& d) {
    const glm::vec3 v = d.vec3();
    const float length = glm::length(v);
    if (!(length > 0.0f) || !std::isfinite(length)) d.fail("must be a direction, not zero");
    return v / length;
  }

  std::uint32_t material(const JsonReader& o) {
    const JsonReader m = o["material"];
    const std::string name = m.string();
    const auto it = materialIndex_.find(name);
    if (it == materialIndex_.end()) m.fail("no material named '" + name + "' in materials");
    return it->second;
  }

  Transform transform(const JsonReader& o) {
    Transform t;
    const std::optional<JsonReader> r = o.find("transform");
    if (!r) return t;
    r->allowKeys({"scale", "rotate", "translate"});
    if (auto s = r->find("scale")) {
      t.scale = s->isNumber() ? glm::vec3(s->number()) : s->vec3();
      if (t.scale.x == 0.0f || t.scale.y == 0.0f || t.scale.z == 0.0f) s->fail("must not be zero");
    }
    if (auto rot = r->find("rotate")) {
      if (!rot->isArray() || rot->arraySize() != 4) rot->fail("must be [axis x, y, z, angle in degrees]");
      t.axis = {rot->at(0).number(), rot->at(1).number(), rot->at(2).number()};
      t.angleDegrees = rot->at(3).number();
      if (glm::dot(t.axis, t.axis) == 0.0f) rot->fail("the rotation axis must not be the zero vector");
    }
    t.translate = r->vec3("translate", glm::vec3(0.0f));
    return t;
  }

  void readObject(const JsonReader& o) {
    o.requireObject();
    switch (choice<ObjectKind>(o["type"])) {
      case ObjectKind::kSphere:
        return readSphere(o);
      case ObjectKind::kTriangle:
        return readTriangle(o);
      case ObjectKind::kQuad:
        return readQuad(o);
      case ObjectKind::kMesh:
        return readMeshWarned(o);
    }
  }

  void readSphere(const JsonReader& o) {
    o.allowKeys({"type", "center", "radius", "material", "transform"});
    const Transform t = transform(o);
    if (!t.uniformScale()) {
      o["transform"]["scale"].fail("a sphere takes only a uniform scale (one number)");
    }
    Sphere s;
    s.centre = glm::vec3(t.matrix() * glm::vec4(o["center"].vec3(), 1.0f));
    s.radius = o["radius"].number(0.0f, kMax, true) * std::abs(t.scale.x);
    s.material = material(o);
    if (!std::isfinite(s.radius) || !std::isfinite(s.centre.x + s.centre.y + s.centre.z)) {
      o.fail("the transform takes the sphere out of the float range");
    }
    budget_.chargeSphere(o.path());
    scene_.geometry.addSphere(s);
  }

  void readTriangle(const JsonReader& o) {
    o.allowKeys({"type", "vertices", "normals", "uvs", "material", "transform"});
    MeshInput mesh;
    mesh.positions = vectors3(o["vertices"], 3);
    if (auto n = o.find("normals")) mesh.normals = vectors3(*n, 3);
    mesh.uvs = o.has("uvs") ? vectors2(o["uvs"], 3)
                            : std::vector<glm::vec2>{{0.0f, 0.0f}, {1.0f, 0.0f}, {0.0f, 1.0f}};
    mesh.indices = {0, 1, 2};
    mesh.material = material(o);
    addMesh(o, std::move(mesh));
  }

  void readQuad(const JsonReader& o) {
    o.allowKeys({"type", "corners", "uvs", "material", "transform"});
    MeshInput mesh;
    const JsonReader corners = o["corners"];
    mesh.positions = vectors3(corners, 4);
    const auto& p = mesh.positions;
    const glm::vec3 n = glm::cross(p[1] - p[0], p[2] - p[0]);
    float size = 0.0f;
    for (const glm::vec3& c : p) size = std::max(size, glm::length(c - p[0]));
    if (!(glm::length(n) > 0.0f)) corners.fail("the first three corners are collinear");
    if (std::abs(glm::dot(glm::normalize(n), p[3] - p[0])) > 1e-4f * size) {
      corners.fail("the four corners are not coplanar");
    }
    mesh.uvs = o.has("uvs") ? vectors2(o["uvs"], 4)
                            : std::vector<glm::vec2>{{0.0f, 0.0f}, {1.0f, 0.0f}, {1.0f, 1.0f}, {0.0f, 1.0f}};
    mesh.indices = {0, 1, 2, 0, 2, 3};
    mesh.material = material(o);
    addMesh(o, std::move(mesh));
  }

  // A mesh, and a warning if it leaves nothing to see: every triangle
  // dropped (BoxWithInfinites.glb's), which would otherwise be an empty frame
  // without a word.
  void readMeshWarned(const JsonReader& o) {
    const Geometry& g = scene_.geometry;
    const std::size_t kept = g.triangles().size(), dropped = g.droppedTriangles();
    readMesh(o);
    const std::size_t lost = g.droppedTriangles() - dropped;
    if (lost == 0 || g.triangles().size() > kept) return;
    const std::string file = o.has("file") ? " ('" + o["file"].string() + "')" : "";
    warn(o.path() + file + ": all " + std::to_string(lost) + " of its triangles were dropped (" +
         Geometry::kDroppedWhy + "): nothing of this mesh can be seen");
  }

  void readMesh(const JsonReader& o) {
    o.allowKeys({"type", "file", "positions", "indices", "normals", "uvs", "material", "materials", "raytrace",
                 "smooth", "transform", "lights"});
    if (o.has("file") == o.has("positions")) o.fail("a mesh needs either file or positions (not both)");
    if (o.has("material") && o.has("materials")) {
      o["materials"].fail("renames the file's materials one by one; \"material\" already gives them all one");
    }
    if (auto f = o.find("file")) return readMeshFile(o, *f);
    MeshInput mesh;
    const JsonReader positions = o["positions"];
    const std::size_t values = positions.arraySize();
    if (values % 3 != 0) positions.fail("must hold x, y, z triples (the count is not a multiple of 3)");
    const std::size_t vertices = values / 3;
    checkVertexBudget(positions, vertices);
    mesh.positions.reserve(vertices);
    for (std::size_t i = 0; i < vertices; ++i) {
      mesh.positions.emplace_back(positions.at(3 * i).number(), positions.at(3 * i + 1).number(),
                                  positions.at(3 * i + 2).number());
    }
    const JsonReader indices = o["indices"];
    if (indices.arraySize() % 3 != 0) indices.fail("must hold 3 indices per triangle");
    checkTriangleBudget(indices, indices.arraySize() / 3);
    mesh.indices.reserve(indices.arraySize());
    for (std::size_t i = 0; i < indices.arraySize(); ++i) mesh.indices.push_back(indices.at(i).index(vertices));
    if (auto n = o.find("normals")) {
      if (n->arraySize() != values) n->fail("must hold one normal (x, y, z) per vertex");
      for (std::size_t i = 0; i < vertices; ++i) {
        mesh.normals.emplace_back(n->at(3 * i).number(), n->at(3 * i + 1).number(), n->at(3 * i + 2).number());
      }
    }
    if (auto uv = o.find("uvs")) {
      if (uv->arraySize() != 2 * vertices) uv->fail("must hold one (u, v) pair per vertex");
      for (std::size_t i = 0; i < vertices; ++i) mesh.uvs.emplace_back(uv->at(2 * i).number(), uv->at(2 * i + 1).number());
    }
    if (o.has("materials")) o["materials"].fail("renames a mesh file's materials; an inline mesh has one material");
    mesh.material = meshMaterial(o, material(o));
    addMesh(o, std::move(mesh));
  }

  // A mesh from a file: its own materials (renamed by "materials"), or the
  // one "material" names for all its faces.
  void readMeshFile(const JsonReader& o, const JsonReader& f) {
    for (const char* key : {"indices", "normals", "uvs"}) {
      if (o.has(key)) o[key].fail("belongs to an inline mesh; a mesh from a file takes its own");
    }
    const bool own = !o.has("material");
    MeshModel obj = importMeshFile(files_, normalisePath(f.string()), f.path(), budget_, own, &images_);
    for (std::string& w : obj.warnings) warn(std::move(w));
    if (auto l = o.find("lights"); l && l->boolean()) addFileLights(o, *l, obj.lights);
    const std::vector<std::uint32_t> mapped = own ? ownMaterials(o, obj) : std::vector<std::uint32_t>{};
    const std::uint32_t named = own ? 0 : material(o);
    for (MeshInput& mesh : obj.meshes) {
      mesh.material = meshMaterial(o, own ? mapped[mesh.material] : named);
      addMesh(o, std::move(mesh));
    }
  }

  // A glTF file's lights, placed by the mesh's transform as its triangles.
  void addFileLights(const JsonReader& o, const JsonReader& flag, const std::vector<Light>& lights) {
    if (lights.empty()) flag.fail("the file has no KHR_lights_punctual lights (only glTF files carry lights)");
    const glm::mat4 m = transform(o).matrix();
    for (Light l : lights) {
      l.position = glm::vec3(m * glm::vec4(l.position, 1.0f));
      l.direction = glm::normalize(glm::vec3(m * glm::vec4(l.direction, 0.0f)));
      scene_.lights.push_back(l);
    }
  }

  // The file's materials as scene materials (their textures with them),
  // each renamed by the mesh's "materials" map where it names it; returns
  // the scene index of each.
  std::vector<std::uint32_t> ownMaterials(const JsonReader& o, MeshModel& obj) {
    std::map<std::string, std::uint32_t> renamed;
    if (auto r = o.find("materials")) {
      r->requireObject();
      for (const auto& item : r->raw().items()) {
        const std::string& name = item.key();
        const JsonReader entry(item.value(), r->path() + "." + name);
        const bool known = std::any_of(obj.materials.begin(), obj.materials.end(),
                                       [&name](const Material& m) { return m.name == name; });
        if (!known) entry.fail("the file has no material named '" + name + "'");
        const auto it = materialIndex_.find(entry.string());
        if (it == materialIndex_.end()) entry.fail("no material named '" + entry.string() + "' in materials");
        renamed[name] = it->second;
      }
    }
    const auto textureBase = static_cast<int>(scene_.textures.size());
    for (Texture& t : obj.textures) scene_.textures.push_back(std::move(t));
    std::vector<std::uint32_t> index;
    for (Material& m : obj.materials) {
      if (const auto it = renamed.find(m.name); it != renamed.end()) {
        index.push_back(it->second);
        continue;
      }
      if (m.texture >= 0) m.texture += textureBase;
      if (m.emissionTexture >= 0) m.emissionTexture += textureBase;
      m.name = o.path() + ":" + m.name;
      index.push_back(static_cast<std::uint32_t>(scene_.materials.size()));
      scene_.materials.push_back(std::move(m));
    }
    return index;
  }

  // The material a mesh's faces get: `index`, or with the mesh's "raytrace"
  // a copy of it that the auto mask rule traces (true) or leaves out (false).
  std::uint32_t meshMaterial(const JsonReader& o, std::uint32_t index) {
    const std::optional<JsonReader> r = o.find("raytrace");
    if (!r) return index;
    const RaytraceRule rule = r->boolean() ? RaytraceRule::kAlways : RaytraceRule::kNever;
    if (scene_.materials[index].raytrace == rule) return index;
    const auto key = std::make_pair(index, rule);
    if (const auto it = raytraceCopies_.find(key); it != raytraceCopies_.end()) return it->second;
    Material copy = scene_.materials[index];
    copy.raytrace = rule;
    copy.name = o.path() + ":" + copy.name;
    scene_.materials.push_back(std::move(copy));
    return raytraceCopies_[key] = static_cast<std::uint32_t>(scene_.materials.size() - 1);
  }

  // A warning, once however often it comes.
  void warn(std::string warning) {
    if (std::find(scene_.warnings.begin(), scene_.warnings.end(), warning) == scene_.warnings.end()) {
      scene_.warnings.push_back(std::move(warning));
    }
  }

  std::vector<glm::vec3> vectors3(const JsonReader& r, std::size_t count) {
    if (r.arraySize() != count) r.fail("must be an array of " + std::to_string(count) + " points");
    std::vector<glm::vec3> out;
    for (std::size_t i = 0; i < count; ++i) out.push_back(r.at(i).vec3());
    return out;
  }

  std::vector<glm::vec2> vectors2(const JsonReader& r, std::size_t count) {
    if (r.arraySize() != count) r.fail("must be an array of " + std::to_string(count) + " (u, v) pairs");
    std::vector<glm::vec2> out;
    for (std::size_t i = 0; i < count; ++i) out.push_back(r.at(i).vec2());
    return out;
  }

  void checkVertexBudget(const JsonReader& r, std::size_t vertices) {
    vertices_ += vertices;
    if (vertices_ > limits_.maxVertices) {
      r.fail("the scene's meshes have more vertices than the limit of " + std::to_string(limits_.maxVertices));
    }
  }

  void checkTriangleBudget(const JsonReader& r, std::size_t triangles) {
    triangles_ += triangles;
    if (triangles_ > limits_.maxTriangles) {
      r.fail("the scene's meshes have more triangles than the limit of " + std::to_string(limits_.maxTriangles));
    }
  }

  void addMesh(const JsonReader& o, MeshInput mesh) {
    if (!o.has("positions")) {  // inline meshes counted their budget before allocating
      checkVertexBudget(o, mesh.positions.size());
      checkTriangleBudget(o, mesh.indices.size() / 3);
    }
    const Transform t = transform(o);
    const glm::mat4 m = t.matrix();
    const glm::mat3 nm = t.normalMatrix();
    for (glm::vec3& p : mesh.positions) p = glm::vec3(m * glm::vec4(p, 1.0f));
    for (glm::vec3& n : mesh.normals) {
      const glm::vec3 v = nm * n;
      const float len = glm::length(v);
      n = len > 0.0f ? v / len : v;
    }
    if (auto smooth = o.find("smooth"); smooth && mesh.normals.empty()) {
      smoothNormals(mesh, smooth->number(0.0f, 180.0f));
    }
    budget_.chargeMesh(mesh.positions.size(), mesh.indices.size() / 3, o.path());
    scene_.geometry.addMesh(std::move(mesh));
  }

  FileSource& files_;
  SceneBudget& budget_;
  const LoadLimits& limits_;
  Scene scene_;
  std::map<std::string, int> textureIndex_;
  ImageCache images_;
  std::map<std::string, std::uint32_t> materialIndex_;
  std::map<std::pair<std::uint32_t, RaytraceRule>, std::uint32_t> raytraceCopies_;  // meshMaterial's copies
  std::size_t vertices_ = 0;
  std::size_t triangles_ = 0;
};

}  // namespace

Scene loadScene(std::string_view text, FileSource& files, const LoadLimits& limits) {
  SceneBudget budget(limits);
  return loadScene(text, files, budget);
}

Scene loadScene(std::string_view text, FileSource& files, SceneBudget& budget) {
  if (text.size() > budget.limits().maxFileBytes) {
    throw InputError("scene of " + std::to_string(text.size()) + " bytes is over the limit of " +
                     std::to_string(budget.limits().maxFileBytes));
  }
  // The text's shape bounds the parse before it begins: a deep nest would
  // take the parser's stack and a long array its memory.
  const JsonShape shape = measureJson(text);
  if (shape.depth > budget.limits().maxJsonDepth) {
    throw InputError("scene nests arrays and objects " + std::to_string(shape.depth) + " deep; at most " +
                     std::to_string(budget.limits().maxJsonDepth));
  }
  const std::size_t parsed = budget.chargeJson(
      shape.values, shape.members, "the scene's JSON (" + std::to_string(shape.values) + " values)");
  const nlohmann::json doc = parseJson(text, shape);
  try {
    Scene scene = SceneLoader(files, budget).load(doc);
    budget.refund(parsed);
    return scene;
  } catch (const nlohmann::json::exception& e) {
    throw InputError(std::string("unexpected JSON content: ") + e.what());
  }
}

Scene loadSceneFile(const std::filesystem::path& path, const LoadLimits& limits) {
  try {
    DirectorySource files(path.parent_path(), limits.maxFileBytes);
    const std::string text = sceneTextFor(path, files);
    return loadScene(text, files, limits);
  } catch (const InputError& e) {
    throw InputError(path.string() + ": " + e.what());
  }
}

}  // namespace glint

#include "client/commands/view_command.h"

// GL comes from client/raster/gl_api.h (loaded through glfwGetProcAddress).
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <atomic>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "client/farm/distributed_tile_service.h"
#include "client/raster/gl_api.h"
#include "client/raster/hybrid_frame.h"
#include "client/raster/image_rows.h"
#include "client/commands/progress.h"
#include "client/commands/provenance.h"
#include "client/raster/raster_scene.h"
#include "client/commands/scene_warnings.h"
#include "client/farm/tile_backend.h"
#include "common/base/error.h"
#include "common/base/timing.h"
#include "common/image/image_write.h"
#include "common/render/progressive_frame.h"
#include "proto/scene_bundle.h"

namespace glint {
namespace {

// Mouse and keyboard state, reached from GLFW's callbacks.
struct Controls {
  CameraSpec camera;
  MaskRule rule = MaskRule::kAuto;
  bool ruleFixed = false;  // path transport with no field to read: every pixel is traced under any rule
  bool overlay = false;
  bool provenance = false;
  bool dragging = false;
  bool panning = false;
  double lastX = 0.0;
  double lastY = 0.0;
  bool changed = true;  // the camera, the mask rule, an overlay or the size: a new preview
};

// While the camera moves, each frame is a preview: one sample at each
// pixel's centre (cheap, and without the raster's second, multisampled
// pass); once it stops, the frame with the scene's samples, equal to
// `glint render`'s.
FrameSettings previewOf(FrameSettings frame) {
  frame.sampling.samples = 1;
  frame.sampling.pattern = SamplePattern::kRegular;
  return frame;
}

// The scene's frame at the window's size, seen by the controls' camera.
FrameSettings viewFrame(GLFWwindow* window, const Scene& scene, const Controls& controls) {
  FrameSettings frame = scene.frame;
  glfwGetFramebufferSize(window, &frame.width, &frame.height);
  frame.camera = controls.camera;
  return frame;
}

void orbit(CameraSpec& c, float yaw, float pitch) {
  glm::vec3 offset = c.eye - c.lookAt;
  const glm::vec3 up = glm::normalize(c.up);
  offset = glm::vec3(glm::rotate(glm::mat4(1.0f), yaw, up) * glm::vec4(offset, 0.0f));
  const glm::vec3 right = glm::normalize(glm::cross(up, offset));
  const glm::vec3 pitched = glm::vec3(glm::rotate(glm::mat4(1.0f), pitch, right) * glm::vec4(offset, 0.0f));
  // Stop short of looking straight along the up vector.
  if (std::abs(glm::dot(glm::normalize(pitched), up)) < 0.99f) offset = pitched;
  c.eye = c.lookAt + offset;
}

void pan(CameraSpec& c, float dx, float dy) {
  const glm::vec3 forward = c.lookAt - c.eye;
  const float scale = glm::length(forward) * 0.002f;
  const glm::vec3 right = glm::normalize(glm::cross(forward, c.up));
  const glm::vec3 up = glm::normalize(glm::cross(right, forward));
  const glm::vec3 move = (-dx * right + dy * up) * scale;
  c.eye += move;
  c.lookAt += move;
}

Controls& controlsOf(GLFWwindow* window) {
  return *static_cast<Controls*>(glfwGetWindowUserPointer(window));
}

void installCallbacks(GLFWwindow* window) {
  glfwSetMouseButtonCallback(window, [](GLFWwindow* w, int button, int action, int) {
    Controls& c = controlsOf(w);
    glfwGetCursorPos(w, &c.lastX, &c.lastY);
    if (button == GLFW_MOUSE_BUTTON_LEFT) c.dragging = action == GLFW_PRESS;
    if (button == GLFW_MOUSE_BUTTON_RIGHT) c.panning = action == GLFW_PRESS;
  });
  glfwSetCursorPosCallback(window, [](GLFWwindow* w, double x, double y) {
    Controls& c = controlsOf(w);
    const auto dx = static_cast<float>(x - c.lastX), dy = static_cast<float>(y - c.lastY);
    c.lastX = x;
    c.lastY = y;
    if (c.dragging) orbit(c.camera, -dx * 0.005f, -dy * 0.005f);
    if (c.panning) pan(c.camera, dx, dy);
    c.changed = c.changed || c.dragging || c.panning;
  });
  glfwSetScrollCallback(window, [](GLFWwindow* w, double, double dy) {
    Controls& c = controlsOf(w);
    c.camera.eye = c.camera.lookAt + (c.camera.eye - c.camera.lookAt) * std::pow(0.9f, static_cast<float>(dy));
    c.changed = true;
  });
  glfwSetKeyCallback(window, [](GLFWwindow* w, int key, int, int action, int) {
    if (action != GLFW_PRESS) return;
    Controls& c = controlsOf(w);
    if (key == GLFW_KEY_Q || key == GLFW_KEY_ESCAPE) glfwSetWindowShouldClose(w, GLFW_TRUE);
    if (key == GLFW_KEY_M && !c.ruleFixed) {
      c.rule = c.rule == MaskRule::kAuto         ? MaskRule::kPerceptual
               : c.rule == MaskRule::kPerceptual ? MaskRule::kAll
               : c.rule == MaskRule::kAll        ? MaskRule::kNone
                                                 : MaskRule::kAuto;
    }
    if (key == GLFW_KEY_O) c.overlay = !c.overlay;
    if (key == GLFW_KEY_P) c.provenance = !c.provenance;
    c.changed = true;
  });
}

// The traced pixels (the mask) tinted red.
std::vector<std::uint8_t> maskOverlay(const HybridResult& r) {
  std::vector<std::uint8_t> rgb = r.image.rgb;
  for (std::size_t i = 0; i < r.mask.size(); ++i) {
    if (r.mask[i]) rgb[3 * i] = static_cast<std::uint8_t>(std::min(255, rgb[3 * i] / 2 + 128));
  }
  return rgb;
}

// Draws a top-down RGB image over the window. glDrawPixels' fragments pass
// the per-fragment tests like any other, so it sets every state they read
// instead of taking what the raster pass left: that pass leaves a reversed
// depth test (GL_GREATER) on, against which the window's depth buffer, never
// cleared, refused every pixel, and the window stayed black while the frame
// was right.
void drawImage(const gl::Api& gl, std::vector<std::uint8_t> rgb, int width, int height) {
  flipRows(rgb, width, height, 3);
  gl.BindFramebuffer(GL_FRAMEBUFFER, 0);
  gl.BindBuffer(GL_PIXEL_UNPACK_BUFFER, 0);
  gl.UseProgram(0);
  for (const GLenum test : {GL_DEPTH_TEST, GL_STENCIL_TEST, GL_SCISSOR_TEST, GL_BLEND, GL_FRAMEBUFFER_SRGB}) {
    gl.Disable(test);
  }
  gl.Viewport(0, 0, width, height);
  gl.PixelStorei(GL_UNPACK_ALIGNMENT, 1);
  gl.PixelStorei(GL_UNPACK_ROW_LENGTH, 0);
  gl.WindowPos2i(0, 0);
  gl.DrawPixels(width, height, GL_RGB, GL_UNSIGNED_BYTE, rgb.data());
}

// Stands in for the servers while none is left: every traced pixel comes
// back magenta, so that the raster frame shows what is missing.
class MissingTiles : public TileService {
 public:
  void render(const FrameSettings&, std::span<const TileJob> jobs,
              const std::function<void(std::size_t, TileOutput&&)>& done) override {
    for (std::size_t i = 0; i < jobs.size(); ++i) {
      TileOutput out;
      for (std::size_t p = 0; p < tracedPixels(jobs[i]); ++p) out.rgb.insert(out.rgb.end(), {255, 0, 255});
      done(i, std::move(out));
    }
  }
  int parallelism() const override { return 1; }
};

// "in process", "servers 2/3 up", or that none is and the view retries.
std::string whereLabel(TileBackend& backend, bool missing) {
  DistributedTileService* d = backend.distributed();
  if (!d) return backend.where();
  if (missing) return "no server left (missing tiles magenta), retrying";
  return "servers " + std::to_string(d->serversUp()) + "/" + std::to_string(d->serverCount()) + " up";
}

// The window's title: what the last frame was (`frame`), and where its
// tiles go, kept up to date between frames as servers come and go.
struct Title {
  std::string frame;
  std::string where;
  void show(GLFWwindow* window) const { glfwSetWindowTitle(window, ("glint view  |  " + frame + "  |  " + where).c_str()); }
};

// A traced frame's progress, told from the tile service's threads and shown
// in the title from the window's thread (GLFW's calls are the main thread's).
struct TitleProgress {
  std::atomic<int> done{0};
  std::atomic<int> total{0};
  int shown = -1;
  void show(GLFWwindow* window, const std::string& where) {
    const int now = done;
    if (now == shown) return;
    shown = now;
    Title{"tracing " + std::to_string(now) + " of " + std::to_string(total) + " pixels", where}.show(window);
  }
};

// One frame of the view: the hybrid frame through the backend's service
// or, when no server is left, the raster frame with the traced pixels
// marked (`reported`: the last error printed, so that a retry that fails the
// same way says nothing new); then the overlays and the title. A full frame
// is abandoned, and the window left as it was, when the camera moves while
// its tiles are traced.
enum class Shown { kFrame, kMissingTiles, kAbandoned };
Shown showFrame(GLFWwindow* window, const gl::Api& api, gl::RasterScene& raster, TileBackend& backend,
                Controls& controls, int tileSize, bool preview, HybridResult& last, std::string& reported,
                Title& title) {
  FrameSettings frame = viewFrame(window, backend.scene(), controls);
  if (preview) frame = previewOf(frame);
  MaskSettings mask = backend.scene().mask;
  mask.rule = controls.rule;
  bool missing = false;
  TitleProgress progress;
  const CancelCheck cameraMoved = [&] {
    glfwPollEvents();
    progress.show(window, title.where);
    return controls.changed;
  };
  const auto told = [&progress](int done, int total) {
    progress.total = total;
    progress.done = done;
  };
  // Under the rule all the field's frame traces path transport in full, as glint render --mask all does.
  std::optional<LocalTileService> unlit;
  const bool unlitFrame = backend.field() && mask.rule == MaskRule::kAll;
  if (unlitFrame && backend.prepared()) unlit.emplace(*backend.prepared(), *backend.pool());
  if (backend.distributed()) backend.distributed()->readField(!unlitFrame);
  try {
    if (!renderHybrid(api, raster, unlit ? *unlit : backend.service(), frame, mask, tileSize, last, std::nullopt,
                      {.cancelled = preview ? CancelCheck{} : cameraMoved, .progress = told})) {
      return Shown::kAbandoned;
    }
    reported.clear();
  } catch (const InputError& e) {
    if (!backend.distributed()) throw;
    if (reported != e.what()) std::fprintf(stderr, "glint view: %s\n", e.what());
    reported = e.what();
    MissingTiles none;
    renderHybrid(api, raster, none, frame, mask, tileSize, last);
    missing = true;
  }
  std::vector<std::uint8_t> shown = controls.overlay ? maskOverlay(last) : last.image.rgb;
  if (controls.provenance && backend.distributed() && !missing) {
    shown = provenanceImage(last.image, backend.distributed()->lastFrame()).rgb;
  }
  drawImage(api, std::move(shown), frame.width, frame.height);
  glfwSwapBuffers(window);
  char text[256];
  std::snprintf(text, sizeof text, "mask %s%s  |  %s %.0f ms: raster %.0f, read %.0f, RT %.0f, compose %.0f",
                std::string(enumWord(controls.rule)).c_str(), controls.overlay ? " (shown)" : "",
                preview ? "preview, 1 spp" : "frame", last.times.totalMs, last.times.rasterMs, last.times.readbackMs,
                last.times.traceMs, last.times.composeMs);
  title = {text, whereLabel(backend, missing)};
  title.show(window);
  return missing ? Shown::kMissingTiles : Shown::kFrame;
}

// The resting camera's frame summed in passes (in process, every pixel
// traced): 1, 2, 4, ... samples a pixel, each pass shown, until the frame
// is glint render's.
struct Accumulation {
  Accumulation(const PreparedScene& prepared, const FrameSettings& frame, int tileSize)
      : renderer(prepared, frame), frame(renderer, tileSize) {}
  Renderer renderer;
  ProgressiveFrame frame;
  double ms = 0.0;  // spent on its passes so far
};

// Whether the view sums its frames in passes: every pixel traced in
// process with a pattern whose samples add up in any number of passes (the
// hybrid rules' raster, the servers' 8-bit tiles and the adaptive patterns
// cannot).
bool summable(TileBackend& backend, const Controls& controls) {
  const SamplingSettings& s = backend.scene().frame.sampling;
  return backend.prepared() && controls.rule == MaskRule::kAll && s.samples > 1 &&
         s.pattern != SamplePattern::kAdaptive && s.pattern != SamplePattern::kPerceptual;
}

// The next pass of the resting camera's frame, made anew after the camera
// moved: its samples added (the first pass at once, a later one abandoned,
// and the frame dropped, when the camera moves meanwhile), then shown.
bool showPass(GLFWwindow* window, const gl::Api& api, TileBackend& backend, Controls& controls, int tileSize,
              std::unique_ptr<Accumulation>& acc, HybridResult& last, Title& title) {
  if (!acc) acc = std::make_unique<Accumulation>(*backend.prepared(), viewFrame(window, backend.scene(), controls), tileSize);
  const CancelCheck cameraMoved = [&] {
    glfwPollEvents();
    return controls.changed;
  };
  const Clock::time_point start = Clock::now();
  if (!acc->frame.addPass(*backend.pool(), acc->frame.samples() == 0 ? CancelCheck{} : cameraMoved)) {
    acc.reset();
    return false;
  }
  acc->ms += msSince(start);
  last.image = acc->frame.image();
  last.mask.assign(last.image.rgb.size() / 3, 1);
  drawImage(api, controls.overlay ? maskOverlay(last) : last.image.rgb, last.image.width, last.image.height);
  glfwSwapBuffers(window);
  const FrameSettings& frame = acc->renderer.frame();
  char text[256];
  std::snprintf(text, sizeof text, "mask all%s  |  %d of %d spp, %.0f ms", controls.overlay ? " (shown)" : "",
                acc->frame.samples(), frame.sampling.samples, acc->ms);
  title = {text, whereLabel(backend, false)};
  title.show(window);
  return true;
}

// Between frames: servers that joined connect and upload, servers that left
// go, and the title says how many are up.
void refreshFarm(GLFWwindow* window, TileBackend& backend, bool missing, Title& title) {
  DistributedTileService* farm = backend.distributed();
  if (!farm) return;
  farm->refresh();
  const std::string where = whereLabel(backend, missing);
  if (where == title.where || title.frame.empty()) return;
  title.where = where;
  title.show(window);
}

}  // namespace

void runView(const ViewOptions& options) {
  proto::LoadedBundle loaded = proto::loadSceneBundle(options.scene);
  printSceneWarnings(options.scene, loaded.scene);
  printNote(applyFrameOverrides(options.frame, loaded.scene));
  // The hybrid frame under path transport reads the irradiance field, filled once for the whole view.
  const bool field =
      loaded.scene.frame.tracing.transport == Transport::kPath && loaded.scene.mask.rule != MaskRule::kAll;

  if (!glfwInit()) {
    throw InputError(
        "glint view needs a display: cannot initialise GLFW (is DISPLAY set? glint render works headless)");
  }
  struct Terminate {
    ~Terminate() { glfwTerminate(); }
  } terminate;
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_COMPAT_PROFILE);
  glfwWindowHint(GLFW_RESIZABLE, GLFW_TRUE);
  GLFWwindow* window =
      glfwCreateWindow(loaded.scene.frame.width, loaded.scene.frame.height, "glint view", nullptr, nullptr);
  if (!window) throw InputError("glint view: cannot open an OpenGL 3.3 compatibility window");
  glfwMakeContextCurrent(window);
  glfwSwapInterval(0);
  const gl::Api api = gl::loadApi([](const char* name) { return reinterpret_cast<void*>(glfwGetProcAddress(name)); });

  if (field) glfwSetWindowTitle(window, "glint view  |  filling the irradiance field");
  ProgressLine probes = stderrProgress(ProgressMode::kAuto, "irradiance field", "probes");
  TileBackend backend({options.remote, options.bvh, false, field,
                       [&probes](int done, int total) { probes.update(done, total, {}, ProgressLine::Clock::now()); }},
                      std::move(loaded));
  probes.clear();
  const Scene& scene = backend.scene();
  gl::RasterScene raster(api, scene);
  if (backend.field()) raster.useField(*backend.field());

  Controls controls;
  controls.camera = scene.frame.camera;
  controls.rule = scene.mask.rule;
  controls.ruleFixed = scene.frame.tracing.transport == Transport::kPath && !backend.field();
  glfwSetWindowUserPointer(window, &controls);
  installCallbacks(window);
  glfwSetFramebufferSizeCallback(window, [](GLFWwindow* w, int, int) { controlsOf(w).changed = true; });

  constexpr double kRetrySeconds = 1.0;  // with no server left, a new frame this often
  const bool progressive = scene.frame.sampling.samples > 1;
  int frames = 0;
  double retryAt = 0.0;
  bool refine = false;  // a preview is shown; the full frame is owed once the camera rests
  HybridResult last;    // the latest frame; reused by the next
  std::string reported;
  Title title;
  std::unique_ptr<Accumulation> accumulating;  // the frame summed in passes, when summable()
  while (!glfwWindowShouldClose(window)) {
    const bool moved = controls.changed;
    if (summable(backend, controls)) {
      if (moved) accumulating.reset();
      refine = !accumulating || !accumulating->frame.complete();
      if (!refine && options.frames > 0) break;  // nothing more to show
      controls.changed = false;
      if (refine && showPass(window, api, backend, controls, options.frame.tileSize, accumulating, last, title) &&
          options.frames > 0 && ++frames >= options.frames) {
        break;
      }
    } else if (moved || refine || options.frames > 0 || (retryAt > 0.0 && glfwGetTime() >= retryAt)) {
      controls.changed = false;
      const bool preview = progressive && moved;
      const Shown shown =
          showFrame(window, api, raster, backend, controls, options.frame.tileSize, preview, last, reported, title);
      refine = preview;
      retryAt = shown == Shown::kMissingTiles ? glfwGetTime() + kRetrySeconds : 0.0;
      if (options.frames > 0 && ++frames >= options.frames) break;
    }
    if (refine) {
      glfwPollEvents();  // the full frame comes next unless the camera moved meanwhile
    } else {
      glfwWaitEventsTimeout(0.1);
      refreshFarm(window, backend, retryAt > 0.0, title);
    }
  }
  if (!options.screenshot.empty()) writePng(options.screenshot, last.image, backend.scene().frame.output.encoding);
  glfwDestroyWindow(window);
}

}  // namespace glint

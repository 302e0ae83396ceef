#include "client/cli.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <functional>
#include <memory>
#include <regex>
#include <sstream>
#include <utility>
#include <vector>

#include <CLI/CLI.hpp>

#include "client/accuracy/accuracy_command.h"
#include "client/accuracy/accuracy_sweep.h"
#include "client/commands/compare_command.h"
#include "client/commands/info_command.h"
#include "client/raster/offscreen_context.h"
#include "client/commands/render_command.h"
#include "client/farm/server_list.h"
#include "client/farm/server_source.h"
#include "client/commands/view_command.h"
#include "common/base/build_identity.h"
#include "common/base/compute_pool.h"
#include "common/base/error.h"
#include "common/base/nearest_word.h"
#include "common/scene/camera.h"
#include "common/scene/frame_limits.h"

namespace glint {
namespace {

constexpr const char* kRenderHelp =
    "Render a Glint scene (JSON, see docs/scene-format.md): the hybrid frame, OpenGL's pixels and the\n"
    "traced ones, written as PNG, EXR or PFM (by -o's extension).\n"
    "Settings given here override the scene file's. The image is the same\n"
    "whatever --threads and --tile-size are.";
constexpr const char* kViewHelp =
    "Open a window on a scene: the hybrid frame, live. Left drag orbits, right drag pans, the wheel "
    "zooms; M cycles the mask rule (auto, perceptual, all, none), O shows the mask, P (with --server) tints each "
    "traced pixel by the server that traced it, Q or Escape closes. While the camera "
    "moves each frame is a one-sample preview; at rest the scene's samples follow. The window may be resized.";

FieldSettings parseField(const std::string& text) {
  static const std::regex pattern(R"((\d{1,6}),(\d{1,6}))");
  std::smatch m;
  if (!std::regex_match(text, m, pattern)) throw UsageError("--field " + text + ": expected PROBES,RAYS, e.g. 8,256");
  const FieldSettings f{std::stoi(m[1]), std::stoi(m[2])};
  if (f.probes < FieldSettings::kMinProbes || f.probes > FieldSettings::kMaxProbes) {
    throw UsageError("--field " + text + ": probes must be in [" + std::to_string(FieldSettings::kMinProbes) + ", " +
                     std::to_string(FieldSettings::kMaxProbes) + "]");
  }
  if (const auto problem = FieldSettings::raysProblem(f.rays)) throw UsageError("--field " + text + ": rays " + *problem);
  return f;
}

void parseSize(const std::string& text, std::optional<int>& width, std::optional<int>& height) {
  static const std::regex pattern(R"((\d+)x(\d+))");
  std::smatch m;
  if (!std::regex_match(text, m, pattern)) {
    throw UsageError("--size " + text + ": expected WIDTHxHEIGHT, e.g. 640x480");
  }
  // Digits beyond what an edge can be are out of range, not malformed.
  const auto edge = [](const std::string& digits) {
    return digits.size() > 6 ? FrameLimits::kMaxEdge + 1 : std::stoi(digits);
  };
  const int w = edge(m[1]);
  const int h = edge(m[2]);
  if (w < 1 || h < 1 || w > FrameLimits::kMaxEdge || h > FrameLimits::kMaxEdge) {
    throw UsageError("--size " + text + ": width and height must be in [1, " + std::to_string(FrameLimits::kMaxEdge) +
                     "]");
  }
  width = w;
  height = h;
}

// "X0,Y0,X1,Y1" -> the window x0 <= x < x1, y0 <= y < y1 (y from the top).
TileRect parseCrop(const std::string& text) {
  static const std::regex pattern(R"((\d{1,6}),(\d{1,6}),(\d{1,6}),(\d{1,6}))");
  std::smatch m;
  if (!std::regex_match(text, m, pattern)) {
    throw UsageError("--crop " + text + ": expected X0,Y0,X1,Y1 (pixels, y from the top), e.g. 100,50,300,200");
  }
  const int x0 = std::stoi(m[1]), y0 = std::stoi(m[2]), x1 = std::stoi(m[3]), y1 = std::stoi(m[4]);
  if (x1 <= x0 || y1 <= y0) throw UsageError("--crop " + text + ": X1 must be above X0 and Y1 above Y0");
  return {x0, y0, x1 - x0, y1 - y0};
}

// "X,Y,Z" -> a point or direction; InputError naming the option otherwise
// (a value a float cannot hold, 1e999, included).
glm::vec3 parseVec3(const std::string& option, const std::string& text) {
  std::stringstream list(text);
  std::vector<float> values;
  for (std::string item; std::getline(list, item, ',');) {
    const auto first = item.find_first_not_of(' '), last = item.find_last_not_of(' ');
    if (first == std::string::npos) break;
    const std::size_t start = item[first] == '+' ? first + 1 : first;  // from_chars takes no '+'
    float v = 0.0f;
    const char* end = item.data() + last + 1;
    const auto [ptr, ec] = std::from_chars(item.data() + start, end, v);
    if (ec != std::errc() || ptr != end) break;
    values.push_back(v);
  }
  if (values.size() != 3 || !std::isfinite(values[0]) || !std::isfinite(values[1]) || !std::isfinite(values[2])) {
    throw UsageError(option + " " + text + ": expected X,Y,Z, e.g. 0,1.6,5");
  }
  return {values[0], values[1], values[2]};
}

// The value `parse` reads from an option's text; its InputError becomes a
// usage error, reported as CLI11 reports its own.
template <typename Parse>
auto asUsageError(const Parse& parse) {
  try {
    return parse();
  } catch (const InputError& e) {
    throw CLI::ValidationError(e.what());
  }
}

// --eye, --look-at, --up, --fov: the scene's camera, overridden.
void addCameraOptions(CLI::App* app, FrameOverrides& o) {
  const auto vec = [app](const char* name, std::optional<glm::vec3>& target, const char* help) {
    app->add_option_function<std::string>(
           name,
           [name, &target](const std::string& text) { target = asUsageError([&] { return parseVec3(name, text); }); },
           help)
        ->type_name("X,Y,Z");
  };
  vec("--eye", o.eye, "The camera's position (default: the scene's)");
  vec("--look-at", o.lookAt, "The point the camera looks at");
  vec("--up", o.up, "The camera's up direction");
  app->add_option("--fov", o.fovY, "Vertical field of view in degrees, in " + fovRange())
      ->check(CLI::Validator(
          [](const std::string& v) {
            char* end = nullptr;
            const float fov = std::strtof(v.c_str(), &end);  // not a number: CLI11's conversion says so
            return *end != '\0' || (fov > 0.0f && fov <= kMaxFovY) ? std::string() : "must be in " + fovRange();
          },
          "", "fov"));
  app->add_flag("--fit", o.fit,
                "Move the camera along its direction to frame every object (after --eye, --look-at; as the "
                "scene's camera \"fit\": true)");
}

// An option that takes one of an enum's words (common/base/enum_words.h); the
// words are listed in --help and in the error for any other.
template <typename Enum>
CLI::Option* addEnumOption(CLI::App* app, const std::string& name, std::optional<Enum>& target,
                           const std::string& help) {
  return app
      ->add_option_function<std::string>(
          name, [&target](const std::string& word) { target = enumFromWord<Enum>(word); }, help)
      ->check(CLI::IsMember(enumWordList<Enum>()));
}

// --gl: which headless OpenGL the raster pass runs on.
void addGlOption(CLI::App* app, std::optional<gl::GlBackend>& target) {
  std::string built;
  for (const gl::GlBackend b : gl::builtGlBackends())
    built += std::string(built.empty() ? "" : ", ") + std::string(enumWord(b));
  addEnumOption(app, "--gl", target,
                "Headless OpenGL for the raster pass: egl (Mesa's surfaceless platform) or osmesa; both draw the same "
                "bytes (default: the first of " +
                    built + " that can be had)");
}

// --server (repeatable, comma-separated), --server-file, --stall-timeout, --scene-timeout and
// TLS, for render, view and accuracy.
void addServerOptions(CLI::App* app, RemoteOptions& remote) {
  app->add_option("--server", remote.servers,
                  "Trace through the glintd at HOST:PORT (e.g. 127.0.0.1:7878); several: A:P,B:P or the option "
                  "repeated; a name with several addresses is one server each. The image is byte-identical to the "
                  "in-process one whatever the servers do")
      ->type_name("HOST:PORT[,...]")
      ->each([](const std::string& value) {
        if (const std::string problem = hostPortListProblem(value); !problem.empty()) {
          throw CLI::ValidationError("--server " + problem);
        }
      })
      ->expected(1)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  app->add_option("--server-file", remote.serverFile,
                  "Trace through the glintd listed in FILE (one HOST:PORT a line, # comments), besides any --server; "
                  "FILE is read again between frames: a server added joins, a server removed is dropped. Names "
                  "(here and in --server) are resolved again every " +
                      std::to_string(ServerSource::kResolveEvery.count()) + " s")
      ->type_name("FILE");
  app->add_option("--stall-timeout", remote.stallTimeoutS,
                  "Seconds a server with tiles outstanding may deliver nothing before its tiles go to the others")
      ->type_name("SECONDS")
      ->check(CLI::Range(0.05, 3600.0))
      ->default_val(2.0);
  app->add_option("--scene-timeout", remote.sceneTimeoutS,
                  "Seconds a server that lacks the scene may take to receive it (counted from the last byte "
                  "sent) and build it before it counts as unreachable")
      ->type_name("SECONDS")
      ->check(CLI::Range(1.0, 86400.0))
      ->default_val(120.0);
  app->add_option("--tls-ca", remote.tls.ca,
                  "Talk to the servers over TLS 1.3: the CA certificate (PEM) their certificates must chain to; each "
                  "must name the address dialled")
      ->envname("GLINT_TLS_CA");
  app->add_option("--tls-cert", remote.tls.cert, "This client's certificate (PEM), for servers that demand one")
      ->envname("GLINT_TLS_CERT");
  app->add_option("--tls-key", remote.tls.key, "The private key of --tls-cert (PEM)")->envname("GLINT_TLS_KEY");
}

// The frame's and mask's options, the same for every command that renders:
// each overrides the scene file's value.
void addFrameOptions(CLI::App* app, FrameOverrides& o) {
  addEnumOption(app, "--mask", o.mask,
                "Which pixels are ray traced (default: the scene's): auto, objects whose materials need it, "
                "drawn by OpenGL otherwise; perceptual, auto's pixels and the raster's visible colour edges, each "
                "traced with one ray and the frame's samples only where the difference is visible; all, the full "
                "ray trace; none, OpenGL only");
  app->add_option("--mask-threshold", o.maskThreshold,
                  "Under --mask auto or perceptual: materials with reflectivity above this are ray traced")
      ->check(CLI::Range(0.0f, 1.0f));
  app->add_option("--shadow-map", o.shadowMap,
                  "Shadow map size in texels a cube face edge (default: the scene's, 1024): surfaces OpenGL "
                  "draws get shadows, traced where the map cannot decide; 0: no shadows on them (the thesis)")
      ->check(CLI::Range(0, MaskSettings::kMaxShadowMap));
  app->add_option("--tile-size", o.tileSize, "Tile edge in pixels (work unit of a thread or a server request)")
      ->check(CLI::Range(1, 4096))
      ->default_val(64);
  app->add_option("--samples", o.samples, "Samples per pixel (regular: 1, 2, 4, 9, 16 ...)")
      ->check(CLI::Range(1, FrameLimits::kMaxSamples));
  addEnumOption(app, "--pattern", o.pattern,
                "Sample pattern (default: the scene's); adaptive: one sample per pixel, all where it differs from a "
                "neighbour; sobol: scrambled Sobol points, even in every direction at 2, 4, 8 ... samples");
  app->add_option("--adaptive-threshold", o.adaptiveThreshold,
                  "Under --pattern adaptive: a channel difference above this (linear, default 1/64) refines");
  app->add_option("--perceptual-threshold", o.perceptualThreshold,
                  "Under --pattern or --mask perceptual: a colour difference (FLIP's colour term, 0-1, default 0.3) "
                  "above this is visible and gets the frame's samples");
  app->add_option("--light-samples", o.lightSamples,
                  "Shadow rays each area and sphere light takes per query (default 0: each light's own samples)")
      ->check(CLI::Range(0, FrameLimits::kMaxLightSamples));
  addEnumOption(app, "--filter", o.filter, "Pixel filter (default: the scene's)");
  app->add_option("--seed", o.seed, "Seed of the jitter (same seed, same image)")
      ->check(CLI::Range(0u, FrameLimits::kMaxSeed));
  app->add_option("--max-depth", o.maxDepth, "Maximum ray depth (primary ray = 1)")
      ->check(CLI::Range(1, FrameLimits::kMaxDepth));
  app->add_option("--min-weight", o.minWeight, "Rays whose path weight falls below this are not traced")
      ->check(CLI::Range(0.0f, 1.0f));
  addEnumOption(app, "--transport", o.transport,
                "How light is carried: whitted (direct light and mirror paths) or path (path tracing: light "
                "between surfaces too); default: the scene's");
  app->add_option("--max-bounces", o.maxBounces, "Under path transport: bounces after a path's first hit")
      ->check(CLI::Range(0, FrameLimits::kMaxBounces));
  app->add_option_function<std::string>(
         "--field", [&o](const std::string& text) { asUsageError([&] { o.field = parseField(text); }); },
         "Under path transport: the hybrid frame draws the light between surfaces from an irradiance field of "
         "PROBES along the scene's longest side, RAYS each (a power of two), e.g. 8,256 (default: the scene's "
         "tracing.field; none: every pixel is traced)")
      ->type_name("PROBES,RAYS");
  app->add_option_function<std::string>(
         "--size", [&o](const std::string& text) { asUsageError([&] { parseSize(text, o.width, o.height); }); },
         "Image size WIDTHxHEIGHT (the camera's fov_y is kept; default: the scene's)")
      ->type_name("WxH");
  addCameraOptions(app, o);
  addEnumOption(app, "--encoding", o.encoding,
                "8-bit values (PNG): srgb (the sRGB transfer function, as a display shows a PNG) or linear (the "
                "thesis's frame buffer); default: the scene's image.encoding, else srgb");
  app->add_option("--exposure", o.exposure, "Scale the colour by 2^EV before encoding (default: the scene's, 0)")
      ->type_name("EV")
      ->check(CLI::Range(-FrameLimits::kMaxExposure, FrameLimits::kMaxExposure));
}

// --threads: the threads that trace and fill the irradiance field.
void addThreadsOption(CLI::App* app, int& threads) {
  app->add_option("--threads", threads, "Threads that trace and fill the irradiance field; 0 = one per hardware thread")
      ->check(CLI::Range(0, 1024))
      ->default_val(0);
}

// Declares `glint render`'s options; returns what runs once they are parsed.
std::function<void()> declareRender(CLI::App* render) {
  auto options = std::make_shared<RenderOptions>();
  RenderOptions& o = *options;
  render->add_option("scene", o.scene, "Scene file (.json), or a model file (.gltf, .glb, .obj, .ply) in a default scene")->required();
  render
      ->add_option("-o,--output", o.output,
                   "Image to write, its format by extension: .png (8-bit), .exr (half float, linear), .pfm (float, "
                   "linear); written only when the render succeeds")
      ->required();
  addFrameOptions(render, o.frame);
  addGlOption(render, o.gl);
  render->add_option("--mask-out", o.maskOut, "Also write the mask as a PNG (white: ray traced)");
  addThreadsOption(render, o.threads);
  render
      ->add_option_function<std::string>(
          "--crop", [&o](const std::string& text) { o.crop = asUsageError([&] { return parseCrop(text); }); },
          "Render only pixels X0 <= x < X1, Y0 <= y < Y1 (y from the top) of the frame; the image is that window")
      ->type_name("X0,Y0,X1,Y1");
  addEnumOption(render, "--bvh", o.bvh, "BVH builder in process (default: sah; qsplit is the thesis's)");
  addServerOptions(render, o.remote);
  render->add_option("--provenance-out", o.provenanceOut,
                     "With --server: also write the frame with each traced pixel tinted by the server that traced it "
                     "(tiles re-issued from a lost server outlined; the legend is printed)");
  render->add_option("--stats", o.statsPath,
                     "Write one JSON object per frame (rays by kind, timings, effect plan; docs/stats.md) to FILE; "
                     "- for stdout");
  render
      ->add_option("--frames", o.frames,
                   "Render N frames and print the median time of each step (like the thesis's Table 4.1)")
      ->check(CLI::Range(1, 100000))
      ->default_val(1);
  render->add_flag("-q,--quiet", o.quiet, "No progress, notes or summary on stderr (warnings and errors still show)");
  render->add_flag("--progress", o.progress,
                   "Show each frame's progress (pixels traced, each server's share, time left) even when stderr is not a "
                   "terminal (a line a second) or the frame is short");
  return [options] {
    setComputeThreads(options->threads);
    runRender(*options);
  };
}

// Declares `glint view`'s options; returns what runs once they are parsed.
std::function<void()> declareView(CLI::App* view) {
  auto options = std::make_shared<ViewOptions>();
  ViewOptions& o = *options;
  view->add_option("scene", o.scene, "Scene file (.json), or a model file (.gltf, .glb, .obj, .ply) in a default scene")->required();
  addServerOptions(view, o.remote);
  addFrameOptions(view, o.frame);
  addThreadsOption(view, o.threads);
  addEnumOption(view, "--bvh", o.bvh, "BVH builder in process (default: sah; qsplit is the thesis's)");
  view->add_option("--frames", o.frames, "Close after N frames (for scripts)")->check(CLI::Range(1, 1000000));
  view->add_option("--screenshot", o.screenshot, "Write the last frame as PNG when the window closes");
  return [options] {
    setComputeThreads(options->threads);
    runView(*options);
  };
}

constexpr const char* kInfoHelp =
    "Print what a scene holds and what rendering it would do: its image and camera, the box around its objects "
    "(and the camera --fit would give), objects, triangles, materials (which the mask traces), textures, lights, "
    "the effects the tracer will simulate, and the share of pixels the hybrid frame traces (one raster pass, "
    "nothing traced). Takes the frame options render takes.";

// Declares `glint info`'s options; returns what runs once they are parsed.
std::function<void()> declareInfo(CLI::App* info) {
  auto options = std::make_shared<InfoOptions>();
  InfoOptions& o = *options;
  info->add_option("scene", o.scene, "Scene file (.json), or a model file (.gltf, .glb, .obj, .ply) in a default scene")->required();
  addFrameOptions(info, o.frame);
  addGlOption(info, o.gl);
  info->add_flag_callback("--no-raster", [&o] { o.raster = false; },
                          "Skip the raster pass (no OpenGL; no traced-pixel count)");
  addThreadsOption(info, o.threads);
  return [options] {
    setComputeThreads(options->threads);
    runInfo(*options);
  };
}

std::string accuracyHelp() {
  return "Show what accuracy costs in time: render a converged reference of the scene, then the scene with one "
         "setting varied at a time (--vary KEY=V1,V2,...; KEY: " +
         enumWordsJoined<AccuracyKey>() +
         "; none: a default sweep of every key the scene uses), and write each setting's time and error against "
         "the reference (accuracy.csv: FLIP's mean, 95th and 99th percentiles, RMSE, PSNR), its images, error "
         "images and FLIP maps, a plot of error against time and report.md to DIR.";
}

// Declares `glint accuracy`'s options; returns what runs once they are parsed.
std::function<void()> declareAccuracy(CLI::App* accuracy) {
  auto options = std::make_shared<AccuracyOptions>();
  AccuracyOptions& o = *options;
  accuracy->add_option("scene", o.scene, "Scene file (.json), or a model file (.gltf, .glb, .obj, .ply) in a default scene")->required();
  accuracy->add_option("-o,--output", o.outDir, "Folder for the report, the CSV and the images")->required();
  accuracy->add_option("--vary", o.vary, "KEY=V1,V2,...: one series (repeatable)")
      ->type_name("KEY=V1,V2,...")
      ->expected(1)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  accuracy->add_option("--reference-samples", o.referenceSamples, "Samples per pixel of the reference (even), in the scene's pattern where it is jittered or sobol, else jittered")
      ->check(CLI::Range(2, FrameLimits::kMaxSamples))
      ->default_val(256);
  accuracy->add_option("--frames", o.frames, "Frames per setting; the median time is reported")
      ->check(CLI::Range(1, 1000))
      ->default_val(3);
  addFrameOptions(accuracy, o.frame);
  addThreadsOption(accuracy, o.threads);
  addServerOptions(accuracy, o.remote);
  addGlOption(accuracy, o.gl);
  addEnumOption(accuracy, "--metric", o.metric,
                "The plot's error axis and the Pareto front's: flip (mean FLIP, what a viewer sees; the default) or "
                "rmse");
  return [options] {
    setComputeThreads(options->threads);
    runAccuracy(*options);
  };
}

constexpr const char* kCompareHelp =
    "Compare two images of one size (PNG, JPEG, BMP, TGA: 8-bit values shown through sRGB; EXR, PFM, HDR: "
    "linear): print the mean FLIP error (the perceptual difference a viewer sees flipping between them, 0 none, "
    "1 the most; HDR-FLIP over a range of exposures when both are EXR, PFM or HDR) with its 95th and 99th "
    "percentiles, the RMSE and the PSNR, one line each; -o writes FLIP's error map.";

// Declares `glint compare`'s options; returns what runs once they are parsed.
std::function<void()> declareCompare(CLI::App* compare) {
  auto options = std::make_shared<CompareOptions>();
  CompareOptions& o = *options;
  compare->add_option("reference", o.reference, "The reference image")->required();
  compare->add_option("test", o.test, "The image judged against it")->required();
  compare->add_option("-o,--output", o.errorMap, "Write the FLIP error map (magma: black none, yellow most) as a PNG");
  compare
      ->add_option("--ppd", o.pixelsPerDegree,
                   "The viewer's pixels per degree (default 67: 0.7 m from a 0.7 m wide 3840-pixel display)")
      ->check(CLI::Range(1.0, 1000.0));
  return [options] { runCompare(*options); };
}

// glint's commands: a name, its help, and the function that declares its
// options. A new command is one more row.
struct CommandSpec {
  const char* name;
  std::string help;
  std::function<void()> (*declare)(CLI::App*);
};
const CommandSpec kCommands[] = {
    {"render", kRenderHelp, declareRender},
    {"view", kViewHelp, declareView},
    {"accuracy", accuracyHelp(), declareAccuracy},
    {"info", kInfoHelp, declareInfo},
    {"compare", kCompareHelp, declareCompare},
};

}  // namespace

constexpr int kUsageError = 2;

std::string joined(const std::vector<std::string>& words) {
  std::string text;
  for (const std::string& w : words) text += (text.empty() ? "" : ", ") + w;
  return text;
}

// Every name of the options `app` has ("--samples", "-o").
std::vector<std::string> optionNames(const CLI::App& app) {
  std::vector<std::string> names;
  for (const CLI::Option* option : app.get_options()) {
    for (const std::string& name : option->get_lnames()) names.push_back("--" + name);
    for (const std::string& name : option->get_snames()) names.push_back("-" + name);
  }
  return names;
}

// What CLI11 found wrong, said so that the user knows what to type instead:
// a command glint lacks or an option the command lacks (each with the
// nearest there is), else CLI11's own words.
std::string usageProblem(CLI::App& app, const CLI::ParseError& e, int argc, char** argv) {
  std::vector<std::string> commands;
  CLI::App* command = nullptr;
  for (CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; })) {
    commands.push_back(sub->get_name());
    if (argc > 1 && sub->get_name() == argv[1]) command = sub;
  }
  if (argc < 2) return "a command is required: " + joined(commands);
  if (argv[1][0] == '-') return e.what();
  if (!command) {
    const std::string near = nearestWord(argv[1], commands);
    return std::string("'") + argv[1] + "' is not a glint command (" + joined(commands) + ")" +
           (near.empty() ? "" : "; did you mean '" + near + "'?");
  }
  const std::string unknown =
      unknownOption("glint " + command->get_name(), std::vector<std::string>(argv + 2, argv + argc), optionNames(*command));
  return unknown.empty() ? e.what() : unknown;
}

// Where the options are listed: "glint render --help" for the command given.
std::string helpHint(const CLI::App& app) {
  for (const CLI::App* sub : app.get_subcommands()) return "the options: glint " + sub->get_name() + " --help";
  return "the commands: glint --help";
}

// A usage error in one line: what is wrong, then where the options are.
int usageError(const CLI::App& app, const std::string& problem) {
  std::fprintf(stderr, "glint: error: %s (%s)\n", problem.c_str(), helpHint(app).c_str());
  return kUsageError;
}

int runCli(int argc, char** argv) {
  CLI::App app{"glint: a hybrid OpenGL / ray-tracing renderer", "glint"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "glint 0.1.0 (" + buildIdentity() + ")");
  std::vector<std::pair<CLI::App*, std::function<void()>>> commands;
  for (const CommandSpec& c : kCommands) {
    CLI::App* sub = app.add_subcommand(c.name, c.help);
    commands.emplace_back(sub, c.declare(sub));
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // --help and --version are not errors; a usage error exits with 2, as
    // shells expect, in the same words as every other error.
    if (e.get_exit_code() == 0) return app.exit(e);
    return usageError(app, usageProblem(app, e, argc, argv));
  }
  try {
    for (const auto& [sub, run] : commands) {
      if (sub->parsed()) run();
    }
    return 0;
  } catch (const UsageError& e) {
    return usageError(app, e.what());
  } catch (const InputError& e) {
    std::fprintf(stderr, "glint: error: %s\n", e.what());
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "glint: internal error: %s\n", e.what());
    return 1;
  }
}

}  // namespace glint

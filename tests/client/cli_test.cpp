// Runs the real `glint` program as a user would and checks what it prints,
// its exit status and the files it leaves behind.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "client/accuracy/accuracy_sweep.h"
#include "common/image/encoding.h"
#include "common/image/image_read.h"
#include "common/image/image_write.h"
#include "tests/support/glint_run.h"
#include "tests/support/glintd_process.h"
#include "tests/support/test_support.h"

namespace {

namespace fs = std::filesystem;
using glint::Image;

using Result = glint::test::GlintRun;
Result glint(const std::string& args, const std::string& prefix = "") { return glint::test::runGlint(args, prefix); }
Image decodePng(const std::string& path) { return glint::test::decodePngFile(path); }

class Cli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("glint_cli_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  std::string writeScene(const std::string& name, const std::string& text) const {
    std::ofstream(path(name)) << text;
    return path(name);
  }
  static std::string scene(const std::string& name) { return std::string(GLINT_SOURCE_DIR) + "/scenes/" + name; }
  // A command's prefix that runs it on a virtual display of its own.
  static std::string onDisplay() { return "bash " + std::string(GLINT_SOURCE_DIR) + "/tests/support/with_display.sh "; }
  // glint view of `args` on a virtual display, closed after `frames`
  // frames, the last written to the PNG `png`.
  Result view(const std::string& args, int frames, const std::string& png) const {
    return glint("view " + args + " --frames " + std::to_string(frames) + " --screenshot " + path(png), onDisplay());
  }

  // Debian's textured glTF box in box/, and beside it box/NAME.gltf: the
  // same with `insert` written before the first `anchor`.
  void boxVariant(const std::string& name, const std::string& anchor, const std::string& insert) const {
    const fs::path models = "/usr/share/assimp/models/glTF2/BoxTextured-glTF";
    ASSERT_TRUE(fs::exists(models)) << "install assimp-testmodels (make deps)";
    if (!fs::exists(dir_ / "box")) fs::copy(models, dir_ / "box");
    std::ifstream in(models / "BoxTextured.gltf");
    std::string gltf((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    ASSERT_NE(gltf.find(anchor), std::string::npos);
    gltf.insert(gltf.find(anchor), insert);
    std::ofstream(dir_ / "box" / (name + ".gltf")) << gltf;
  }
  // A scene framing box/FILE.gltf, lit by one light.
  std::string boxScene(const std::string& file) const {
    return writeScene(file + ".json", R"({"glint": 1, "image": {"width": 96, "height": 72},
      "camera": {"eye": [2, 1.5, 3], "look_at": [0, 0, 0], "fit": true},
      "lights": [{"type": "point", "position": [3, 4, 5]}],
      "objects": [{"type": "mesh", "file": "box/)" +
                                          file + R"(.gltf"}]})");
  }

  fs::path dir_;
};

TEST_F(Cli, HelpExplainsEveryOption) {
  const Result run = glint("render --help");
  EXPECT_EQ(run.status, 0);
  for (const char* option : {"--output", "--mask", "--threads", "--samples", "--pattern", "--filter", "--max-depth",
                             "--min-weight", "--transport", "--max-bounces", "--size", "--stats", "--seed", "--bvh"}) {
    EXPECT_NE(run.output.find(option), std::string::npos) << option;
  }
  // glint accuracy's help names every key --vary takes.
  const std::string top = glint("--help").output;
  const std::size_t from = top.find("KEY: "), to = top.find("; none", from);
  ASSERT_NE(to, std::string::npos) << top;
  const std::string keys = ", " + top.substr(from + 5, to - from - 5) + ",";
  for (const std::string& key : glint::enumWordList<glint::AccuracyKey>()) {
    EXPECT_NE(keys.find(", " + key + ","), std::string::npos) << "accuracy's help lacks " << key;
  }
}

TEST_F(Cli, RendersThePngAndStats) {
  const Result run = glint("render " + scene("room.json") + " -o " + path("room.png") +
                           " --mask all --size 80x60 --samples 1 --pattern regular --stats " + path("stats.json"));
  ASSERT_EQ(run.status, 0) << run.output;
  ASSERT_TRUE(fs::exists(path("room.png")));
  std::ifstream png(path("room.png"), std::ios::binary);
  char magic[8] = {};
  png.read(magic, 8);
  EXPECT_EQ(std::string(magic + 1, 3), "PNG");
  std::ifstream statsFile(path("stats.json"));
  std::string stats((std::istreambuf_iterator<char>(statsFile)), std::istreambuf_iterator<char>());
  for (const char* key :
       {"\"width\":80", "\"height\":60", "\"masked_pixels\":4800", "\"primary\":4800", "\"shadow\":", "\"reflection\":",
        "\"refraction\":", "\"trace_ms\":", "\"total_ms\":", "\"effects\":", "\"nonfinite_samples\":0"}) {
    EXPECT_NE(stats.find(key), std::string::npos) << key << " in " << stats;
  }
}

// stderr here is a pipe, not a terminal: --progress prints lines (the last
// with the share each server traced), --quiet nothing, and neither changes
// the image.
TEST_F(Cli, ProgressLinesWhenAskedAndNothingWhenQuiet) {
  glint::server::test::GlintdProcess a({"--threads", "1"}), b({"--threads", "1"});
  const std::string args = "render " + scene("room.json") +
                           " --mask all --size 320x240 --samples 1 --pattern regular --frames 2 --server " +
                           a.address() + "," + b.address();
  const Result shown = glint(args + " --progress -o " + path("shown.png"));
  ASSERT_EQ(shown.status, 0) << shown.output;
  EXPECT_NE(shown.output.find("frame 1 of 2: "), std::string::npos) << shown.output;
  const std::size_t last = shown.output.find("frame 2 of 2: 76800/76800 pixels (100 %)");
  ASSERT_NE(last, std::string::npos) << shown.output;
  const std::string lastLine = shown.output.substr(last, shown.output.find('\n', last) - last);
  // Each server that traced some of it, with its share: the shares add up to
  // the whole (each floored). Which servers take part depends on which were
  // ready when the frame began.
  int shares = 0;
  for (const std::string& address : {a.address(), b.address()}) {
    const std::size_t at = lastLine.find(address + " ");
    if (at != std::string::npos) shares += std::stoi(lastLine.substr(at + address.size() + 1));
  }
  EXPECT_GE(shares, 99) << lastLine;
  EXPECT_LE(shares, 100) << lastLine;

  const Result unasked = glint(args + " -o " + path("unasked.png"));
  ASSERT_EQ(unasked.status, 0) << unasked.output;
  EXPECT_EQ(unasked.output.find("pixels ("), std::string::npos) << unasked.output;  // not a terminal
  const Result quiet = glint(args + " --progress --quiet -o " + path("quiet.png"));
  ASSERT_EQ(quiet.status, 0) << quiet.output;
  EXPECT_EQ(quiet.output, "");
  EXPECT_EQ(decodePng(path("shown.png")).rgb, decodePng(path("quiet.png")).rgb);

  const Result hybrid = glint("render " + scene("room.json") + " --size 160x120 --progress -o " + path("h.png"));
  ASSERT_EQ(hybrid.status, 0) << hybrid.output;
  EXPECT_NE(hybrid.output.find("rendering: "), std::string::npos) << hybrid.output;  // the traced pixels'
  EXPECT_NE(hybrid.output.find("pixels (100 %)"), std::string::npos) << hybrid.output;
}

// Progress is counted in pixels as they are traced, not in tiles: a path
// trace of one tile on one thread that takes seconds prints a line about
// every second while its one tile is traced, each further on than the last.
TEST_F(Cli, ProgressComesEverySecondWithinATile) {
  const Result run = glint("render " + scene("cornell.json") + " --size 64x64 --samples 512 --threads 1 --progress -o " +
                           path("p.png"));
  ASSERT_EQ(run.status, 0) << run.output;
  std::vector<int> done;
  std::size_t last = std::string::npos;
  for (std::size_t at = run.output.find("rendering: "); at != std::string::npos;
       at = run.output.find("rendering: ", at + 1)) {
    done.push_back(std::stoi(run.output.substr(at + 11)));
    last = at;
  }
  ASSERT_FALSE(done.empty()) << run.output;
  EXPECT_EQ(done.back(), 64 * 64) << run.output;
  for (std::size_t i = 1; i < done.size(); ++i) EXPECT_GT(done[i], done[i - 1]) << run.output;
  // The last line's time: a line at 0 s, one a second after, and the last.
  const std::size_t time = run.output.find("(100 %), ", last);
  ASSERT_NE(time, std::string::npos) << run.output;
  const double seconds = std::stod(run.output.substr(time + 9));
  ASSERT_GE(seconds, 1.5) << "too fast a machine to see it: raise --samples";
  EXPECT_GE(done.size(), static_cast<std::size_t>(seconds) + 1) << run.output;
}

TEST_F(Cli, HybridRenderWritesImageMaskAndStepTimes) {
  const Result run = glint("render " + scene("room.json") + " -o " + path("h.png") + " --mask auto --size 160x120" +
                           " --mask-out " + path("m.png") + " --stats " + path("s.json"));
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_TRUE(fs::exists(path("h.png")));
  EXPECT_TRUE(fs::exists(path("m.png")));
  std::ifstream statsFile(path("s.json"));
  std::string stats((std::istreambuf_iterator<char>(statsFile)), std::istreambuf_iterator<char>());
  for (const char* key : {"\"raster_ms\":", "\"readback_ms\":", "\"compose_ms\":", "\"trace_ms\":", "\"tiles\":",
                          "\"masked_pixels\":", "\"bvh_ms\":"}) {
    EXPECT_NE(stats.find(key), std::string::npos) << key << " in " << stats;
  }
  // In process nothing crosses a network, and the preparation is the BVH build.
  EXPECT_EQ(stats.find("\"network_ms\""), std::string::npos) << stats;
  EXPECT_EQ(stats.find("\"connect_ms\""), std::string::npos) << stats;
}

// glint view in a real window (an X server in memory, Xvfb) shows exactly the
// frame glint render writes.
// The view converges to glint render's frame; its preview is the one-sample
// frame.
TEST_F(Cli, ViewShowsTheSameFrameAsRender) {
  if (std::system("command -v Xvfb > /dev/null 2>&1") != 0) GTEST_SKIP() << "Xvfb is not installed";
  const std::string args = scene("room.json") + " --size 160x120";
  const Result shown = view(args, 2, "view.png");
  ASSERT_EQ(shown.status, 0) << shown.output;
  const Result render = glint("render " + args + " -o " + path("render.png") + " -q");
  ASSERT_EQ(render.status, 0) << render.output;
  std::ifstream a(path("view.png"), std::ios::binary), b(path("render.png"), std::ios::binary);
  const std::string viewBytes((std::istreambuf_iterator<char>(a)), std::istreambuf_iterator<char>());
  const std::string renderBytes((std::istreambuf_iterator<char>(b)), std::istreambuf_iterator<char>());
  EXPECT_FALSE(viewBytes.empty());
  EXPECT_EQ(viewBytes, renderBytes);

  // The view's first frame (the camera has just "moved") is the one-sample
  // preview: glint render's frame at one sample a pixel, at its centre.
  const Result preview = view(args, 1, "preview.png");
  ASSERT_EQ(preview.status, 0) << preview.output;
  ASSERT_EQ(glint("render " + args + " -o " + path("one.png") + " -q --samples 1 --pattern regular").status, 0);
  EXPECT_EQ(decodePng(path("preview.png")).rgb, decodePng(path("one.png")).rgb);
  EXPECT_NE(decodePng(path("preview.png")).rgb, decodePng(path("render.png")).rgb);
}

// Where every pixel is traced in process (path transport), the resting view
// sums its samples in passes, each shown, and ends as glint render's frame;
// its first pass, one sample a pixel, is far from it.
TEST_F(Cli, ThePathTracedViewConvergesToRendersFrame) {
  if (std::system("command -v Xvfb > /dev/null 2>&1") != 0) GTEST_SKIP() << "Xvfb is not installed";
  const std::string args = scene("cornell.json") + " --size 48x48 --samples 16 --max-bounces 3";
  const Result passes = view(args, 100, "view.png");
  ASSERT_EQ(passes.status, 0) << passes.output;
  const Result render = glint("render " + args + " -o " + path("render.png") + " -q");
  ASSERT_EQ(render.status, 0) << render.output;
  const std::vector<std::uint8_t> rendered = decodePng(path("render.png")).rgb;
  EXPECT_EQ(decodePng(path("view.png")).rgb, rendered);

  const Result first = view(args, 1, "first.png");
  ASSERT_EQ(first.status, 0) << first.output;
  const std::vector<std::uint8_t> pass = decodePng(path("first.png")).rgb;
  ASSERT_EQ(pass.size(), rendered.size());
  double squares = 0.0;
  for (std::size_t i = 0; i < pass.size(); ++i) squares += std::pow(double(pass[i]) - double(rendered[i]), 2.0);
  EXPECT_GT(std::sqrt(squares / static_cast<double>(pass.size())), 4.0);  // one sample's noise, in 8-bit steps
}

// Through two glintd the irradiance field is filled in batches both trace,
// then sent to each: the frame is the same bytes as in process, and the
// summary lists each server's share of the field's probes.
TEST_F(Cli, TheFarmFillsTheFieldAndDrawsTheSameFrame) {
  glint::server::test::GlintdProcess a({"--threads", "1"}), b({"--threads", "1"});
  const std::string args = scene("cornell.json") + " --size 48x48 --samples 16 --field 16,256";
  const Result local = glint("render " + args + " -o " + path("local.png"));
  ASSERT_EQ(local.status, 0) << local.output;
  const Result farm = glint("render " + args + " -o " + path("farm.png") + " --server " + a.address() + "," +
                            b.address());
  ASSERT_EQ(farm.status, 0) << farm.output;
  EXPECT_EQ(farm.output.find("every pixel is traced"), std::string::npos) << farm.output;
  EXPECT_EQ(decodePng(path("farm.png")).rgb, decodePng(path("local.png")).rgb);
  // Each server's line of the field: "server ADDRESS ok N batches P probes".
  std::size_t probes = 0, servers = 0;
  for (const std::string& address : {a.address(), b.address()}) {
    const auto at = farm.output.find("server " + address);
    ASSERT_NE(at, std::string::npos) << farm.output;
    const std::string line = farm.output.substr(at, farm.output.find('\n', at) - at);
    const auto batches = line.find(" batches ");
    if (batches == std::string::npos) continue;  // the frame's line, not the field's
    const std::size_t p = std::stoul(line.substr(batches + 9));
    probes += p;
    servers += p > 0 ? 1 : 0;
  }
  EXPECT_EQ(probes, 4096u) << farm.output;  // 16 x 16 x 16
  EXPECT_EQ(servers, 2u) << farm.output;
}

// Through two glintd, the view shows the same frame, with an irradiance field
// too; with no server at all it keeps showing the raster frame, the pixels
// that needed tracing magenta, and says why.
TEST_F(Cli, ViewThroughServersAndWithoutThem) {
  if (std::system("command -v Xvfb > /dev/null 2>&1") != 0) GTEST_SKIP() << "Xvfb is not installed";
  glint::server::test::GlintdProcess a({"--threads", "1"}), b({"--threads", "1"});
  const std::string args = scene("room.json") + " --size 160x120";
  const Result view = glint(
      "view " + args + " --frames 2 --screenshot " + path("view.png") + " --server " + a.address() + "," + b.address(),
      onDisplay());
  ASSERT_EQ(view.status, 0) << view.output;
  const Result render = glint("render " + args + " -o " + path("render.png") + " -q");
  ASSERT_EQ(render.status, 0) << render.output;
  EXPECT_EQ(decodePng(path("view.png")).rgb, decodePng(path("render.png")).rgb);

  // With an irradiance field, which the servers fill and then read.
  const std::string field = scene("cornell.json") + " --size 48x48 --samples 4 --field 8,256";
  const Result fieldView = glint("view " + field + " --frames 2 --screenshot " + path("field-view.png") +
                                     " --server " + a.address() + "," + b.address(),
                                 onDisplay());
  ASSERT_EQ(fieldView.status, 0) << fieldView.output;
  EXPECT_EQ(fieldView.output.find("every pixel is traced"), std::string::npos) << fieldView.output;
  ASSERT_EQ(glint("render " + field + " -o " + path("field-render.png") + " -q").status, 0);
  EXPECT_EQ(decodePng(path("field-view.png")).rgb, decodePng(path("field-render.png")).rgb);

  const Result alone =
      glint("view " + args + " --frames 2 --screenshot " + path("alone.png") + " --server 127.0.0.1:1", onDisplay());
  ASSERT_EQ(alone.status, 0) << alone.output;
  EXPECT_NE(alone.output.find("no glintd can serve"), std::string::npos) << alone.output;
  const Image missing = decodePng(path("alone.png"));
  std::size_t magenta = 0;
  for (std::size_t i = 0; i + 2 < missing.rgb.size(); i += 3) {
    magenta += missing.rgb[i] == 255 && missing.rgb[i + 1] == 0 && missing.rgb[i + 2] == 255 ? 1 : 0;
  }
  EXPECT_GT(magenta, 1000u);  // the mirror, the sphere and the floor of the room's auto mask
}

// A glTF and a PLY model (Debian's assimp-testmodels), with a missing
// texture's warning: the same image in process and through two glintd, which
// get the imported meshes, not the files.
TEST_F(Cli, ImportedModelsRenderTheSameThroughServers) {
  const fs::path models = "/usr/share/assimp/models";
  fs::create_directories(dir_ / "box");
  for (const char* f : {"BoxTextured.gltf", "BoxTextured0.bin"}) {
    fs::copy_file(models / "glTF2/BoxTextured-glTF" / f, dir_ / "box" / f);  // its CesiumLogoFlat.png left behind
  }
  fs::copy_file(models / "PLY/cube_binary.ply", dir_ / "cube.ply");
  const std::string scenePath = writeScene("models.json", R"({"glint": 1, "image": {"width": 96, "height": 64},
    "camera": {"eye": [3, 2, 4], "look_at": [0, 0, 0]}, "lights": [{"type": "point", "position": [3, 5, 4]}],
    "materials": {"clay": {"color": [0.8, 0.6, 0.4], "reflectivity": 0.3}},
    "objects": [{"type": "mesh", "file": "box/BoxTextured.gltf"},
                {"type": "mesh", "file": "cube.ply", "material": "clay", "transform": {"translate": [-1.5, 0, 0]}}]})");
  const Result here = glint("render " + scenePath + " -o " + path("here.png"));
  ASSERT_EQ(here.status, 0) << here.output;
  EXPECT_NE(here.output.find("warning: " + scenePath +
                             ": 'box/BoxTextured.gltf' names the texture "
                             "'box/CesiumLogoFlat.png', which is missing"),
            std::string::npos)
      << here.output;
  glint::server::test::GlintdProcess a({"--threads", "1"}), b({"--threads", "1"});
  const Result there =
      glint("render " + scenePath + " -o " + path("there.png") + " --server " + a.address() + "," + b.address());
  ASSERT_EQ(there.status, 0) << there.output;
  EXPECT_EQ(decodePng(path("there.png")).rgb, decodePng(path("here.png")).rgb);
  const Image image = decodePng(path("here.png"));
  std::size_t lit[2] = {0, 0};  // left half: the PLY cube; right half: the glTF box
  for (std::size_t i = 0; i < image.rgb.size() / 3; ++i) {
    const bool bright = image.rgb[3 * i] > 20 || image.rgb[3 * i + 1] > 20 || image.rgb[3 * i + 2] > 20;
    lit[i % 96 < 48 ? 0 : 1] += bright ? 1 : 0;
  }
  EXPECT_GT(lit[0], 150u);
  EXPECT_GT(lit[1], 150u);
}

// A scene whose mesh is larger than a server's message limit goes through
// in pieces (here a 2.2 MB OBJ to a glintd taking 1 MiB messages; the same
// path carries a 150 MB mesh past the default 64 MiB).
TEST_F(Cli, MeshLargerThanTheMessageLimitGoesThroughInPieces) {
  std::ofstream obj(path("grid.obj"));
  constexpr int n = 180;  // 32,761 vertices, 64,800 triangles
  for (int y = 0; y <= n; ++y) {
    for (int x = 0; x <= n; ++x)
      obj << "v " << x / 90.0 - 1 << ' ' << y / 90.0 - 1 << ' ' << 0.1 * std::sin(x * 0.3) * std::cos(y * 0.2) << '\n';
  }
  for (int y = 0; y < n; ++y) {
    for (int x = 0; x < n; ++x) {
      const int a = y * (n + 1) + x + 1;
      obj << "f " << a << ' ' << a + 1 << ' ' << a + n + 2 << "\nf " << a << ' ' << a + n + 2 << ' ' << a + n + 1
          << '\n';
    }
  }
  obj.close();
  ASSERT_GT(fs::file_size(path("grid.obj")), std::uintmax_t{2} << 20);  // two pieces at least
  const std::string scenePath = writeScene("grid.json", R"({"glint": 1, "image": {"width": 64, "height": 48},
    "camera": {"eye": [0, 0, 3], "look_at": [0, 0, 0]}, "lights": [{"type": "point", "position": [1, 2, 3]}],
    "materials": {"m": {"color": [0.7, 0.8, 0.9], "reflectivity": 0.5}},
    "objects": [{"type": "mesh", "file": "grid.obj", "material": "m", "smooth": 80}]})");
  ASSERT_EQ(glint("render " + scenePath + " -o " + path("here.png") + " -q").status, 0);
  glint::server::test::GlintdProcess glintd({"--max-message-mb", "1"});
  const Result there = glint("render " + scenePath + " -o " + path("there.png") + " -q --server " + glintd.address());
  ASSERT_EQ(there.status, 0) << there.output;
  EXPECT_EQ(decodePng(path("there.png")).rgb, decodePng(path("here.png")).rgb);
}

// A usage error (an option or command that does not exist) exits with 2 and
// names the nearest one there is; other errors, a missing file among them,
// exit with 1. Every error is one line.
TEST_F(Cli, UsageErrorsExitWithTwo) {
  const auto oneLine = [](const Result& r) {
    return r.output.find('\n') == r.output.size() - 1 && r.output.rfind("glint: error: ", 0) == 0;
  };
  const Result misspelt = glint("render " + scene("room.json") + " -o " + path("x.png") + " --smaples 4");
  EXPECT_EQ(misspelt.status, 2);
  EXPECT_EQ(misspelt.output,
            "glint: error: glint render has no option --smaples; did you mean --samples? (the options: glint render "
            "--help)\n");
  const Result command = glint("rendr " + scene("room.json"));
  EXPECT_EQ(command.status, 2);
  EXPECT_NE(command.output.find("'rendr' is not a glint command (render, view, accuracy, info, compare); did you "
                                "mean 'render'?"),
            std::string::npos)
      << command.output;
  EXPECT_TRUE(oneLine(command)) << command.output;
  // info takes the frame options, not render's --frames: said so, not "arguments not expected: 2 --frames".
  const Result info = glint("info " + scene("room.json") + " --frames 2");
  EXPECT_EQ(info.status, 2);
  EXPECT_EQ(info.output, "glint: error: glint info has no option --frames (the options: glint info --help)\n");
  EXPECT_EQ(glint("render " + scene("room.json") + " -o " + path("x.png") + " --eye 1,2").status, 2);
  // A scene or image that is not there is a file error.
  const Result missing = glint("render " + path("missing.json") + " -o " + path("x.png"));
  EXPECT_EQ(missing.status, 1);
  EXPECT_NE(missing.output.find("missing.json"), std::string::npos) << missing.output;
  EXPECT_TRUE(oneLine(missing)) << missing.output;
  EXPECT_EQ(glint("compare " + path("a.png") + " " + path("b.png")).status, 1);
  // A value glint cannot use, or options that do not go together, are usage errors too; every message in
  // one style, with where the options are listed.
  for (const char* options : {"-o x.jpg", "-o x.png --size 640", "-o x.png --size -5x10",
                              "-o x.png --samples 5 --pattern regular", "-o x.png --adaptive-threshold 0",
                              "-o x.png --mask bogus", "-o x.png --crop 0,0,700,10",
                              "-o x.png --provenance-out p.png", "-o x.png --tls-ca ca.pem", "-o x.png --server 127.0.0.1",
                              "-o x.png --server 127.0.0.1:7878,host:port"}) {
    const Result run = glint("render " + scene("room.json") + " " + options);
    EXPECT_EQ(run.status, 2) << options << "\n" << run.output;
    EXPECT_TRUE(oneLine(run)) << options << "\n" << run.output;
    EXPECT_NE(run.output.find("(the options: glint render --help)"), std::string::npos) << run.output;
  }
  // Everything else is 1: a scene, a file, a server.
  EXPECT_EQ(glint("render " + writeScene("bad.json", R"({"glint": 1, "objects": 3})") + " -o " + path("x.png")).status,
            1);
  EXPECT_EQ(glint("render " + scene("room.json") + " -o " + path("x.png") + " --server 127.0.0.1:1").status, 1);
  const Result version = glint("--version");
  EXPECT_EQ(version.status, 0);
  EXPECT_NE(version.output.find("glint 0.1.0 (pixels-"), std::string::npos) << version.output;
}

// Every command that renders takes the same frame options (declared once),
// and a malformed one is a usage error in each (--size 640 exited 1 where
// it was parsed after the command line).
TEST_F(Cli, EveryRenderingCommandTakesTheSameFrameOptions) {
  for (const char* command : {"render", "view", "accuracy"}) {
    const Result help = glint(std::string(command) + " --help");
    EXPECT_EQ(help.status, 0) << command;
    for (const char* option : {"--mask ", "--mask-threshold", "--shadow-map", "--tile-size", "--samples", "--pattern",
                               "--adaptive-threshold", "--perceptual-threshold", "--filter", "--seed", "--max-depth", "--min-weight", "--size",
                               "--eye", "--look-at", "--up", "--fov", "--encoding", "--exposure"}) {
      EXPECT_NE(help.output.find(option), std::string::npos) << command << " lacks " << option;
    }
    const std::string output = std::string(command) == "view" ? "" : " -o " + path("x");
    const Result size = glint(std::string(command) + " " + scene("room.json") + output + " --size 640");
    EXPECT_EQ(size.status, 2) << command << ": " << size.output;
    EXPECT_NE(size.output.find("--size 640: expected WIDTHxHEIGHT"), std::string::npos) << size.output;
  }
  EXPECT_TRUE(fs::is_empty(dir_));
}

// A scene whose objects are known: a mirror sphere (radius 1 at (1, 0, 0))
// over a matte floor quad from (-3, -1, -2) to (3, -1, 2).
constexpr const char* kTwoObjects = R"({"glint": 1, "image": {"width": 64, "height": 48},
  "camera": {"eye": [0, 1, 6], "look_at": [0, 0, 0]},
  "materials": {"mirror": {"color": [1, 1, 1], "reflectivity": 0.9}, "matte": {"color": [0.5, 0.5, 0.5]}},
  "lights": [{"type": "point", "position": [0, 4, 4]}],
  "objects": [{"type": "sphere", "center": [1, 0, 0], "radius": 1, "material": "mirror"},
              {"type": "mesh", "positions": [-3,-1,-2, 3,-1,-2, 3,-1,2, -3,-1,2], "indices": [0,1,2, 0,2,3],
               "material": "matte"}]})";

// glint info says what the scene holds; the pixels it says the hybrid frame
// traces are those of the mask glint render writes (--mask-out), counted.
TEST_F(Cli, InfoDescribesTheSceneAndWhatTheHybridFrameTraces) {
  const std::string file = writeScene("two.json", kTwoObjects);
  const Result info = glint("info " + file);
  ASSERT_EQ(info.status, 0) << info.output;
  for (const char* line : {"image      64x48, 1 regular samples a pixel", "bounds     min (-3, -1, -2), max (3, 1, 2)",
                           "objects    1 mesh, 1 sphere; 2 triangles (0 dropped: cannot be hit), 4 vertices",
                           "materials  2, 1 traced under the mask rule auto: mirror", "lights     1 light\n             point at (",
                           "effects    simulated: shadows reflection; left out: refraction textures"}) {
    EXPECT_NE(info.output.find(line), std::string::npos) << line << "\n" << info.output;
  }
  const std::size_t at = info.output.find("hybrid     traces ");
  ASSERT_NE(at, std::string::npos) << info.output;
  const unsigned long traced = std::stoul(info.output.substr(at + 18));
  EXPECT_NE(info.output.find(" of 3072 pixels", at), std::string::npos) << info.output;
  ASSERT_EQ(glint("render " + file + " -q -o " + path("x.png") + " --mask-out " + path("mask.png")).status, 0);
  const Image mask = decodePng(path("mask.png"));
  unsigned long white = 0;
  for (std::size_t i = 0; i < mask.rgb.size(); i += 3) white += mask.rgb[i] == 255 ? 1 : 0;
  EXPECT_GT(white, 100u);
  EXPECT_EQ(traced, white);
  // The frame options apply, and --no-raster leaves the count out.
  const Result small = glint("info " + file + " --size 32x24 --mask all --no-raster");
  EXPECT_NE(small.output.find("image      32x24"), std::string::npos) << small.output;
  EXPECT_EQ(small.output.find("hybrid"), std::string::npos) << small.output;
}

// An environment image is named with its size and what the hybrid frame
// does with the pixels that show it.
TEST_F(Cli, InfoNamesTheEnvironmentImage) {
  const Result info = glint("info " + scene("environment.json") + " --size 64x36 --no-raster");
  ASSERT_EQ(info.status, 0) << info.output;
  EXPECT_NE(info.output.find("sky        256x128 environment image (escaping rays; the background traced)"),
            std::string::npos)
      << info.output;
  EXPECT_NE(info.output.find(" environment; left out:"), std::string::npos) << info.output;
  const Result flat = glint("info " + scene("environment.json") + " --mask none --no-raster");
  EXPECT_NE(flat.output.find("(escaping rays; the background drawn flat by OpenGL)"), std::string::npos) << flat.output;
}

// A sphere light is named with its ball and shadow rays, and soft shadows
// are simulated.
TEST_F(Cli, InfoNamesTheSphereLight) {
  const Result info = glint("info " + scene("sphere-light.json") + " --no-raster");
  ASSERT_EQ(info.status, 0) << info.output;
  EXPECT_NE(info.output.find("sphere at (1.2, 3.4, 0.8), radius 0.7, 16 samples, colour (1, 1, 1)"), std::string::npos)
      << info.output;
  EXPECT_NE(info.output.find(" soft_shadows"), std::string::npos) << info.output;
  EXPECT_EQ(info.output.find("left out: soft_shadows"), std::string::npos) << info.output;
}

// The Cornell box's lamp is its light: info counts its emitting surfaces,
// and its shadows (soft, as an area light's) are simulated, not left out.
TEST_F(Cli, InfoCountsEmittingSurfacesAsLights) {
  const Result info = glint("info " + scene("cornell.json") + " --no-raster");
  ASSERT_EQ(info.status, 0) << info.output;
  EXPECT_NE(info.output.find("0 lights; 2 emitting surfaces (lighting the others: path transport)"), std::string::npos)
      << info.output;
  const std::size_t left = info.output.find("left out:");
  ASSERT_NE(left, std::string::npos) << info.output;
  EXPECT_EQ(info.output.find(" shadows", left), std::string::npos) << info.output;
  EXPECT_EQ(info.output.find(" soft_shadows", left), std::string::npos) << info.output;
  const Result whitted = glint("info " + scene("cornell.json") + " --transport whitted --no-raster");
  EXPECT_NE(whitted.output.find("2 emitting surfaces (their own colour only: Whitted transport)"), std::string::npos)
      << whitted.output;
}

// Path transport is named by info, simulated as indirect light, and traced
// in full under any mask rule (the raster draws direct light only), with a
// note saying so; --transport chooses it from the command line.
TEST_F(Cli, PathTransportIsTracedInFullAndSaysSo) {
  const Result info = glint("info " + scene("cornell.json") + " --no-raster");
  ASSERT_EQ(info.status, 0) << info.output;
  EXPECT_NE(info.output.find("transport  path: light between surfaces too, up to 8 bounces"), std::string::npos)
      << info.output;
  EXPECT_NE(info.output.find(" indirect_light;"), std::string::npos) << info.output;
  const Result room = glint("info " + scene("room.json") + " --no-raster");
  EXPECT_NE(room.output.find("transport  whitted: direct light"), std::string::npos) << room.output;
  EXPECT_NE(room.output.find(" indirect_light\n"), std::string::npos) << room.output;  // left out

  const std::string small = " --size 40x40 --samples 2 -o ";
  const Result hybrid = glint("render " + scene("cornell.json") + small + path("auto.png"));
  ASSERT_EQ(hybrid.status, 0) << hybrid.output;
  EXPECT_NE(hybrid.output.find("note: path transport: every pixel is traced"), std::string::npos) << hybrid.output;
  ASSERT_EQ(glint("render " + scene("cornell.json") + " -q --mask all" + small + path("all.png")).status, 0);
  EXPECT_EQ(decodePng(path("auto.png")).rgb, decodePng(path("all.png")).rgb);
  const Result whitted = glint("render " + scene("cornell.json") + " --transport whitted" + small + path("w.png"));
  EXPECT_EQ(whitted.output.find("note: path transport"), std::string::npos) << whitted.output;
  EXPECT_NE(decodePng(path("w.png")).rgb, decodePng(path("all.png")).rgb);
  const Result room2 = glint("render " + scene("room.json") + " -q --transport path --max-bounces 2" + small +
                             path("room.png"));
  EXPECT_EQ(room2.status, 0) << room2.output;
}

// The words a user reads are true: --quiet is quiet under path transport
// too (no note), the help names every output format and shows no internal
// default, info takes --threads, a range is said once whichever side a value
// falls, and a format version this build does not read says which it does.
TEST_F(Cli, WordsAreTrue) {
  const std::string small = " --size 24x24 --samples 1 -o ";
  const Result quiet = glint("render " + scene("cornell.json") + " -q" + small + path("q.png"));
  EXPECT_EQ(quiet.status, 0);
  EXPECT_EQ(quiet.output, "");
  const Result help = glint("--help");
  EXPECT_NE(help.output.find("written as PNG, EXR or PFM"), std::string::npos) << help.output;
  const Result info = glint("info --help");
  EXPECT_NE(info.output.find("--no-raster "), std::string::npos) << info.output;
  EXPECT_EQ(info.output.find("{false}"), std::string::npos) << info.output;
  // info fills the irradiance field as render does, on the threads it is given.
  const Result field = glint("info " + scene("cornell.json") + " --field 4,64 --size 24x24 --threads 1");
  EXPECT_EQ(field.status, 0) << field.output;
  for (const char* fov : {"0", "180"}) {
    const Result r = glint("render " + scene("room.json") + " --fov " + fov + small + path("f.png"));
    EXPECT_NE(r.output.find("must be in (0, 179]"), std::string::npos) << fov << ": " << r.output;
  }
}

// --field (or the scene's tracing.field) has the hybrid frame draw path
// transport's light between surfaces from an irradiance field: OpenGL draws
// most pixels, the tracer the emitter's penumbra and where the field cannot
// decide; its mean light is the path trace's within the field's bias. info
// says so and counts the pixels render traced; bad values say what they take.
TEST_F(Cli, TheFieldDrawsIndirectLightInTheHybridFrame) {
  const std::string small = " --size 48x48 --samples 16 -o ";
  const Result field = glint("render " + scene("cornell.json") + " --field 8,256 --stats " + path("stats.json") +
                             small + path("field.png"));
  ASSERT_EQ(field.status, 0) << field.output;
  EXPECT_EQ(field.output.find("every pixel is traced"), std::string::npos) << field.output;
  std::ifstream statsFile(path("stats.json"));
  const auto stats = nlohmann::json::parse(statsFile);
  const auto masked = stats["masked_pixels"].get<long>();
  std::printf("field: %ld of %d pixels traced, %ld for the emitter's penumbra or the field\n", masked, 48 * 48,
              stats["shadow_edge_pixels"].get<long>());
  EXPECT_LT(masked, 48 * 48 * 3 / 4);
  EXPECT_GT(stats["shadow_edge_pixels"].get<long>(), 0);
  ASSERT_EQ(glint("render " + scene("cornell.json") + " -q --mask all" + small + path("all.png")).status, 0);
  const auto mean = [](const std::vector<std::uint8_t>& rgb) {
    double sum = 0.0;
    for (const std::uint8_t v : rgb) sum += v;
    return sum / static_cast<double>(rgb.size());
  };
  const double withField = mean(decodePng(path("field.png")).rgb), traced = mean(decodePng(path("all.png")).rgb);
  std::printf("mean byte: %.2f with the field, %.2f path traced\n", withField, traced);
  EXPECT_NEAR(withField, traced, 0.05 * traced);

  const Result info = glint("info " + scene("cornell.json") + " --field 8,256 --size 48x48 --samples 16");
  EXPECT_NE(info.output.find("the hybrid frame draws it from an irradiance field (8 probes along the longest side, "
                             "256 rays each)"),
            std::string::npos)
      << info.output;
  EXPECT_NE(info.output.find("hybrid     traces " + std::to_string(masked) + " of 2304 pixels"), std::string::npos)
      << info.output;
  const Result bad = glint("render " + scene("cornell.json") + " --field 8,300 -o " + path("bad.png"));
  EXPECT_EQ(bad.status, 2) << bad.output;
  EXPECT_NE(bad.output.find("--field 8,300: rays must be a power of two"), std::string::npos) << bad.output;
  EXPECT_FALSE(fs::exists(path("bad.png")));
}

// The line after a render and --stats say the same of the frame's paths, a
// mean no longer than the longest, though the room's mirror adds Whitted
// reflection rays beside them.
TEST_F(Cli, ThePathLineAgreesWithTheStats) {
  const Result run = glint("render " + scene("room-path.json") + " --size 64x48 --samples 4 --field 8,64 --stats " +
                           path("stats.json") + " -o " + path("room.png"));
  ASSERT_EQ(run.status, 0) << run.output;
  std::ifstream statsFile(path("stats.json"));
  const auto paths = nlohmann::json::parse(statsFile)["paths"];
  const std::size_t line = run.output.find("paths: ");
  ASSERT_NE(line, std::string::npos) << run.output;
  const double mean = std::stod(run.output.substr(line + 7));
  EXPECT_NEAR(mean, paths["bounces_mean"].get<double>(), 0.005) << run.output;
  EXPECT_LE(mean, paths["bounces_max"].get<double>()) << run.output;
}

// --fit frames every object as the scene's "fit": true does: the same image.
TEST_F(Cli, FitFromTheCommandLineOrTheScene) {
  std::string text = kTwoObjects;
  const std::string far = writeScene("far.json", text.replace(text.find("[0, 1, 6]"), 9, "[0, 10, 60]"));
  ASSERT_EQ(glint("render " + far + " -q -o " + path("option.png") + " --fit").status, 0);
  text.replace(text.find("\"look_at\""), 9, "\"fit\": true, \"look_at\"");
  const std::string fitted = writeScene("fitted.json", text);
  ASSERT_EQ(glint("render " + fitted + " -q -o " + path("scene.png")).status, 0);
  ASSERT_EQ(glint("render " + far + " -q -o " + path("far.png")).status, 0);
  EXPECT_EQ(decodePng(path("option.png")).rgb, decodePng(path("scene.png")).rgb);
  EXPECT_NE(decodePng(path("option.png")).rgb, decodePng(path("far.png")).rgb);
  const Result empty = glint("render " + writeScene("empty.json", R"({"glint": 1, "image": {"width": 8, "height": 8},
    "camera": {"eye": [0, 0, 5], "look_at": [0, 0, 0]}, "objects": []})") + " -o " + path("e.png") + " --fit");
  EXPECT_EQ(empty.status, 1) << empty.output;
  EXPECT_NE(empty.output.find("--fit: the scene has no object to frame"), std::string::npos) << empty.output;
}

// A glTF material's baseColorFactor multiplies its baseColorTexture (it
// was dropped): Debian's textured box with a red factor renders, in the
// full trace and in the hybrid frame (the raster draws the matte box), as
// the box without it in red and black in green and blue.
TEST_F(Cli, BaseColorFactorTimesTheTexture) {
  ASSERT_NO_FATAL_FAILURE(boxVariant("Red", "\"baseColorTexture\"", "\"baseColorFactor\": [1, 0, 0, 1], "));
  for (const char* mask : {"all", "auto"}) {
    const std::string m = std::string(" -q --mask ") + mask + " -o ";
    ASSERT_EQ(glint("render " + boxScene("BoxTextured") + m + path("plain.png")).status, 0);
    ASSERT_EQ(glint("render " + boxScene("Red") + m + path("red.png")).status, 0);
    const Image plain = decodePng(path("plain.png")), red = decodePng(path("red.png"));
    std::size_t box = 0;
    for (std::size_t i = 0; i < plain.rgb.size(); i += 3) {
      if (plain.rgb[i] == 0 && plain.rgb[i + 1] == 0 && plain.rgb[i + 2] == 0) continue;  // the black background
      ++box;
      EXPECT_EQ(red.rgb[i], plain.rgb[i]) << mask << " at " << i / 3;
      EXPECT_EQ(red.rgb[i + 1], 0) << mask << " at " << i / 3;
      EXPECT_EQ(red.rgb[i + 2], 0) << mask << " at " << i / 3;
    }
    EXPECT_GT(box, 1000u) << mask;
  }
}

// A material's emission (times its emission texture) is light of its own:
// on the panel that has it, every renderer (the full trace, the raster
// alone, the hybrid frame) adds exactly emission x texel to the pixels of
// the panel without it, and not one other pixel changes (it lights nothing).
// Linear bytes, so that light adds as bytes do.
TEST_F(Cli, EmissionAddsToItsSurfaceOnly) {
  std::ofstream(path("glow.png"), std::ios::binary) << glint::test::flatPng(2, 2);  // texels 200 / 255
  const auto sceneWith = [&](const std::string& name, const std::string& emission) {
    return writeScene(name, R"({"glint": 1, "image": {"width": 64, "height": 48, "encoding": "linear"},
      "camera": {"eye": [0, 0.5, 5], "look_at": [0, 0, 0]}, "background": [0, 0, 0.2],
      "textures": {"glow": {"type": "image", "file": "glow.png"}},
      "materials": {"panel": {"color": [0.4, 0.4, 0.4], "ambient": 0.1)" + emission + R"(},
                    "floor": {"color": [0.8, 0.8, 0.8], "ambient": 0.1}},
      "lights": [{"type": "point", "position": [2, 3, 4]}],
      "objects": [{"type": "quad", "corners": [[-1, -0.5, 0], [1, -0.5, 0], [1, 1, 0], [-1, 1, 0]],
                   "uvs": [[0, 0], [1, 0], [1, 1], [0, 1]], "material": "panel"},
                  {"type": "quad", "corners": [[-4, -1, -4], [4, -1, -4], [4, -1, 4], [-4, -1, 4]],
                   "material": "floor"}]})");
  };
  const std::string plain = sceneWith("plain.json", "");
  const std::string glowing = sceneWith("glow.json", R"(, "emission": [0.6, 0.3, 0], "emission_texture": "glow")");
  for (const char* mask : {"all", "none", "auto"}) {
    const std::string m = std::string(" -q --mask ") + mask + " -o ";
    ASSERT_EQ(glint("render " + plain + m + path("plain.png")).status, 0);
    ASSERT_EQ(glint("render " + glowing + m + path("glow.png.out.png")).status, 0);
    const Image before = decodePng(path("plain.png")), after = decodePng(path("glow.png.out.png"));
    ASSERT_EQ(before.rgb.size(), after.rgb.size());
    std::size_t panel = 0, unchanged = 0;
    for (std::size_t i = 0; i < before.rgb.size(); i += 3) {
      const int dr = after.rgb[i] - before.rgb[i], dg = after.rgb[i + 1] - before.rgb[i + 1];
      const int db = after.rgb[i + 2] - before.rgb[i + 2];
      if (dr == 0 && dg == 0 && db == 0) {
        ++unchanged;
        continue;
      }
      ++panel;  // 0.6 x 200 = 120 and 0.3 x 200 = 60, each within the rounding of a sum
      EXPECT_TRUE(std::abs(dr - 120) <= 1 && std::abs(dg - 60) <= 1 && db == 0)
          << mask << " at " << i / 3 << ": " << dr << " " << dg << " " << db;
    }
    EXPECT_GT(panel, 300u) << mask;
    EXPECT_GT(unchanged, 2000u) << mask;
  }
}

// A glTF material's emissiveFactor times its emissiveTexture is the
// emission: Debian's textured box emitting its own texture in red adds
// light to red alone, the same in the full trace and the hybrid frame, and
// through a server (the imported material travels with the mesh).
TEST_F(Cli, GltfEmissionAsAuthored) {
  ASSERT_NO_FATAL_FAILURE(boxVariant("Glow", "\"name\": \"Texture\"",
                                     "\"emissiveFactor\": [0.5, 0, 0], \"emissiveTexture\": {\"index\": 0}, "));
  glint::server::test::GlintdProcess server({"--threads", "1"});
  std::vector<int> redAdded[2];
  for (const char* mask : {"all", "auto"}) {
    const std::string m = std::string(" -q --mask ") + mask + " -o ";
    ASSERT_EQ(glint("render " + boxScene("BoxTextured") + m + path("plain.png")).status, 0);
    ASSERT_EQ(glint("render " + boxScene("Glow") + m + path("glow.png")).status, 0);
    ASSERT_EQ(glint("render " + boxScene("Glow") + m + path("served.png") + " --server " + server.address()).status, 0);
    const Image plain = decodePng(path("plain.png")), glow = decodePng(path("glow.png"));
    EXPECT_EQ(decodePng(path("served.png")).rgb, glow.rgb) << mask;
    std::vector<int>& added = redAdded[mask[0] == 'a' && mask[1] == 'l' ? 0 : 1];
    for (std::size_t i = 0; i < plain.rgb.size(); i += 3) {
      added.push_back(glow.rgb[i] - plain.rgb[i]);
      EXPECT_EQ(glow.rgb[i + 1], plain.rgb[i + 1]) << mask << " at " << i / 3;
      EXPECT_EQ(glow.rgb[i + 2], plain.rgb[i + 2]) << mask << " at " << i / 3;
    }
  }
  std::size_t glowing = 0, apart = 0;  // apart: the two frames disagree (a texel's edge, a silhouette)
  for (std::size_t i = 0; i < redAdded[0].size(); ++i) {
    apart += std::abs(redAdded[0][i] - redAdded[1][i]) > 2 ? 1 : 0;
    EXPECT_GE(redAdded[0][i], 0) << "at " << i;
    glowing += redAdded[0][i] > 20 ? 1 : 0;
  }
  EXPECT_GT(glowing, 1000u);
  EXPECT_LE(apart, glowing / 100);
}

// KHR_texture_transform as the extension's example has it: offset (0, 1),
// rotation 90 degrees, scale 0.5 show the lower left quarter of the image
// turned clockwise. A quad made here (uv (0, 0) at its top left, as glTF
// has it) with a 4 x 4 image whose lower left quarter is red, green / blue,
// white (the rest black) shows blue, red / white, green in its quarters, in
// the full trace, the raster and through a server, with no warning about
// the extension.
TEST_F(Cli, GltfTextureTransformAsTheExtensionSays) {
  glint::FrameImage grid{4, 4, std::vector<std::uint8_t>(48, 0)};
  const auto paint = [&grid](int x, int y, int r, int g, int b) {
    const std::size_t at = static_cast<std::size_t>(3 * (y * 4 + x));
    grid.rgb[at] = static_cast<std::uint8_t>(r), grid.rgb[at + 1] = static_cast<std::uint8_t>(g);
    grid.rgb[at + 2] = static_cast<std::uint8_t>(b);
  };
  paint(0, 2, 255, 0, 0), paint(1, 2, 0, 255, 0), paint(0, 3, 0, 0, 255), paint(1, 3, 255, 255, 255);
  glint::writePng(dir_ / "grid.png", grid, glint::Encoding::kSrgb);
  const float positions[] = {-1, 1, 0, 1, 1, 0, -1, -1, 0, 1, -1, 0};
  const float uvs[] = {0, 0, 1, 0, 0, 1, 1, 1};
  const std::uint16_t indices[] = {0, 2, 1, 1, 2, 3};
  std::ofstream bin(dir_ / "quad.bin", std::ios::binary);
  bin.write(reinterpret_cast<const char*>(positions), sizeof positions);
  bin.write(reinterpret_cast<const char*>(uvs), sizeof uvs);
  bin.write(reinterpret_cast<const char*>(indices), sizeof indices);
  bin.close();
  std::ofstream(dir_ / "quad.gltf") << R"({"asset": {"version": "2.0"}, "extensionsUsed": ["KHR_texture_transform"],
    "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
    "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "TEXCOORD_0": 1}, "indices": 2, "material": 0}]}],
    "materials": [{"pbrMetallicRoughness": {"metallicFactor": 0, "baseColorTexture": {"index": 0,
      "extensions": {"KHR_texture_transform": {"offset": [0, 1], "rotation": 1.5707963267948966, "scale": [0.5, 0.5]}}}}}],
    "textures": [{"source": 0}], "images": [{"uri": "grid.png"}],
    "buffers": [{"uri": "quad.bin", "byteLength": 92}],
    "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 48}, {"buffer": 0, "byteOffset": 48, "byteLength": 32},
                    {"buffer": 0, "byteOffset": 80, "byteLength": 12}],
    "accessors": [{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [-1, -1, 0], "max": [1, 1, 0]},
                  {"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC2"},
                  {"bufferView": 2, "componentType": 5123, "count": 6, "type": "SCALAR"}]})";
  const std::string scene = writeScene("quad.json", R"({"glint": 1, "image": {"width": 64, "height": 64},
    "camera": {"eye": [0, 0, 3], "look_at": [0, 0, 0]}, "lights": [{"type": "point", "position": [0, 0, 3]}],
    "objects": [{"type": "mesh", "file": "quad.gltf"}]})");
  glint::server::test::GlintdProcess server({"--threads", "1"});
  for (const std::string& options :
       std::vector<std::string>{"--mask all", "--mask none", "--mask all --server " + server.address()}) {
    const Result run = glint("render " + scene + " " + options + " -o " + path("quad.png"));
    ASSERT_EQ(run.status, 0) << run.output;
    EXPECT_EQ(run.output.find("KHR_texture_transform"), std::string::npos) << run.output;
    const Image image = decodePng(path("quad.png"));
    // The quarters' centres, 0.5 from the middle: 12.9 pixels at this distance and field of view.
    const auto colour = [&image](int x, int y) {
      const std::size_t at = static_cast<std::size_t>(3 * (y * 64 + x));
      const auto on = [&](int k) { return image.rgb[at + static_cast<std::size_t>(k)] > 40 ? 1 : 0; };
      return on(0) * 4 + on(1) * 2 + on(2);  // 4 red, 2 green, 1 blue, 7 white
    };
    EXPECT_EQ(colour(19, 19), 1) << options << ": top left, blue";
    EXPECT_EQ(colour(45, 19), 4) << options << ": top right, red";
    EXPECT_EQ(colour(19, 45), 7) << options << ": bottom left, white";
    EXPECT_EQ(colour(45, 45), 2) << options << ": bottom right, green";
  }
}

// A mesh's vertex colours multiply its colour, blended across each
// triangle: a PLY (an OBJ, a glTF's COLOR_0) quad red on its left edge and blue on its right shows, in
// every pixel, red and blue adding up to the uncoloured quad's value (the
// light is the same; the colour is a linear blend), red falling from left
// to right, in the full trace, the raster and through a server (linear
// bytes, so that the blend adds as bytes do).
TEST_F(Cli, VertexColorsBlendAcrossTheMesh) {
  const auto ply = [&](const std::string& name, bool colored) {
    std::ofstream out(path(name));
    out << "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
        << (colored ? "property uchar red\nproperty uchar green\nproperty uchar blue\n" : "")
        << "element face 2\nproperty list uchar int vertex_indices\nend_header\n";
    const char* corners[] = {"-1 1 0", "1 1 0", "1 -1 0", "-1 -1 0"};
    for (int i = 0; i < 4; ++i)
      out << corners[i] << (!colored ? "" : i == 1 || i == 2 ? " 0 0 255" : " 255 0 0") << "\n";
    out << "3 0 3 2\n3 0 2 1\n";
  };
  ply("plain.ply", false);
  ply("colored.ply", true);
  const auto obj = [&](const std::string& name, bool colored) {
    std::ofstream out(path(name));
    const char* corners[] = {"-1 1 0", "1 1 0", "1 -1 0", "-1 -1 0"};
    for (int i = 0; i < 4; ++i)
      out << "v " << corners[i] << (!colored ? "" : i == 1 || i == 2 ? " 0 0 1" : " 1 0 0") << "\n";
    out << "f 1 4 3\nf 1 3 2\n";
  };
  obj("plain.obj", false);
  obj("colored.obj", true);
  const float positions[] = {-1, 1, 0, 1, 1, 0, 1, -1, 0, -1, -1, 0};
  const float colors[] = {1, 0, 0, 0, 0, 1, 0, 0, 1, 1, 0, 0};
  const std::uint16_t indices[] = {0, 3, 2, 0, 2, 1};
  std::ofstream bin(path("quad.bin"), std::ios::binary);
  bin.write(reinterpret_cast<const char*>(positions), sizeof positions);
  bin.write(reinterpret_cast<const char*>(colors), sizeof colors);
  bin.write(reinterpret_cast<const char*>(indices), sizeof indices);
  bin.close();
  const auto gltf = [&](const std::string& name, bool colored) {
    std::ofstream(path(name)) << R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
      "nodes": [{"mesh": 0}], "meshes": [{"primitives": [{"attributes": {"POSITION": 0)"
                              << (colored ? R"(, "COLOR_0": 1)" : "") << R"(}, "indices": 2}]}],
      "buffers": [{"uri": "quad.bin", "byteLength": 108}],
      "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 48}, {"buffer": 0, "byteOffset": 48, "byteLength": 48},
                      {"buffer": 0, "byteOffset": 96, "byteLength": 12}],
      "accessors": [{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [-1, -1, 0], "max": [1, 1, 0]},
                    {"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC3"},
                    {"bufferView": 2, "componentType": 5123, "count": 6, "type": "SCALAR"}]})";
  };
  gltf("plain.gltf", false);
  gltf("colored.gltf", true);
  const auto sceneOf = [&](const std::string& file) {
    return writeScene(file + ".json", R"({"glint": 1, "image": {"width": 64, "height": 64, "encoding": "linear"},
      "camera": {"eye": [0, 0, 3], "look_at": [0, 0, 0]}, "lights": [{"type": "point", "position": [0.5, 0.5, 3]}],
      "objects": [{"type": "mesh", "file": ")" +
                                          file + R"("}]})");
  };
  glint::server::test::GlintdProcess server({"--threads", "1"});
  for (const std::string& format : {std::string("ply"), std::string("obj"), std::string("gltf")}) {
    const std::string plainScene = sceneOf("plain." + format), coloredScene = sceneOf("colored." + format);
    for (const std::string& options :
         std::vector<std::string>{"--mask all", "--mask none", "--mask all --server " + server.address()}) {
      ASSERT_EQ(glint("render " + plainScene + " -q " + options + " -o " + path("plain.png")).status, 0);
      ASSERT_EQ(glint("render " + coloredScene + " -q " + options + " -o " + path("colored.png")).status, 0);
      const Image plain = decodePng(path("plain.png")), colored = decodePng(path("colored.png"));
      std::size_t quad = 0;
      for (std::size_t i = 0; i < plain.rgb.size(); i += 3) {
        if (plain.rgb[i] == 0) continue;  // the background
        ++quad;
        EXPECT_LE(std::abs(colored.rgb[i] + colored.rgb[i + 2] - plain.rgb[i]), 2) << options << " at " << i / 3;
        EXPECT_EQ(colored.rgb[i + 1], 0) << options << " at " << i / 3;
      }
      EXPECT_GT(quad, 1500u) << options;
      const auto red = [&colored](int x) { return colored.rgb[static_cast<std::size_t>(3 * (32 * 64 + x))]; };
      const auto blue = [&colored](int x) { return colored.rgb[static_cast<std::size_t>(3 * (32 * 64 + x)) + 2]; };
      EXPECT_GT(red(12), 3 * blue(12)) << options;
      EXPECT_GT(blue(51), 3 * red(51)) << options;
      EXPECT_LE(std::abs(red(32) - blue(32)), 0.1 * red(32) + 2) << options;
    }
  }
}

// --gl picks the headless OpenGL; each gives the same image (and info
// names the one it ran on); a backend glint does not know is a usage error.
TEST_F(Cli, GlBackendsGiveTheSameImage) {
  const std::string room = scene("room.json") + " --size 160x120";
  for (const char* backend : {"egl", "osmesa"}) {
    const Result run = glint("render " + room + " -q -o " + path(std::string(backend) + ".png") + " --gl " + backend);
    ASSERT_EQ(run.status, 0) << backend << ": " << run.output;
    const Result info = glint("info " + room + " --gl " + backend);
    EXPECT_NE(info.output.find(std::string("(OpenGL: ") + backend + ")"), std::string::npos) << info.output;
  }
  EXPECT_EQ(decodePng(path("egl.png")).rgb, decodePng(path("osmesa.png")).rgb);
  EXPECT_EQ(glint("render " + room + " -o " + path("x.png") + " --gl vulkan").status, 2);
}

// A scene with comments renders as the same scene without them; --eye,
// --look-at, --up and --fov render as a scene file with that camera.
TEST_F(Cli, CommentsAndCameraOverrides) {
  std::ifstream in(scene("glass.json"));
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const auto write = [this](const std::string& name, const std::string& content) {
    std::ofstream(path(name)) << content;
    return path(name);
  };
  std::string commented = "// glass spheres\n/* with a comment block */\n" + text;
  commented.insert(commented.find("\"camera\""), "/* the camera: */ ");
  const std::string args = " --size 64x48 -q --mask all";
  ASSERT_EQ(glint("render " + scene("glass.json") + " -o " + path("plain.png") + args).status, 0);
  ASSERT_EQ(glint("render " + write("commented.json", commented) + " -o " + path("commented.png") + args).status, 0);
  EXPECT_EQ(decodePng(path("commented.png")).rgb, decodePng(path("plain.png")).rgb);

  std::string moved = text;
  const std::string camera = R"("eye": [0, 1.4, 5], "look_at": [0, 0.9, 0], "up": [0, 1, 0], "fov_y": 45)";
  ASSERT_NE(moved.find(camera), std::string::npos);
  moved.replace(moved.find(camera), camera.size(),
                R"("eye": [1, 2, 4], "look_at": [0, 0.5, 0], "up": [0, 1, 0.1], "fov_y": 30)");
  ASSERT_EQ(glint("render " + write("moved.json", moved) + " -o " + path("moved.png") + args).status, 0);
  ASSERT_EQ(glint("render " + scene("glass.json") + " -o " + path("flag.png") + args +
                  " --eye 1,2,4 --look-at 0,0.5,0 --up 0,1,0.1 --fov 30")
                .status,
            0);
  EXPECT_EQ(decodePng(path("flag.png")).rgb, decodePng(path("moved.png")).rgb);
  EXPECT_NE(decodePng(path("flag.png")).rgb, decodePng(path("plain.png")).rgb);
}

// --crop renders the window of the frame: the same pixels as that window of
// the whole frame, hybrid and full trace; the stats name the window.
TEST_F(Cli, CropIsTheWindowOfTheWholeFrame) {
  for (const std::string mask : {"auto", "all"}) {
    const std::string args = " --size 96x64 -q --mask " + mask;
    ASSERT_EQ(glint("render " + scene("room.json") + " -o " + path("whole.png") + args).status, 0);
    const Result run = glint("render " + scene("room.json") + " -o " + path("crop.png") + args +
                             " --crop 10,5,70,41 --stats " + path("stats.json"));
    ASSERT_EQ(run.status, 0) << run.output;
    const Image whole = decodePng(path("whole.png")), crop = decodePng(path("crop.png"));
    ASSERT_EQ(crop.width, 60);
    ASSERT_EQ(crop.height, 36);
    for (int y = 0; y < crop.height; ++y) {
      for (int x = 0; x < crop.width * 3; ++x) {
        const std::size_t w = static_cast<std::size_t>((y + 5) * whole.width * 3 + 30 + x);
        ASSERT_EQ(crop.rgb[static_cast<std::size_t>(y * crop.width * 3 + x)], whole.rgb[w])
            << mask << " " << x / 3 << "," << y;
      }
    }
    std::ifstream stats(path("stats.json"));
    const std::string line((std::istreambuf_iterator<char>(stats)), std::istreambuf_iterator<char>());
    EXPECT_NE(line.find("\"crop\":[10,5,70,41]"), std::string::npos) << line;
  }
}

// A model file opens as it is, in the default scene around it, under either
// transport: the model fills part of the frame, not all of it, and is lit;
// an OBJ or PLY gets the light rig, a glTF file with a camera its camera.
// Through glintd the frame is the in-process bytes. A file that is neither
// a scene nor a model says what Glint reads.
TEST_F(Cli, AModelFileOpensAsItIs) {
  const std::string models = "/usr/share/assimp/models/";
  ASSERT_TRUE(fs::exists(models + "OBJ/WusonOBJ.obj")) << "install assimp-testmodels (make deps)";
  for (const char* model : {"glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb",
                            "glTF2/BoxTextured-glTF/BoxTextured.gltf", "OBJ/WusonOBJ.obj", "PLY/Wuson.ply"}) {
    for (const char* transport : {"whitted", "path"}) {
      const std::string png = path("model.png");
      const Result r = glint("render " + models + model + " -q --size 64x48 --samples 2 --transport " + transport +
                             " -o " + png);
      ASSERT_EQ(r.status, 0) << model << ": " << r.output;
      const Image image = decodePng(png);
      const std::uint8_t* corner = image.rgb.data();  // the background
      std::size_t shown = 0, lit = 0;
      for (std::size_t i = 0; i < image.rgb.size(); i += 3) {
        const bool background = std::equal(corner, corner + 3, image.rgb.data() + i);
        shown += !background;
        lit += !background && image.rgb[i] + image.rgb[i + 1] + image.rgb[i + 2] > 3 * 120;
      }
      const std::size_t pixels = image.rgb.size() / 3;
      EXPECT_GT(shown, pixels / 20) << model << " " << transport;
      EXPECT_LT(shown, pixels) << model << " " << transport;
      EXPECT_GT(lit, shown / 4) << model << " " << transport;
    }
  }
  const Result obj = glint("info " + models + "OBJ/WusonOBJ.obj --no-raster");
  EXPECT_NE(obj.output.find("3 lights"), std::string::npos) << obj.output;
  const Result glb = glint("info " + models + "glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb --no-raster");
  EXPECT_NE(glb.output.find("image      480x480"), std::string::npos) << glb.output;  // its camera's aspect, 1

  glint::server::test::GlintdProcess glintd;
  const std::string box = models + "glTF2/BoxTextured-glTF/BoxTextured.gltf --size 48x36 -q -o ";
  ASSERT_EQ(glint("render " + box + path("here.png")).status, 0);
  ASSERT_EQ(glint("render " + box + path("there.png") + " --server " + glintd.address()).status, 0);
  EXPECT_EQ(decodePng(path("here.png")).rgb, decodePng(path("there.png")).rgb);

  std::ofstream(path("notes.txt")) << "not a scene\n";
  const Result neither = glint("render " + path("notes.txt") + " -o " + path("n.png"));
  EXPECT_EQ(neither.status, 1);
  EXPECT_EQ(neither.output, "glint: error: " + path("notes.txt") +
                                ": neither a Glint scene (JSON, docs/scene-format.md) nor a model file Glint opens "
                                "(.gltf, .glb, .obj, .ply)\n");
  EXPECT_FALSE(fs::exists(path("n.png")));
}

// .pfm and .exr of the in-process full trace hold the tracer's floats (the
// PNG's bytes are their rounding).
TEST_F(Cli, FloatOutputsHoldTheFrame) {
  const std::string args = " --size 48x32 -q --mask all";
  ASSERT_EQ(glint("render " + scene("room.json") + " -o " + path("room.png") + args).status, 0);
  ASSERT_EQ(glint("render " + scene("room.json") + " -o " + path("room.pfm") + args).status, 0);
  ASSERT_EQ(glint("render " + scene("room.json") + " -o " + path("room.exr") + args).status, 0);
  const Image png = decodePng(path("room.png"));
  std::ifstream pfm(path("room.pfm"), std::ios::binary);
  std::string header[4];
  pfm >> header[0] >> header[1] >> header[2] >> header[3];
  pfm.get();
  EXPECT_EQ(header[0] + " " + header[1] + " " + header[2] + " " + header[3], "PF 48 32 -1.0");
  std::vector<float> values(48 * 32 * 3);
  pfm.read(reinterpret_cast<char*>(values.data()), static_cast<std::streamsize>(values.size() * sizeof(float)));
  ASSERT_TRUE(pfm);
  for (int y = 0; y < 32; ++y) {  // PFM rows run bottom-up
    for (int i = 0; i < 48 * 3; ++i) {
      const float v = values[static_cast<std::size_t>((31 - y) * 48 * 3 + i)];
      ASSERT_EQ(glint::toByte(v), png.rgb[static_cast<std::size_t>(y * 48 * 3 + i)]) << i / 3 << "," << y;
    }
  }
  EXPECT_GT(fs::file_size(path("room.exr")), 100u);
}

// A float output of a hybrid frame holds linear light whatever the 8-bit
// encoding: the PNG's values decoded (a .pfm exactly, an .exr to half
// precision), and the same light under srgb and linear within their 8-bit
// rounding.
TEST_F(Cli, AHybridFramesFloatOutputsHoldLinearLight) {
  double mean[2] = {};
  for (const glint::Encoding encoding : {glint::Encoding::kSrgb, glint::Encoding::kLinear}) {
    const std::string name = encoding == glint::Encoding::kSrgb ? "srgb" : "linear";
    const std::string args = " --size 48x32 -q --encoding " + name + " -o " + path(name);
    for (const char* extension : {".png", ".pfm", ".exr"}) {
      ASSERT_EQ(glint("render " + scene("room.json") + args + extension).status, 0) << extension;
    }
    const glint::ImageFile png = glint::readImageFile(path(name + ".png"));
    const glint::ImageFile pfm = glint::readImageFile(path(name + ".pfm"));
    const glint::ImageFile exr = glint::readImageFile(path(name + ".exr"));
    ASSERT_EQ(pfm.values.rgb.size(), png.values.rgb.size());
    ASSERT_EQ(exr.values.rgb.size(), png.values.rgb.size());
    const glint::Encoder encoder(glint::OutputSettings{.encoding = encoding});
    for (std::size_t i = 0; i < png.values.rgb.size(); ++i) {
      const auto byte = static_cast<std::uint8_t>(std::lround(png.values.rgb[i] * 255.0f));
      ASSERT_EQ(pfm.values.rgb[i], encoder.decoded(byte)) << i;
      ASSERT_NEAR(exr.values.rgb[i], encoder.decoded(byte), 1e-3f * (1.0f + encoder.decoded(byte))) << i;
      mean[encoding == glint::Encoding::kSrgb] += pfm.values.rgb[i] / static_cast<double>(png.values.rgb.size());
    }
  }
  EXPECT_NEAR(mean[1], mean[0], 0.01 * mean[0]);
}

TEST_F(Cli, ViewWithoutADisplaySaysSo) {
  const Result run = glint("view " + scene("room.json") + " --frames 1", "env -u DISPLAY -u WAYLAND_DISPLAY ");
  EXPECT_EQ(run.status, 1);
  EXPECT_NE(run.output.find("needs a display"), std::string::npos) << run.output;
}

TEST_F(Cli, BadValuesGiveClearErrorsAndWriteNothing) {
  const std::string out = " -o " + path("x.png");
  const std::string room = scene("room.json");
  struct Case {
    std::string args;
    std::string message;
  };
  const Case cases[] = {
      {"render " + room + out + " --mask all --threads -1", "--threads"},
      {"render " + room + out + " --mask all --samples 0", "--samples"},
      {"render " + room + out + " --mask all --samples 3 --pattern regular", "--samples 3"},
      {"render " + room + out + " --mask all --filter lanczos", "--filter"},
      {"render " + room + out + " --mask all --size 0x10", "--size 0x10"},
      {"render " + room + out + " --mask all --size big", "--size big"},
      {"render " + room + out + " --mask all --min-weight 2", "--min-weight"},
      {"render " + room + out + " --mask sometimes", "--mask"},
      {"render " + room + out + " --mask auto --mask-threshold 1.5", "--mask-threshold"},
      {"render " + path("missing.json") + out + " --mask all", "missing.json"},
      {"render " + room + " --mask all", "--output"},
      {"render " + room + " -o " + path("no/such/folder/x.png") + " --mask all --size 8x8", "no/such/folder"},
      {"render " + room + out + " --mask all --server 127.0.0.1:1", "server 127.0.0.1:1: unreachable, cannot connect"},
      {"render " + room + out + " --mask all --bvh qsplit --server 127.0.0.1:1", "--bvh: a glintd builds"},
      {"render " + room + out + " --mask all --server nowhere", "--server nowhere: expected HOST:PORT"},
      {"render " + room + " -o " + path("x.jpg") + " --mask all",
       "-o " + path("x.jpg") + ": glint writes .png, .exr, .pfm"},
      {"render " + room + out + " --mask-out " + path("m.exr"),
       "--mask-out " + path("m.exr") + ": this image is 8-bit"},
      {"render " + room + out + " --crop 0,0,641,10",
       "--crop 0,0,641,10: the window must lie inside the 640x480 frame"},
      {"render " + room + out + " --crop 10,10,10,20", "--crop 10,10,10,20: X1 must be above X0"},
      {"render " + room + out + " --crop 1,2,3", "--crop 1,2,3: expected X0,Y0,X1,Y1"},
      {"render " + room + out + " --exposure 40", "--exposure"},
      {"render " + room + out + " --encoding gamma", "--encoding"},
      {"render " + room + out + " --mask all --mask-out " + path("nowhere/m.png"), "nowhere does not exist"},
      {"render " + room + out + " --mask all --size 100000x100000", "width and height must be in [1, 65536]"},
      {"render " + room + out + " --mask all --eye 1,2", "--eye 1,2: expected X,Y,Z"},
      {"render " + room + out + " --mask all --eye 1e999,0,0", "--eye 1e999,0,0: expected X,Y,Z"},
  };
  for (const Case& c : cases) {
    const Result run = glint(c.args);
    EXPECT_NE(run.status, 0) << c.args;
    EXPECT_NE(run.output.find(c.message), std::string::npos) << c.args << "\n" << run.output;
    EXPECT_FALSE(fs::exists(path("x.png"))) << c.args;
  }
  EXPECT_TRUE(fs::is_empty(dir_));
}

TEST_F(Cli, BadSceneNamesTheJsonPathAndWritesNothing) {
  const std::string bad = writeScene("bad.json", R"({"glint": 1, "image": {"width": 4, "height": 4},
        "camera": {"eye": [0, 0, 5], "look_at": [0, 0, 0]}, "materials": {"m": {}},
        "objects": [{"type": "sphere", "center": [0, 0, 0], "radius": -1, "material": "m"}]})");
  const Result run = glint("render " + bad + " -o " + path("x.png") + " --mask all");
  EXPECT_EQ(run.status, 1);
  EXPECT_NE(run.output.find("bad.json: objects[0].radius: must be > 0"), std::string::npos) << run.output;
  EXPECT_FALSE(fs::exists(path("x.png")));

  const std::string truncated = writeScene("cut.json", R"({"glint": 1, "image": {"wid)");
  const Result cut = glint("render " + truncated + " -o " + path("x.png") + " --mask all");
  EXPECT_EQ(cut.status, 1);
  EXPECT_NE(cut.output.find("not valid JSON"), std::string::npos) << cut.output;
  EXPECT_FALSE(fs::exists(path("x.png")));
}

}  // namespace

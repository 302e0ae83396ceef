#include "tests/bench/mesh_file_section.h"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <stdexcept>
#include <string>
#include <vector>

#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <tiny_obj_loader.h>

#include "common/base/file_source.h"
#include "common/scene/obj_load.h"
#include "common/base/timing.h"
#include "tests/bench/bench_timing.h"
#include "tests/bench/bench_scenes.h"
#include "tests/support/glint_run.h"

namespace glint::bench {
namespace {

namespace fs = std::filesystem;

// The bench's rippled sphere as an OBJ file (one-based indices).
void writeSphere(const fs::path& path, int n) {
  const MeshInput sphere = rippledSphere(n);
  std::ofstream out(path);
  char line[96];
  for (const glm::vec3& p : sphere.positions) {
    std::snprintf(line, sizeof line, "v %.6f %.6f %.6f\n", p.x, p.y, p.z);
    out << line;
  }
  for (std::size_t i = 0; i < sphere.indices.size(); i += 3) {
    out << "f " << sphere.indices[i] + 1 << ' ' << sphere.indices[i + 1] + 1 << ' ' << sphere.indices[i + 2] + 1
        << '\n';
  }
}

// `glint render`'s load_ms for a scene of the one mesh: the command users
// run, a fresh process each time (its memory is new to it, as a user's is).
double commandLoadMs(const fs::path& dir) {
  std::ofstream(dir / "scene.json") << R"({"glint": 1, "image": {"width": 8, "height": 8},
    "camera": {"eye": [0, 0, 4], "look_at": [0, 0, 0]}, "objects": [{"type": "mesh", "file": "sphere.obj"}]})";
  const fs::path stats = dir / "stats.json";
  const test::GlintRun run = test::runGlint("render " + (dir / "scene.json").string() + " -q --mask all -o " +
                                            (dir / "out.png").string() + " --stats " + stats.string());
  std::ifstream in(stats);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::size_t at = text.find("\"load_ms\":");
  if (run.status != 0 || at == std::string::npos) throw std::runtime_error("glint render failed: " + run.output);
  return std::strtod(text.c_str() + at + 10, nullptr);
}

}  // namespace

void meshFileSection(bool quick, int runs) {
  const int n = quick ? 100 : 700;
  const fs::path dir = fs::temp_directory_path() / "glint-bench-meshfile";
  fs::create_directories(dir);
  writeSphere(dir / "sphere.obj", n);
  const auto bytes = fs::file_size(dir / "sphere.obj");
  std::size_t triangles = 0;
  const double glint = medianMs(runs, [&] {
    DirectorySource files(dir, std::size_t{1} << 30);
    SceneBudget budget;
    triangles = loadObj(files, "sphere.obj", "bench", budget, true).meshes.at(0).indices.size() / 3;
  });
  const double parse = medianMs(runs, [&] {
    tinyobj::ObjReaderConfig config;
    config.triangulate = true;
    tinyobj::ObjReader reader;
    reader.ParseFromFile((dir / "sphere.obj").string(), config);
  });
  std::vector<double> loads;
  for (int r = 0; r < runs; ++r) loads.push_back(commandLoadMs(dir));
  const double command = median(loads);
  const double assimp = medianMs(runs, [&] {
    Assimp::Importer importer;
    importer.ReadFile((dir / "sphere.obj").string(), aiProcess_Triangulate);
  });
  std::printf("\n## Reading a mesh file: %zu triangles, %.1f MB OBJ, median of %d\n\n", triangles,
              static_cast<double>(bytes) / 1e6, runs);
  std::printf("| reader | ms | Glint's / this |\n|---|---:|---:|\n");
  std::printf("| Glint loadObj (callback parse in pieces at once + vertices grouped), in this process | %.0f | 1.00 |\n",
              glint);
  std::printf("| `glint render`'s load_ms (a fresh process: the command users run) | %.0f | %.2f |\n", command,
              glint / command);
  std::printf("| tinyobjloader LoadObj alone (its shapes) | %.0f | %.2f |\n", parse, glint / parse);
  std::printf("| Assimp 5.2, triangulate (a vertex per corner) | %.0f | %.2f |\n", assimp, glint / assimp);
  fs::remove_all(dir);
}

}  // namespace glint::bench

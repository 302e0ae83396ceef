// Writes the fuzzers' seed corpora (tests/fuzz/corpus/TARGET/NAME) with the
// project's own encoders and from scenes/: `glint-fuzz-seeds SOURCE_DIR`.
// The corpora are kept in the tree; run `make fuzz-seeds` after a change to
// the protocol or the scene format.
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include <OpenEXR/ImfArray.h>
#include <OpenEXR/ImfRgbaFile.h>
#include <OpenEXR/ImfTiledRgbaFile.h>
#include <stb_image_write.h>

#include "common/render/frame.h"
#include "common/render/irradiance_field.h"
#include "common/image/image_write.h"
#include "common/scene/mesh_blob.h"
#include "common/scene/obj_load.h"
#include "proto/messages.h"
#include "proto/scene_bundle.h"
#include "tests/fuzz/fuzz_files.h"
#include "tests/fuzz/server_link_script.h"
#include "tests/support/full_upload.h"
#include "tests/support/hostile_frames.h"
#include "tests/support/hostile_images.h"

namespace {

using namespace glint;
namespace fs = std::filesystem;
using Bytes = std::vector<std::uint8_t>;

fs::path gRoot;

void write(const std::string& target, const std::string& name, const std::string& bytes) {
  const fs::path dir = gRoot / "tests/fuzz/corpus" / target;
  fs::create_directories(dir);
  std::ofstream(dir / name, std::ios::binary) << bytes;
}

void write(const std::string& target, const std::string& name, const Bytes& bytes) {
  write(target, name, std::string(bytes.begin(), bytes.end()));
}

std::string readFile(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

Bytes join(const std::vector<Bytes>& frames) {
  Bytes out;
  for (const Bytes& f : frames) out.insert(out.end(), f.begin(), f.end());
  return out;
}

// A whole client session: Hello, the scene, a small frame, tiles, Goodbye.
Bytes session(const proto::SceneBundle& bundle, FrameSettings frame) {
  frame.width = 16;
  frame.height = 8;
  frame.sampling.samples = 1;
  frame.sampling.pattern = SamplePattern::kRegular;
  const proto::SceneHash hash = bundle.hash();
  std::vector<std::uint8_t> mask(maskByteCount({0, 0, 8, 8}), 0x5a);
  std::vector<Bytes> frames{proto::encodeHello(1 << 20, 0, "seed"),
                            proto::encodeSceneQuery(hash, proto::digest(bundle).files)};
  for (Bytes& f : proto::encodeFullUpload(bundle, 2048)) frames.push_back(std::move(f));  // files in pieces
  for (Bytes f : {proto::encodeFrameSetup(1, hash, frame), proto::encodeTileRequest(1, 0, {0, 0, 8, 8}, {}),
                  proto::encodeTileRequest(1, 1, {8, 0, 8, 8}, mask), proto::encodeCancel(1, std::vector<std::uint32_t>{1}),
                  proto::encodeCancel(1, {}), proto::encodeGoodbye()}) {
    frames.push_back(std::move(f));
  }
  return join(frames);
}

void framingSeeds(const proto::SceneBundle& bundle, const FrameSettings& frame) {
  const proto::SceneHash hash = bundle.hash();
  write("framing", "hello", proto::encodeHello(1 << 20, 2, "seed"));
  write("framing", "scene-query", proto::encodeSceneQuery(hash, proto::digest(bundle).files));
  write("framing", "scene-status", proto::encodeSceneStatus(hash, false, std::vector<std::uint32_t>{0, 2}));
  write("framing", "file-chunk", proto::encodeFileChunk(proto::sha256("v 0 0 0\n"), 8, 0, "v 0 0 0\n"));
  write("framing", "scene-upload", proto::encodeSceneUpload(hash, bundle));
  write("framing", "scene-ready", proto::encodeSceneReady(hash, 1.5f));
  write("framing", "frame-setup", proto::encodeFrameSetup(3, hash, frame));
  FrameSettings adaptive = frame;
  adaptive.sampling.pattern = SamplePattern::kAdaptive;
  adaptive.sampling.samples = 16;
  write("framing", "frame-setup-adaptive", proto::encodeFrameSetup(4, hash, adaptive));
  write("framing", "tile-request", proto::encodeTileRequest(3, 4, {8, 8, 8, 8}, Bytes(8, 0xff)));
  write("framing", "tile-result", proto::encodeTileResult(3, 4, Bytes(12, 7), {1, 2, 3, 4, 5, 6}, 99));
  write("framing", "error", proto::encodeError(wire::ErrorCode::BadTile, "tile 4: outside", 3, 4));
  write("framing", "goodbye", proto::encodeGoodbye());
  write("framing", "cancel", proto::encodeCancel(3, std::vector<std::uint32_t>{4, 5}));
  write("framing", "cancel-frame", proto::encodeCancel(3, {}));
  // Regressions: a body type without its body, for every type.
  for (const wire::Body type : proto::test::allBodyTypes()) {
    write("framing", std::string("bodyless-") + wire::EnumNameBody(type), proto::test::bodylessFrame(type));
  }
}

// A session that fills an irradiance field's probes in batches, sends it
// back in pieces, and traces a tile of a frame that reads it.
Bytes fieldSession(const proto::SceneBundle& bundle, FrameSettings frame, const Bounds3& bounds) {
  frame.width = 16;
  frame.height = 8;
  frame.sampling.samples = 1;
  frame.tracing.transport = Transport::kPath;
  frame.tracing.maxBounces = 1;
  const FieldSettings settings{2, 64};
  const proto::SceneHash hash = bundle.hash();
  std::vector<Bytes> frames{proto::encodeHello(1 << 20, 0, "seed")};
  for (Bytes& f : proto::encodeFullUpload(bundle, 2048)) frames.push_back(std::move(f));
  frames.push_back(proto::encodeFrameSetup(1, hash, frame, {settings, true}));
  frames.push_back(proto::encodeTileRequest(1, 0, {0, 0, 4, 1}, {}));
  frames.push_back(proto::encodeTileRequest(1, 1, {4, 0, 4, 1}, {}));
  for (Bytes& f : proto::encodeFieldPieces(hash, IrradianceField(bounds, settings), 2048)) {
    frames.push_back(std::move(f));
  }
  frames.push_back(proto::encodeFrameSetup(2, hash, frame, {settings, false}));
  frames.push_back(proto::encodeTileRequest(2, 0, {0, 0, 8, 8}, {}));
  frames.push_back(proto::encodeGoodbye());
  return join(frames);
}

void sessionSeeds(const proto::SceneBundle& room, const FrameSettings& frame, const Bounds3& bounds) {
  write("session", "room", session(room, frame));
  write("session", "field", fieldSession(room, frame, bounds));
  proto::SceneBundle textured{readFile(gRoot / "tests/fuzz/seed-scenes/textured.json"), {}};
  textured.files = {{"models/cube.obj", fuzz::kCubeObj}, {"models/cube.mtl", fuzz::kCubeMtl},
                    {"models/tex.bmp", fuzz::tinyBmp()}};
  write("session", "textured", session(textured, frame));
  // Regressions: bodyless messages before and after Hello.
  write("session", "bodyless-before-hello", proto::test::bodylessFrame(wire::Body::FrameSetup));
  write("session", "bodyless-after-hello",
        join({proto::encodeHello(1 << 20, 0, "seed"), proto::test::bodylessFrame(wire::Body::TileRequest)}));
}

// A server's side of a whole conversation with glint (fuzz_server_link):
// after the first byte (fuzz_server_link.cpp says what it sets), what
// follows the server's Hello, which the target writes itself; and one seed
// with a Hello of its own (this build's: another build's is refused).
void serverLinkSeeds() {
  const proto::SceneHash hash = fuzz::linkBundle().hash();
  const std::vector<TileJob> jobs = fuzz::linkJobs();
  std::vector<Bytes> results;
  for (std::uint32_t tile = 0; tile < jobs.size(); ++tile) {
    results.push_back(proto::encodeTileResult(fuzz::kLinkFrame, tile, Bytes(3 * tracedPixels(jobs[tile]), 9), {}, 5));
  }
  write("server_link", "held", join({Bytes{0x20}, proto::encodeSceneStatus(hash, true), results[0], results[1]}));
  const std::uint32_t missing[] = {0};
  write("server_link", "uploaded",
        join({Bytes{0}, proto::encodeSceneStatus(hash, false, missing), proto::encodeSceneReady(hash, 1.0f),
              results[1], results[0]}));
  write("server_link", "own-hello",
        join({Bytes{0x41}, proto::encodeHello(1 << 20, 2, "seed"), proto::encodeSceneStatus(hash, true), results[0]}));
}

void sceneSeeds() {
  for (const char* dir : {"scenes", "scenes/hard", "tests/fuzz/seed-scenes"}) {
    for (const auto& entry : fs::directory_iterator(gRoot / dir)) {
      if (entry.path().extension() == ".json") {
        write("scene_json", entry.path().filename().string(), readFile(entry.path()));
      }
    }
  }
}

// OpenEXR textures as OpenEXR writes them: scanlines under each lossless
// and lossy compression (each its own decompressor), tiles, luminance.
void exrSeeds() {
  Imf::Array2D<Imf::Rgba> pixels;
  pixels.resizeErase(3, 4);
  for (int i = 0; i < 12; ++i) pixels[i / 4][i % 4] = Imf::Rgba(i / 8.0f, 1.0f - i / 12.0f, 0.25f);
  const fs::path path = fs::temp_directory_path() / "glint-seed.exr";
  const std::pair<Imf::Compression, const char*> compressions[] = {
      {Imf::NO_COMPRESSION, "none"}, {Imf::RLE_COMPRESSION, "rle"},  {Imf::ZIPS_COMPRESSION, "zips"},
      {Imf::ZIP_COMPRESSION, "zip"}, {Imf::PIZ_COMPRESSION, "piz"},  {Imf::PXR24_COMPRESSION, "pxr24"},
      {Imf::B44_COMPRESSION, "b44"}, {Imf::DWAA_COMPRESSION, "dwaa"}};
  for (const auto& [compression, name] : compressions) {
    {
      Imf::RgbaOutputFile out(path.c_str(), 4, 3, Imf::WRITE_RGB, 1.0f, Imath::V2f(0, 0), 1.0f, Imf::INCREASING_Y,
                              compression);
      out.setFrameBuffer(&pixels[0][0], 1, 4);
      out.writePixels(3);
    }
    write("image", std::string("small-") + name + ".exr", readFile(path));
  }
  {
    Imf::RgbaOutputFile out(path.c_str(), 4, 3, Imf::WRITE_Y);
    out.setFrameBuffer(&pixels[0][0], 1, 4);
    out.writePixels(3);
  }
  write("image", "small-luminance.exr", readFile(path));
  {
    Imf::TiledRgbaOutputFile out(path.c_str(), 4, 3, 2, 2, Imf::ONE_LEVEL, Imf::ROUND_DOWN, Imf::WRITE_RGBA);
    out.setFrameBuffer(&pixels[0][0], 1, 4);
    out.writeTiles(0, out.numXTiles() - 1, 0, out.numYTiles() - 1);
  }
  write("image", "small-tiled.exr", readFile(path));
  write("image", "large-window-few-chunks.exr", test::exrWithLargeWindow(readFile(path)));
  fs::remove(path);
}

void objAndImageSeeds() {
  write("obj", "cube", std::string(fuzz::kCubeObj).replace(0, 15, "mtllib m.mtl") + "\n#MTL\n" +
                           std::string(fuzz::kCubeMtl));
  write("obj", "groups-normals",
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nvn 0 0 1\ng a\nf 1//1 2//1 3//1\ng b\nf 2//1 4//1 3//1\n");
  write("image", "tiny.bmp", fuzz::tinyBmp());
  MemorySource cube;
  cube.add("m.obj", fuzz::kCubeObj);
  cube.add("cube.mtl", fuzz::kCubeMtl);
  cube.add("tex.bmp", fuzz::tinyBmp());
  SceneBudget budget;
  MeshModel lit = loadObj(cube, "m.obj", "seed", budget, true);
  write("mesh_blob", "textured-cube", encodeMeshBlob(lit));
  Light spot;
  spot.type = LightType::kSpot;
  spot.cosInner = 0.9f;
  Light sun;
  sun.type = LightType::kDirectional;
  lit.lights = {Light{}, spot, sun};
  write("mesh_blob", "cube-with-lights", encodeMeshBlob(lit));
  lit.materials.at(0).emission.x = std::numeric_limits<float>::infinity();  // refused: checkImportedModel
  write("mesh_blob", "cube-emitting-infinity", encodeMeshBlob(lit));
  FrameImage image{4, 3, Bytes(36)};
  for (std::size_t i = 0; i < image.rgb.size(); ++i) image.rgb[i] = static_cast<std::uint8_t>(i * 7);
  const fs::path png = fs::temp_directory_path() / "glint-seed.png";
  writePng(png, image, Encoding::kSrgb);
  write("image", "small.png", readFile(png));
  fs::remove(png);
  // The other texture formats, as stb_image_write writes them.
  const auto into = [](void* out, void* data, int size) {
    static_cast<std::string*>(out)->append(static_cast<char*>(data), static_cast<std::size_t>(size));
  };
  std::string jpeg, tga, hdr;
  stbi_write_jpg_to_func(into, &jpeg, 4, 3, 3, image.rgb.data(), 90);
  stbi_write_tga_to_func(into, &tga, 4, 3, 3, image.rgb.data());
  std::vector<float> linear(image.rgb.begin(), image.rgb.end());
  for (float& v : linear) v /= 64.0f;
  stbi_write_hdr_to_func(into, &hdr, 4, 3, 3, linear.data());
  write("image", "small.jpg", jpeg);
  write("image", "small.tga", tga);
  write("image", "small.hdr", hdr);
  // Files that claim more than their bytes are worth (tests/support/hostile_images.h).
  write("image", "truncated-8192.hdr", test::truncatedRadiance());
  write("image", "progressive-190-scans.jpg", test::progressiveJpeg(16, 2));
  exrSeeds();
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: glint-fuzz-seeds SOURCE_DIR\n");
    return 2;
  }
  gRoot = argv[1];
  try {
    const proto::LoadedBundle room = proto::loadSceneBundle(gRoot / "scenes/room.json");
    framingSeeds(room.bundle, room.scene.frame);
    sessionSeeds(room.bundle, room.scene.frame, room.scene.geometry.bounds());
    serverLinkSeeds();
    sceneSeeds();
    objAndImageSeeds();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "glint-fuzz-seeds: %s\n", e.what());
    return 1;
  }
  return 0;
}

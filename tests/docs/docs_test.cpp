// What the documents show and say is what the code does: the README's
// picture is today's render, the scene format's example loads and renders,
// the texture formats it lists are the ones that load, and every relative
// link in the documents leads to a file.
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

#include <gtest/gtest.h>
#include <stb_image_write.h>

#include "common/base/error.h"
#include "common/render/frame.h"
#include "common/render/prepared_scene.h"
#include "common/image/image_decode.h"
#include "common/scene/scene_load.h"
#include "tests/support/glint_run.h"
#include "tests/support/test_support.h"

namespace glint {
namespace {

namespace fs = std::filesystem;

std::string readText(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

FrameImage render(const Scene& scene) {
  const PreparedScene prepared(scene, BvhSettings{});
  ThreadPool pool(2);
  return renderFrame(Renderer(prepared, scene.frame), pool, {}).image;
}

// README.md shows docs/images/room.png as "the thesis's room, full ray
// trace": it must be what `glint render scenes/room.json --mask all` writes
// today (re-render it with that command when the tracer changes).
TEST(Docs, ReadmePictureIsTodaysRender) {
  EXPECT_NE(readText(test::sourcePath("README.md")).find("(docs/images/room.png)"), std::string::npos);
  SceneBudget budget;
  const Image picture = decodeImage(readText(test::sourcePath("docs/images/room.png")), "room.png", budget);
  const FrameImage today = render(loadSceneFile(test::sourcePath("scenes/room.json")));
  ASSERT_EQ(picture.width, today.width);
  ASSERT_EQ(picture.height, today.height);
  EXPECT_TRUE(picture.rgb == today.rgb) << "docs/images/room.png is not today's render: run build/bin/glint render "
                                           "scenes/room.json --mask all -o docs/images/room.png";
}

// README.md shows the Cornell box path-traced and as the hybrid frame with an
// irradiance field: each must be what its command writes today.
TEST(Docs, ReadmeCornellPicturesAreTodaysRenders) {
  const std::string readme = readText(test::sourcePath("README.md"));
  const fs::path dir = fs::temp_directory_path() / "glint_docs_cornell";
  fs::create_directories(dir);
  for (const auto& [name, options] : {std::pair<std::string, std::string>{"cornell-path", "--mask all"},
                                      std::pair<std::string, std::string>{"cornell-field", "--field 8,256"}}) {
    EXPECT_NE(readme.find("(docs/images/" + name + ".png)"), std::string::npos) << name;
    const std::string command = "render " + test::sourcePath("scenes/cornell.json") + " --size 256x256 " + options;
    const test::GlintRun run = test::runGlint(command + " -q -o " + (dir / (name + ".png")).string());
    ASSERT_EQ(run.status, 0) << run.output;
    SceneBudget budget;
    const Image picture =
        decodeImage(readText(test::sourcePath("docs/images/" + name + ".png")), name + ".png", budget);
    const Image today = decodeImage(readText((dir / (name + ".png")).string()), name + ".png", budget);
    EXPECT_TRUE(picture.rgb == today.rgb) << "docs/images/" << name << ".png is not today's render: run "
                                          << "build/bin/glint " << command << " -o docs/images/" << name << ".png";
  }
  fs::remove_all(dir);
}

// The example at the top of docs/scene-format.md, with the two files it
// names put beside it, loads and renders something.
TEST(Docs, SceneFormatExampleRenders) {
  const std::string doc = readText(test::sourcePath("docs/scene-format.md"));
  const std::size_t start = doc.find("```json\n");
  ASSERT_NE(start, std::string::npos);
  const std::size_t end = doc.find("```", start + 8);
  const fs::path dir = fs::temp_directory_path() / "glint_docs_example";
  fs::remove_all(dir);
  fs::create_directories(dir / "models");
  fs::create_directories(dir / "textures");
  fs::copy_file(test::sourcePath("scenes/models/bunny.obj"), dir / "models/bunny.obj");
  fs::copy_file(test::sourcePath("scenes/sky.hdr"), dir / "sky.hdr");
  std::ofstream(dir / "textures/photo.png", std::ios::binary) << test::flatPng(4, 4);
  std::ofstream(dir / "scene.json") << doc.substr(start + 8, end - start - 8);
  Scene scene = loadSceneFile(dir / "scene.json");
  scene.frame.width = 80;
  scene.frame.height = 60;
  const FrameImage image = render(scene);
  std::size_t lit = 0;
  for (const std::uint8_t v : image.rgb) lit += v > 30 ? 1 : 0;
  EXPECT_GT(lit, image.rgb.size() / 10);
  fs::remove_all(dir);
}

// "image (PNG, BMP, JPEG, TGA or Radiance HDR ...)": each loads; a GIF,
// which the image library could read, is refused by name, and so is a
// JPEG cut inside its header.
TEST(Docs, TextureFormatsListedAreTheOnesThatLoad) {
  const std::string doc = readText(test::sourcePath("docs/scene-format.md"));
  EXPECT_NE(doc.find("`image` (PNG, BMP, JPEG, TGA, Radiance HDR or\n  OpenEXR"), std::string::npos);
  SceneBudget budget;
  EXPECT_EQ(decodeImage(test::flatPng(3, 2), "png", budget).width, 3);
  const unsigned char bmp[] = {'B', 'M', 58,   0,    0, 0, 0, 0, 0,  0, 54, 0, 0, 0, 40, 0,   0, 0, 1,    0,
                               0,   0,   1,    0,    0, 0, 1, 0, 24, 0, 0,  0, 0, 0, 4,  0,   0, 0, 0x13, 0x0b,
                               0,   0,   0x13, 0x0b, 0, 0, 0, 0, 0,  0, 0,  0, 0, 0, 0,  255, 0, 0};
  EXPECT_EQ(decodeImage(std::string(reinterpret_cast<const char*>(bmp), sizeof bmp), "bmp", budget).width, 1);
  const std::uint8_t rgb[] = {200, 100, 50, 25, 75, 125};
  const auto into = [](void* out, void* data, int size) {
    static_cast<std::string*>(out)->append(static_cast<char*>(data), size);
  };
  std::string jpeg, tga, hdr;
  stbi_write_jpg_to_func(into, &jpeg, 2, 1, 3, rgb, 90);
  stbi_write_tga_to_func(into, &tga, 2, 1, 3, rgb);
  const float linear[] = {0.5f, 0.25f, 0.125f, 1.0f, 2.0f, 0.0f};
  stbi_write_hdr_to_func(into, &hdr, 2, 1, 3, linear);
  for (const std::string* file : {&jpeg, &tga, &hdr}) EXPECT_EQ(decodeImage(*file, "file", budget).width, 2);
  const std::string exr = readText(test::sourcePath("tests/fuzz/corpus/image/small-zip.exr"));  // OpenEXR wrote it
  EXPECT_EQ(decodeImage(exr, "exr", budget).width, 4);
  const std::string gif("GIF89a\x01\x00\x01\x00\x00\x00\x00;", 14);
  EXPECT_THROW(decodeImage(gif, "gif", budget), InputError);
  EXPECT_THROW(decodeImage(jpeg.substr(0, 11), "jpeg", budget), InputError);
}

// Every relative link ([text](path) or [text](path#anchor)) in README.md
// and docs/*.md names a file or folder that exists.
TEST(Docs, RelativeLinksResolve) {
  std::vector<fs::path> documents{test::sourcePath("README.md")};
  for (const auto& entry : fs::directory_iterator(test::sourcePath("docs"))) {
    if (entry.path().extension() == ".md") documents.push_back(entry.path());
  }
  const std::regex link(R"(\]\(([^)#\s]+)(#[^)]*)?\))");
  int checked = 0;
  for (const fs::path& doc : documents) {
    const std::string text = readText(doc);
    for (auto it = std::sregex_iterator(text.begin(), text.end(), link); it != std::sregex_iterator(); ++it) {
      const std::string target = (*it)[1];
      if (target.find("://") != std::string::npos || target.rfind("mailto:", 0) == 0) continue;
      ++checked;
      EXPECT_TRUE(fs::exists(doc.parent_path() / target)) << doc.filename() << " links to " << target;
    }
  }
  EXPECT_GT(checked, 20);
}

}  // namespace
}  // namespace glint

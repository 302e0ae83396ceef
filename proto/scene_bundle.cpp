#include "proto/scene_bundle.h"

#include <memory>

#include <openssl/evp.h>

#include "common/base/error.h"
#include "common/base/file_source.h"
#include "common/scene/model_scene.h"
#include "common/scene/scene_load.h"

namespace glint::proto {
namespace {

// Reads through to the disk and keeps every file read (the disk source
// holds them: nothing is copied); of a mesh an importer reads, the imported
// mesh's blob instead of its files.
class RecordingSource : public FileSource {
 public:
  RecordingSource(std::filesystem::path folder, std::size_t maxBytes) : disk_(std::move(folder), maxBytes) {}
  const std::string& read(const std::string& path, const std::string& place) override {
    return disk_.read(path, place);
  }
  bool has(const std::string& path) override { return disk_.has(path); }
  bool importsMeshes() const override { return true; }
  std::string readForImport(const std::string& path, const std::string& place) override {
    return disk_.readForImport(path, place);
  }
  void keepImported(const std::string& path, std::string blob) override {
    imported_[normalisePath(path)] = std::move(blob);
  }
  // The files read and the imported meshes' blobs, by path.
  std::map<std::string, std::string> take() {
    std::map<std::string, std::string> files = disk_.takeRead();
    for (auto& [path, blob] : imported_) files.insert_or_assign(path, std::move(blob));
    return files;
  }

 private:
  DirectorySource disk_;
  std::map<std::string, std::string> imported_;
};

}  // namespace

SceneHash SceneBundle::hash() const {
  std::unique_ptr<EVP_MD_CTX, void (*)(EVP_MD_CTX*)> ctx(EVP_MD_CTX_new(), EVP_MD_CTX_free);
  EVP_DigestInit_ex(ctx.get(), EVP_sha256(), nullptr);
  const auto part = [&](const std::string& bytes) {
    const std::uint64_t n = bytes.size();
    std::uint8_t length[8];
    for (int i = 0; i < 8; ++i) length[i] = static_cast<std::uint8_t>(n >> (8 * i));
    EVP_DigestUpdate(ctx.get(), length, sizeof length);
    EVP_DigestUpdate(ctx.get(), bytes.data(), bytes.size());
  };
  part(text);
  for (const auto& [path, bytes] : files) {
    part(path);
    part(bytes);
  }
  SceneHash out{};
  unsigned int size = 0;
  EVP_DigestFinal_ex(ctx.get(), out.data(), &size);
  return out;
}

SceneHash sha256(std::string_view bytes) {
  SceneHash out{};
  unsigned int size = 0;
  EVP_Digest(bytes.data(), bytes.size(), out.data(), &size, EVP_sha256(), nullptr);
  return out;
}

BundleDigest digest(const SceneBundle& bundle) {
  BundleDigest d{bundle.hash(), {}};
  for (const auto& [path, bytes] : bundle.files) d.files.push_back(sha256(bytes));
  return d;
}

LoadedBundle loadSceneBundle(const std::filesystem::path& path, const LoadLimits& limits) {
  try {
    RecordingSource files(path.parent_path(), limits.maxFileBytes);
    DirectorySource sceneFile(path.parent_path(), limits.maxFileBytes);
    std::string text = sceneTextFor(path, sceneFile);
    Scene scene = loadScene(text, files, limits);
    return {std::move(scene), SceneBundle{std::move(text), files.take()}};
  } catch (const InputError& e) {
    throw InputError(path.string() + ": " + e.what());
  }
}

Scene loadBundle(const SceneBundle& bundle, SceneBudget& budget) {
  MemorySource files;
  for (const auto& [path, bytes] : bundle.files) files.add(path, bytes);
  return loadScene(bundle.text, files, budget);
}

std::string toHex(const SceneHash& hash) {
  static constexpr char kDigits[] = "0123456789abcdef";
  std::string s;
  for (std::uint8_t b : hash) {
    s += kDigits[b >> 4];
    s += kDigits[b & 15];
  }
  return s;
}

}  // namespace glint::proto

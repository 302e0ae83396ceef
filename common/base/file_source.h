#pragma once

#include <cstddef>
#include <filesystem>
#include <map>
#include <string>

namespace glint {

// The largest file (a scene, mesh or texture) read unless told otherwise.
constexpr std::size_t kDefaultMaxFileBytes = std::size_t{1} << 30;

// Where a scene's files (meshes, materials, textures) come from. Paths are
// the ones written in the scene, relative to the scene file's folder (for a
// file named inside an OBJ or MTL: already joined with that file's folder).
// A scene loaded on a server comes with its files as bytes (MemorySource): it
// never opens a path that a client sent.
class FileSource {
 public:
  virtual ~FileSource() = default;
  // The file's bytes, held by the source for as long as it lives (a large
  // mesh's text is not copied); throws InputError starting with `place` if
  // it cannot.
  virtual const std::string& read(const std::string& path, const std::string& place) = 0;
  // Whether the file is there at all (a file an OBJ names may be missing:
  // a warning, not an error).
  virtual bool has(const std::string& path) = 0;

  // Mesh formats read by an importer (glTF, PLY: common/scene/mesh_import.h) are
  // imported only where the files come from disk; a scene loaded from memory
  // (on a server) takes each imported mesh as a mesh blob instead, so that no
  // importer ever parses bytes a peer sent.
  virtual bool importsMeshes() const { return false; }
  // The bytes an importer reads (a recording source does not keep them: the
  // blob goes in their place).
  virtual std::string readForImport(const std::string& path, const std::string& place) { return read(path, place); }
  // The imported mesh of `path` as a blob (common/scene/mesh_blob.h), for a source
  // that records what a scene needs.
  virtual void keepImported(const std::string& /*path*/, std::string /*blob*/) {}
};

// Files on disk below a folder, each at most maxBytes. A file read is kept
// (read again, it is not read twice) until takeRead() hands them all over;
// readForImport's bytes are not kept.
class DirectorySource : public FileSource {
 public:
  DirectorySource(std::filesystem::path folder, std::size_t maxBytes);
  const std::string& read(const std::string& path, const std::string& place) override;
  bool has(const std::string& path) override;
  bool importsMeshes() const override { return true; }
  std::string readForImport(const std::string& path, const std::string& place) override;
  // Every file read(), by its normalised path; the source keeps none.
  std::map<std::string, std::string> takeRead() { return std::move(read_); }

 private:
  std::filesystem::path folder_;
  std::size_t maxBytes_;
  std::map<std::string, std::string> read_;
};

// Files held in memory, keyed by their normalised relative path.
class MemorySource : public FileSource {
 public:
  void add(const std::string& path, std::string bytes);
  const std::string& read(const std::string& path, const std::string& place) override;
  bool has(const std::string& path) override;

 private:
  std::map<std::string, std::string> files_;
};

// "a/b/../c.png" -> "a/c.png": the key a path is stored and looked up under.
std::string normalisePath(const std::string& path);

// Joins a path written inside a file (an OBJ's mtllib, an MTL's map_Kd) to
// the folder of that file. Backslashes, as Windows exporters write them
// (.\\textures\\wall.png), separate folders too.
std::string siblingPath(const std::string& file, const std::string& name);

}  // namespace glint

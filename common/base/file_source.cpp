#include "common/base/file_source.h"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <fstream>

#include "common/base/error.h"

namespace glint {

std::string normalisePath(const std::string& path) {
  return std::filesystem::path(path).lexically_normal().generic_string();
}

std::string siblingPath(const std::string& file, const std::string& name) {
  std::string forward = name;
  std::replace(forward.begin(), forward.end(), '\\', '/');
  return normalisePath((std::filesystem::path(file).parent_path() / forward).generic_string());
}

DirectorySource::DirectorySource(std::filesystem::path folder, std::size_t maxBytes)
    : folder_(std::move(folder)), maxBytes_(maxBytes) {}

std::string DirectorySource::read(const std::string& path, const std::string& place) {
  const std::filesystem::path full = folder_ / path;
  std::error_code ec;
  const auto size = std::filesystem::file_size(full, ec);
  if (ec) throw InputError(place + ": cannot read '" + full.string() + "' (" + ec.message() + ")");
  if (size > maxBytes_) {
    throw InputError(place + ": '" + full.string() + "' is " + std::to_string(size) +
                     " bytes, over the limit of " + std::to_string(maxBytes_));
  }
  std::ifstream in(full, std::ios::binary);
  if (!in) {
    throw InputError(place + ": cannot open '" + full.string() + "' (" + std::strerror(errno) + ")");
  }
  // One read into a buffer of the file's size; a stream copy grew its
  // buffer step by step, several times slower on a large OBJ
  // (docs/performance.md).
  std::string bytes(size, '\0');
  in.read(bytes.data(), static_cast<std::streamsize>(size));
  const auto got = static_cast<std::size_t>(in.gcount());
  if (got != size || in.peek() != std::ifstream::traits_type::eof()) {
    throw InputError(place + ": error reading '" + full.string() + "': read " + std::to_string(got) + " of its " +
                     std::to_string(size) + " bytes (did it change while it was read?)");
  }
  return bytes;
}

bool DirectorySource::has(const std::string& path) {
  std::error_code ec;
  return std::filesystem::is_regular_file(folder_ / path, ec);
}

void MemorySource::add(const std::string& path, std::string bytes) {
  files_[normalisePath(path)] = std::move(bytes);
}

std::string MemorySource::read(const std::string& path, const std::string& place) {
  const auto it = files_.find(normalisePath(path));
  if (it == files_.end()) throw InputError(place + ": file '" + path + "' was not sent with the scene");
  return it->second;
}

bool MemorySource::has(const std::string& path) { return files_.count(normalisePath(path)) > 0; }

}  // namespace glint

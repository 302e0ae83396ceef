#include "common/base/file_source.h"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <fstream>

#include "common/base/error.h"
#include "common/base/heap_tuning.h"

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

std::string DirectorySource::readForImport(const std::string& path, const std::string& place) {
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
  // One read into a buffer of the file's size, its pages faulted in at
  // once (a stream copy grew its buffer step by step; page by page, the
  // faults cost more than the read: docs/performance.md).
  std::string bytes;
  bytes.reserve(size);
  prefault(bytes.data(), size);
  bytes.resize(size);
  in.read(bytes.data(), static_cast<std::streamsize>(size));
  const auto got = static_cast<std::size_t>(in.gcount());
  if (got != size || in.peek() != std::ifstream::traits_type::eof()) {
    throw InputError(place + ": error reading '" + full.string() + "': read " + std::to_string(got) + " of its " +
                     std::to_string(size) + " bytes (did it change while it was read?)");
  }
  return bytes;
}

const std::string& DirectorySource::read(const std::string& path, const std::string& place) {
  const std::string key = normalisePath(path);
  if (const auto it = read_.find(key); it != read_.end()) return it->second;
  return read_.emplace(key, readForImport(path, place)).first->second;
}

bool DirectorySource::has(const std::string& path) {
  std::error_code ec;
  return std::filesystem::is_regular_file(folder_ / path, ec);
}

void MemorySource::add(const std::string& path, std::string bytes) {
  files_[normalisePath(path)] = std::move(bytes);
}

const std::string& MemorySource::read(const std::string& path, const std::string& place) {
  const auto it = files_.find(normalisePath(path));
  if (it == files_.end()) throw InputError(place + ": file '" + path + "' was not sent with the scene");
  return it->second;
}

bool MemorySource::has(const std::string& path) { return files_.count(normalisePath(path)) > 0; }

}  // namespace glint

// Files read from a folder: every byte as on disk, and the size limit.
#include <filesystem>
#include <fstream>
#include <random>
#include <string>

#include <unistd.h>

#include <gtest/gtest.h>

#include "common/base/error.h"
#include "common/base/file_source.h"

namespace glint {
namespace {

namespace fs = std::filesystem;

// A folder of its own under the temporary directory, removed afterwards.
class Folder {
 public:
  Folder() : path_(fs::temp_directory_path() / ("glint-file-source-" + std::to_string(::getpid()))) {
    fs::create_directories(path_);
  }
  ~Folder() { fs::remove_all(path_); }
  const fs::path& path() const { return path_; }
  void write(const std::string& name, const std::string& bytes) const {
    std::ofstream(path_ / name, std::ios::binary) << bytes;
  }

 private:
  fs::path path_;
};

TEST(FileSource, FolderFilesComeBackByteForByte) {
  Folder folder;
  std::string bytes(300'001, '\0');  // NULs, CR LF and every byte value, an odd size
  std::mt19937 rng(3);
  for (char& c : bytes) c = static_cast<char>(rng() & 0xff);
  folder.write("data.bin", bytes);
  folder.write("empty.obj", "");
  DirectorySource files(folder.path(), bytes.size());
  EXPECT_EQ(files.read("data.bin", "test"), bytes);
  EXPECT_EQ(files.read("empty.obj", "test"), "");
}

TEST(FileSource, FolderFileOverTheLimitIsAnError) {
  Folder folder;
  folder.write("big.obj", std::string(101, 'v'));
  DirectorySource files(folder.path(), 100);
  try {
    files.read("big.obj", "objects[2].file");
    FAIL() << "read a file over the limit";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("objects[2].file: '"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("is 101 bytes, over the limit of 100"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace glint

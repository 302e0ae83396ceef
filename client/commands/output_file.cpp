#include "client/commands/output_file.h"

#include <algorithm>
#include <cstring>
#include <vector>

#include <Imath/half.h>
#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfIO.h>
#include <OpenEXR/ImfOutputFile.h>

#include "common/base/error.h"
#include "common/image/image_write.h"

namespace glint {
namespace {

// An OpenEXR output stream into memory, so that the file is written
// atomically as a whole.
class MemoryStream : public Imf::OStream {
 public:
  MemoryStream() : Imf::OStream("memory") {}
  void write(const char c[], int n) override {
    const auto end = position_ + static_cast<std::size_t>(n);
    if (end > bytes_.size()) bytes_.resize(end);
    std::memcpy(bytes_.data() + position_, c, static_cast<std::size_t>(n));
    position_ = end;
  }
  uint64_t tellp() override { return position_; }
  void seekp(uint64_t pos) override { position_ = pos; }
  const std::vector<unsigned char>& bytes() const { return bytes_; }

 private:
  std::vector<unsigned char> bytes_;
  std::size_t position_ = 0;
};

}  // namespace

OutputFormat outputFormat(const std::string& option, const std::filesystem::path& path) {
  std::string extension = path.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(), ::tolower);
  if (const std::optional<OutputFormat> format = enumFromWord<OutputFormat>(extension)) return *format;
  throw UsageError(option + " " + path.string() + ": glint writes " + enumWordsJoined<OutputFormat>() +
                   " (8-bit PNG; linear half-float OpenEXR; linear float PFM); give a file name ending in one");
}

void writeExr(const std::filesystem::path& path, const LinearImage& image) {
  Imf::Header header(image.width, image.height);
  header.compression() = Imf::ZIP_COMPRESSION;
  // The file's type is half; OpenEXR converts only between the slice's
  // and the channel's type when they are equal, so the rounding is here.
  std::vector<Imath::half> halves(image.rgb.begin(), image.rgb.end());
  Imf::FrameBuffer frame;
  const std::size_t pixel = 3 * sizeof(Imath::half);
  const std::size_t row = pixel * static_cast<std::size_t>(image.width);
  auto* base = reinterpret_cast<char*>(halves.data());
  for (int c = 0; c < 3; ++c) {
    const char* name = c == 0 ? "R" : c == 1 ? "G" : "B";
    header.channels().insert(name, Imf::Channel(Imf::HALF));
    frame.insert(name, Imf::Slice(Imf::HALF, base + c * sizeof(Imath::half), pixel, row));
  }
  MemoryStream stream;
  try {
    Imf::OutputFile file(stream, header);
    file.setFrameBuffer(frame);
    file.writePixels(image.height);
  } catch (const std::exception& e) {
    throw InputError(path.string() + ": OpenEXR encoding failed: " + e.what());
  }
  writeAtomically(path, stream.bytes().data(), stream.bytes().size());
}

void writeOutput(const std::filesystem::path& path, OutputFormat format, const FrameImage& bytes,
                 const LinearImage& linear, Encoding encoding) {
  switch (format) {
    case OutputFormat::kPng:
      return writePng(path, bytes, encoding);
    case OutputFormat::kExr:
      return writeExr(path, linear);
    case OutputFormat::kPfm:
      return writePfm(path, linear);
  }
}

}  // namespace glint

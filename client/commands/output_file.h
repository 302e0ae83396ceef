#pragma once

#include <filesystem>
#include <string>

#include "common/base/enum_words.h"
#include "common/render/frame.h"
#include "common/image/linear_image.h"
#include "common/image/output_settings.h"

namespace glint {

// The image formats `glint render -o` writes, chosen by the file's extension:
// 8-bit PNG, or linear colour as OpenEXR (half float) or PFM (32-bit float).
enum class OutputFormat { kPng, kExr, kPfm };

template <>
struct EnumWords<OutputFormat> {
  static constexpr std::array<std::pair<OutputFormat, std::string_view>, 3> kWords{
      {{OutputFormat::kPng, ".png"}, {OutputFormat::kExr, ".exr"}, {OutputFormat::kPfm, ".pfm"}}};
};

// The format `path` names by its extension (any case); any other extension
// throws InputError naming `option` and the formats there are.
OutputFormat outputFormat(const std::string& option, const std::filesystem::path& path);

// True for the formats that hold linear floats.
inline bool holdsFloats(OutputFormat format) { return format != OutputFormat::kPng; }

// Writes linear colour as OpenEXR (RGB, half float, ZIP compression),
// atomically like writePng.
void writeExr(const std::filesystem::path& path, const LinearImage& image);

// Writes the frame in `format`: PNG from the 8-bit frame (its values in
// `encoding`), the float formats from `linear`.
void writeOutput(const std::filesystem::path& path, OutputFormat format, const FrameImage& bytes,
                 const LinearImage& linear, Encoding encoding);

}  // namespace glint

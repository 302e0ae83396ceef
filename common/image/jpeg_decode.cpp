#include "common/image/jpeg_decode.h"

#include <csetjmp>
#include <cstdio>

#include <jpeglib.h>

#include "common/base/error.h"

namespace glint {
namespace {

// libjpeg reports errors through a callback that must not return: it jumps
// back to decodeJpeg's setjmp with the message. Warnings (corrupt data that
// libjpeg would paper over) are errors here too, and so is a scan past
// kMaxJpegScans (seen by the progress monitor, which libjpeg calls as it
// reads a multi-scan file's scans).
struct ErrorManager {
  jpeg_error_mgr base;
  jpeg_progress_mgr progress;
  std::jmp_buf jump;
  char message[JMSG_LENGTH_MAX];
};

[[noreturn]] void onError(j_common_ptr info) {
  auto* errors = reinterpret_cast<ErrorManager*>(info->err);
  (*info->err->format_message)(info, errors->message);
  std::longjmp(errors->jump, 1);
}

void onProgress(j_common_ptr info) {
  const auto* decompress = reinterpret_cast<j_decompress_ptr>(info);
  if (decompress->input_scan_number <= kMaxJpegScans) return;
  auto* errors = reinterpret_cast<ErrorManager*>(info->err);
  std::snprintf(errors->message, sizeof errors->message, "more than %d scans", kMaxJpegScans);
  std::longjmp(errors->jump, 1);
}

// The bytes libjpeg holds for the whole image's coefficients when the file
// has several scans (one 8 x 8 block of JCOEF a block of each component,
// padded to whole MCUs); a single-scan file is decoded a row of blocks at
// a time.
std::size_t coefficientBytes(const jpeg_decompress_struct& info) {
  if (!info.progressive_mode && info.comps_in_scan >= info.num_components) return 0;
  std::size_t bytes = 0;
  // Blocks of a component along an edge of `size` pixels, sampled `samp`
  // times where the most sampled component is `maxSamp` times, and one MCU more.
  const auto blocks = [](std::size_t size, int samp, int maxSamp) {
    const auto s = static_cast<std::size_t>(samp), m = static_cast<std::size_t>(maxSamp);
    return (size * s + DCTSIZE * m - 1) / (DCTSIZE * m) + s;
  };
  for (int c = 0; c < info.num_components; ++c) {
    const jpeg_component_info& component = info.comp_info[c];
    bytes += blocks(info.image_width, component.h_samp_factor, info.max_h_samp_factor) *
             blocks(info.image_height, component.v_samp_factor, info.max_v_samp_factor) * DCTSIZE2 * sizeof(JCOEF);
  }
  return bytes;
}

void onMessage(j_common_ptr info, int level) {
  if (level < 0) onError(info);  // a warning; trace messages (level >= 0) are dropped
}

// The decompression from header to last row, on state the caller owns (so
// that nothing with a destructor lives between the setjmp and a longjmp).
// False, with the message in `errors`, when libjpeg fails.
bool decompress(jpeg_decompress_struct& info, ErrorManager& errors, std::string_view bytes, Image& image,
                const DecodeAdmit& admit) {
  if (setjmp(errors.jump)) return false;
  jpeg_mem_src(&info, reinterpret_cast<const unsigned char*>(bytes.data()), static_cast<unsigned long>(bytes.size()));
  jpeg_read_header(&info, TRUE);
  // may throw: see decodeJpeg
  admit(static_cast<int>(info.image_width), static_cast<int>(info.image_height), coefficientBytes(info));
  info.out_color_space = JCS_RGB;
  jpeg_start_decompress(&info);
  image.width = static_cast<int>(info.output_width);
  image.height = static_cast<int>(info.output_height);
  image.rgb.resize(static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height) * 3);
  while (info.output_scanline < info.output_height) {
    JSAMPROW row =
        &image.rgb[static_cast<std::size_t>(info.output_scanline) * static_cast<std::size_t>(image.width) * 3];
    jpeg_read_scanlines(&info, &row, 1);
  }
  jpeg_finish_decompress(&info);
  return true;
}

}  // namespace

Image decodeJpeg(std::string_view bytes, const std::string& place, const DecodeAdmit& admit) {
  jpeg_decompress_struct info{};
  ErrorManager errors{};
  info.err = jpeg_std_error(&errors.base);
  errors.base.error_exit = onError;
  errors.base.emit_message = onMessage;
  jpeg_create_decompress(&info);
  errors.progress.progress_monitor = onProgress;
  info.progress = &errors.progress;
  Image image;
  bool decoded = false;
  try {
    decoded = decompress(info, errors, bytes, image, admit);
  } catch (...) {
    jpeg_destroy_decompress(&info);  // admit() refused the size
    throw;
  }
  jpeg_destroy_decompress(&info);
  if (!decoded) throw InputError(place + ": not a readable JPEG image (" + errors.message + ")");
  return image;
}

}  // namespace glint

#pragma once

// Image files that claim more work or memory than their bytes are worth,
// for the decoders' tests and the image fuzzer's seeds.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdio>  // jpeglib.h needs FILE and size_t declared first
#include <cstdlib>
#include <string>
#include <vector>

#include <jpeglib.h>

namespace glint::test {

// A Radiance header announcing 8192 x 8192 pixels with one run-length row
// after it (stb_image would allocate 768 MiB of floats for it).
inline std::string truncatedRadiance() {
  std::string bytes = "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 8192 +X 8192\n";
  bytes += std::string("\x02\x02\x20\x00", 4);
  for (int channel = 0; channel < 4; ++channel) {
    for (int filled = 0; filled < 8192; filled += 127) {
      bytes += static_cast<char>(128 + std::min(127, 8192 - filled));
      bytes += '\x40';
    }
  }
  return bytes;
}

// A grey progressive JPEG of `size` x `size` pixels whose scans are one DC
// scan and the 63 AC coefficients each in a scan of its own, each refined
// `refinements` times: 1 + 63 (1 + refinements) scans.
inline std::string progressiveJpeg(int size, int refinements) {
  jpeg_compress_struct info{};
  jpeg_error_mgr errors{};
  info.err = jpeg_std_error(&errors);
  jpeg_create_compress(&info);
  unsigned char* out = nullptr;
  unsigned long length = 0;
  jpeg_mem_dest(&info, &out, &length);
  info.image_width = info.image_height = static_cast<JDIMENSION>(size);
  info.input_components = 1;
  info.in_color_space = JCS_GRAYSCALE;
  jpeg_set_defaults(&info);
  std::vector<jpeg_scan_info> scans = {{1, {0}, 0, 0, 0, 0}};
  for (int k = 1; k < 64; ++k) {
    for (int al = refinements; al >= 0; --al) scans.push_back({1, {0}, k, k, al == refinements ? 0 : al + 1, al});
  }
  info.scan_info = scans.data();
  info.num_scans = static_cast<int>(scans.size());
  jpeg_start_compress(&info, TRUE);
  std::vector<unsigned char> row(static_cast<std::size_t>(size));
  while (info.next_scanline < info.image_height) {
    for (int x = 0; x < size; ++x) {
      row[static_cast<std::size_t>(x)] = static_cast<unsigned char>((x * 7 + info.next_scanline * 3) % 256);
    }
    JSAMPROW rows[] = {row.data()};
    jpeg_write_scanlines(&info, rows, 1);
  }
  jpeg_finish_compress(&info);
  jpeg_destroy_compress(&info);
  std::string bytes(reinterpret_cast<const char*>(out), length);
  std::free(out);
  return bytes;
}

// An OpenEXR file with its data window made 8192 x 8192 (its chunks left as
// they were: far fewer than the window needs); unchanged if it has none.
inline std::string exrWithLargeWindow(std::string bytes) {
  const std::string key("dataWindow\0box2i\0", 17);
  const std::size_t at = bytes.find(key);
  if (at == std::string::npos) return bytes;
  const std::int32_t corner[] = {0, 0, 8191, 8191};  // little-endian, as EXR stores them
  bytes.replace(at + key.size() + 4, sizeof corner, reinterpret_cast<const char*>(corner), sizeof corner);
  return bytes;
}

}  // namespace glint::test

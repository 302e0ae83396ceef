#include "common/image/exr_decode.h"

#include <algorithm>
#include <cstring>
#include <type_traits>
#include <vector>

#include <Imath/half.h>
#include <OpenEXR/openexr.h>

#include "common/base/error.h"

namespace glint {
namespace {

// The file's bytes and the first message OpenEXR reports on them.
struct ExrSource {
  std::string_view bytes;
  std::string message;
};

int64_t readBytes(exr_const_context_t, void* userdata, void* buffer, uint64_t size, uint64_t offset,
                  exr_stream_error_func_ptr_t) {
  const std::string_view bytes = static_cast<ExrSource*>(userdata)->bytes;
  if (offset >= bytes.size()) return 0;
  const uint64_t n = std::min<uint64_t>(size, bytes.size() - offset);
  std::memcpy(buffer, bytes.data() + offset, n);
  return static_cast<int64_t>(n);
}

int64_t sizeOf(exr_const_context_t, void* userdata) {
  return static_cast<int64_t>(static_cast<ExrSource*>(userdata)->bytes.size());
}

void keepMessage(exr_const_context_t context, exr_result_t, const char* message) {
  void* userdata = nullptr;
  if (exr_get_user_data(context, &userdata) != EXR_ERR_SUCCESS || !userdata) return;
  std::string& kept = static_cast<ExrSource*>(userdata)->message;
  if (kept.empty()) kept = message;
}

// An open reading context, finished however the decode ends.
class ExrReader {
 public:
  ExrReader(std::string_view bytes, const std::string& place) : source_{bytes, {}}, place_(place) {
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    init.user_data = &source_;
    init.read_fn = readBytes;
    init.size_fn = sizeOf;
    init.error_handler_fn = keepMessage;
    init.flags = EXR_CONTEXT_FLAG_STRICT_HEADER | EXR_CONTEXT_FLAG_DISABLE_CHUNK_RECONSTRUCTION;
    check(exr_start_read(&context_, "texture", &init));
  }
  ~ExrReader() { exr_finish(&context_); }
  ExrReader(const ExrReader&) = delete;
  ExrReader& operator=(const ExrReader&) = delete;

  exr_const_context_t context() const { return context_; }
  // Throws the InputError for a failed call, with OpenEXR's message.
  void check(exr_result_t result) const {
    if (result == EXR_ERR_SUCCESS) return;
    const std::string why = source_.message.empty() ? exr_get_default_error_message(result) : source_.message;
    throw InputError(place_ + ": not a readable OpenEXR image (" + why + ")");
  }
  [[noreturn]] void fail(const std::string& why) const { throw InputError(place_ + ": OpenEXR image " + why); }

 private:
  ExrSource source_;
  std::string place_;
  exr_context_t context_ = nullptr;
};

// The channel each of R, G, B reads from: their own, or Y for all three.
std::vector<std::string> colourChannels(const ExrReader& reader) {
  const exr_attr_chlist_t* list = nullptr;
  reader.check(exr_get_channels(reader.context(), 0, &list));
  const auto has = [list](const char* name) {
    for (int i = 0; i < list->num_channels; ++i) {
      if (std::strcmp(list->entries[i].name.str, name) == 0) return true;
    }
    return false;
  };
  for (int i = 0; i < list->num_channels; ++i) {
    if (list->entries[i].x_sampling != 1 || list->entries[i].y_sampling != 1) {
      reader.fail("has subsampled channels (" + std::string(list->entries[i].name.str) + "); save it as full RGB");
    }
  }
  if (has("R") && has("G") && has("B")) return {"R", "G", "B"};
  if (has("Y")) return {"Y", "Y", "Y"};
  reader.fail("has no R, G and B channels (nor Y)");
}

// The bytes one pixel's samples take in the file, over all its channels
// (half: 2, float and unsigned int: 4).
std::size_t sampleBytes(const ExrReader& reader) {
  const exr_attr_chlist_t* list = nullptr;
  reader.check(exr_get_channels(reader.context(), 0, &list));
  std::size_t bytes = 0;
  for (int i = 0; i < list->num_channels; ++i) bytes += list->entries[i].pixel_type == EXR_PIXEL_HALF ? 2 : 4;
  return bytes;
}

// How the first level's pixels are cut into chunks, scanline blocks or
// tiles: checked against the file before anything is allocated. Their
// offset table (8 bytes a chunk) must fit in the file, so that a small file
// cannot ask for millions of reads.
struct ChunkGrid {
  bool tiled = false;
  int32_t lines = 0;  // scanlines a chunk
  int32_t tileW = 0, tileH = 0;
  std::size_t largestPixels = 0;  // the most pixels one chunk holds
};

ChunkGrid chunkGrid(const ExrReader& reader, int64_t width, int64_t height, std::size_t fileBytes) {
  int32_t count = 0;
  reader.check(exr_get_chunk_count(reader.context(), 0, &count));
  if (count <= 0 || static_cast<std::size_t>(count) > fileBytes / 8) reader.fail("has more chunks than bytes");
  exr_storage_t storage{};
  reader.check(exr_get_storage(reader.context(), 0, &storage));
  ChunkGrid grid;
  if (storage == EXR_STORAGE_SCANLINE) {
    reader.check(exr_get_scanlines_per_chunk(reader.context(), 0, &grid.lines));
    if (grid.lines <= 0) reader.fail("has no scanlines per chunk");
    grid.largestPixels =
        static_cast<std::size_t>(width) * static_cast<std::size_t>(std::min<int64_t>(grid.lines, height));
    return grid;
  }
  if (storage != EXR_STORAGE_TILED) reader.fail("holds deep data; save it as a flat image");
  grid.tiled = true;
  reader.check(exr_get_tile_sizes(reader.context(), 0, 0, 0, &grid.tileW, &grid.tileH));
  if (grid.tileW <= 0 || grid.tileH <= 0) reader.fail("has empty tiles");
  if ((width + grid.tileW - 1) / grid.tileW * ((height + grid.tileH - 1) / grid.tileH) > count) {
    reader.fail("has more tiles than chunks");
  }
  grid.largestPixels = static_cast<std::size_t>(std::min<int64_t>(grid.tileW, width)) *
                       static_cast<std::size_t>(std::min<int64_t>(grid.tileH, height));
  return grid;
}

// Calls `decode(chunk, x, y)` on each chunk of the grid, with the chunk's
// first pixel relative to the data window's corner (OpenEXR 3.1 gives a
// tile's start in tiles, not pixels).
template <typename Decode>
void forEachChunk(const ExrReader& reader, const exr_attr_box2i_t& window, const ChunkGrid& grid, Decode decode) {
  exr_chunk_info_t chunk{};
  if (!grid.tiled) {
    for (int64_t y = window.min.y; y <= window.max.y; y += grid.lines) {
      reader.check(exr_read_scanline_chunk_info(reader.context(), 0, static_cast<int>(y), &chunk));
      decode(chunk, 0, y - window.min.y);
    }
    return;
  }
  const int64_t width = int64_t{window.max.x} - window.min.x + 1, height = int64_t{window.max.y} - window.min.y + 1;
  for (int64_t ty = 0; ty * grid.tileH < height; ++ty) {
    for (int64_t tx = 0; tx * grid.tileW < width; ++tx) {
      reader.check(
          exr_read_tile_chunk_info(reader.context(), 0, static_cast<int>(tx), static_cast<int>(ty), 0, 0, &chunk));
      decode(chunk, tx * grid.tileW, ty * grid.tileH);
    }
  }
}

// One stored sample as a float: half, float or unsigned int, little-endian.
float sampleAt(const std::uint8_t* at, std::uint16_t type) {
  if (type == EXR_PIXEL_HALF) {
    std::uint16_t bits = 0;
    std::memcpy(&bits, at, sizeof bits);
    return imath_half_to_float(bits);
  }
  std::uint32_t bits = 0;
  std::memcpy(&bits, at, sizeof bits);
  if (type == EXR_PIXEL_UINT) return static_cast<float>(bits);
  float value = 0.0f;
  std::memcpy(&value, &bits, sizeof value);
  return value;
}

// A sample as the decoded image keeps it: the float, or a texture's byte.
template <typename Texel>
Texel texel(float sample) {
  if constexpr (std::is_same_v<Texel, float>) {
    return sample;
  } else {
    return linearTexelByte(sample);
  }
}

// Decodes one chunk into the RGB image of the data window (its origin
// at the window's corner). OpenEXR only reads and decompresses; the samples
// are taken from its buffer here (line by line, each channel's samples in
// turn): OpenEXR 3.1's half-to-float routines crashed writing into
// per-channel planes.
template <typename Texel>
void decodeChunk(const ExrReader& reader, const exr_chunk_info_t& chunk, int64_t x0, int64_t y0, int64_t width,
                 int64_t height, const std::vector<std::string>& channels, std::vector<Texel>& rgb,
                 exr_decode_pipeline_t& pipeline, bool& started) {
  if (chunk.width < 0 || chunk.height < 0 || x0 + chunk.width > width || y0 + chunk.height > height) {
    reader.fail("has a chunk outside its data window");
  }
  reader.check(started ? exr_decoding_update(reader.context(), 0, &chunk, &pipeline)
                       : exr_decoding_initialize(reader.context(), 0, &chunk, &pipeline));
  started = true;
  std::size_t lineBytes = 0;
  for (int16_t c = 0; c < pipeline.channel_count; ++c) {
    const exr_coding_channel_info_t& info = pipeline.channels[c];
    if (info.width != chunk.width || info.height != chunk.height) reader.fail("has a channel of another size");
    lineBytes += static_cast<std::size_t>(chunk.width) * static_cast<std::size_t>(info.bytes_per_element);
  }
  reader.check(exr_decoding_choose_default_routines(reader.context(), 0, &pipeline));
  reader.check(exr_decoding_run(reader.context(), 0, &pipeline));
  const auto* data = static_cast<const std::uint8_t*>(pipeline.unpacked_buffer);
  if (!data || chunk.unpacked_size < lineBytes * static_cast<std::size_t>(chunk.height)) {
    reader.fail("has a chunk smaller than its pixels");
  }
  for (int64_t y = 0; y < chunk.height; ++y) {
    for (int16_t c = 0; c < pipeline.channel_count; ++c) {
      const exr_coding_channel_info_t& info = pipeline.channels[c];
      for (std::size_t k = 0; k < channels.size(); ++k) {
        if (channels[k] != info.channel_name) continue;
        for (int64_t x = 0; x < chunk.width; ++x) {
          rgb[static_cast<std::size_t>(((y0 + y) * width + x0 + x) * 3) + k] =
              texel<Texel>(sampleAt(data + x * info.bytes_per_element, info.data_type));
        }
      }
      data += static_cast<std::size_t>(chunk.width) * static_cast<std::size_t>(info.bytes_per_element);
    }
  }
}

template <typename Texel>
std::vector<Texel> decodeExrTexels(std::string_view bytes, const std::string& place, const DecodeAdmit& admit, int& w,
                                   int& h) {
  const ExrReader reader(bytes, place);
  int parts = 0;
  reader.check(exr_get_count(reader.context(), &parts));
  if (parts != 1) reader.fail("has " + std::to_string(parts) + " parts; Glint reads images of one");
  exr_attr_box2i_t window{};
  reader.check(exr_get_data_window(reader.context(), 0, &window));
  const int64_t width = int64_t{window.max.x} - window.min.x + 1, height = int64_t{window.max.y} - window.min.y + 1;
  if (width <= 0 || height <= 0 || width > INT32_MAX || height > INT32_MAX) reader.fail("has an empty data window");
  const std::vector<std::string> channels = colourChannels(reader);
  const ChunkGrid grid = chunkGrid(reader, width, height, bytes.size());
  // OpenEXR holds a chunk's packed and its unpacked samples while decoding it.
  admit(static_cast<int>(width), static_cast<int>(height), 2 * grid.largestPixels * sampleBytes(reader));
  std::vector<Texel> rgb(static_cast<std::size_t>(width * height * 3), Texel{});
  exr_decode_pipeline_t pipeline{};
  bool started = false;
  try {
    forEachChunk(reader, window, grid, [&](const exr_chunk_info_t& chunk, int64_t x, int64_t y) {
      decodeChunk(reader, chunk, x, y, width, height, channels, rgb, pipeline, started);
    });
  } catch (...) {
    if (started) exr_decoding_destroy(reader.context(), &pipeline);
    throw;
  }
  if (started) exr_decoding_destroy(reader.context(), &pipeline);
  w = static_cast<int>(width);
  h = static_cast<int>(height);
  return rgb;
}

}  // namespace

bool looksLikeExr(std::string_view bytes) {
  return bytes.starts_with("\x76\x2f\x31\x01");
}

FloatPixels decodeExrLinear(std::string_view bytes, const std::string& place, const DecodeAdmit& admit) {
  FloatPixels pixels;
  pixels.rgb = decodeExrTexels<float>(bytes, place, admit, pixels.width, pixels.height);
  return pixels;
}

Image decodeExr(std::string_view bytes, const std::string& place, const DecodeAdmit& admit) {
  Image image;
  image.rgb = decodeExrTexels<std::uint8_t>(bytes, place, admit, image.width, image.height);
  return image;
}

}  // namespace glint

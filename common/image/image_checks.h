#pragma once

#include <string>
#include <string_view>

namespace glint {

// Checks of a file's structure against its header, made before stb_image
// decodes it: stb_image allocates what a header announces and fills what
// the data lacks with zeros, so a small file could cost the memory and time
// of a large image. Each throws an InputError starting with `place`.

// Every chunk of a PNG lies within the file (stb_image grows its buffer by
// the length a chunk claims before reading it).
void checkPngChunks(std::string_view bytes, const std::string& place);

// An uncompressed BMP holds the rows its header announces.
void checkBmpRows(std::string_view bytes, int width, int height, const std::string& place);

// A Radiance HDR file holds every scanline its header announces, each read
// as stb_image reads it: run-length encoded (a 4-byte row header, then each
// of the 4 channels' runs up to the width) or flat (4 bytes a pixel).
void checkRadianceRows(std::string_view bytes, int width, int height, const std::string& place);

}  // namespace glint

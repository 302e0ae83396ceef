#pragma once

#include <cstddef>
#include <functional>

namespace glint {

// What an image decoder asks before it allocates anything: `admit(width,
// height, heldBytes)` sees the image's size and the bytes the decoder will
// hold meanwhile (its working buffers, freed before it returns), and throws
// to refuse them.
using DecodeAdmit = std::function<void(int width, int height, std::size_t heldBytes)>;

}  // namespace glint

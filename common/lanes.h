#pragma once

#include <cstdint>

namespace glint {

// Four lanes of float arithmetic (GCC / Clang vector extensions: SSE on
// x86-64, NEON on ARM, plain loops elsewhere). Each lane rounds exactly as
// the scalar operation would.
using Float4 = float __attribute__((vector_size(16)));
using Mask4 = std::int32_t __attribute__((vector_size(16)));  // comparisons: all bits set or none
using Int4 = std::int32_t __attribute__((vector_size(16)));   // four integers

}  // namespace glint

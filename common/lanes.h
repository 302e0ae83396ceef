#pragma once

#include <cstdint>
#if defined(__SSE__)
#include <xmmintrin.h>
#endif

namespace glint {

// Four lanes of float arithmetic (GCC / Clang vector extensions: SSE on
// x86-64, NEON on ARM, plain loops elsewhere). Each lane rounds exactly as
// the scalar operation would.
using Float4 = float __attribute__((vector_size(16)));
using Mask4 = std::int32_t __attribute__((vector_size(16)));  // comparisons: all bits set or none
using Int4 = std::int32_t __attribute__((vector_size(16)));   // four integers

// Bit i set where lane i of a comparison's result is true.
inline unsigned laneBits(Mask4 mask) {
#if defined(__SSE__)
  return static_cast<unsigned>(_mm_movemask_ps(reinterpret_cast<__m128>(mask)));  // one instruction
#else
  return static_cast<unsigned>((mask[0] & 1) | (mask[1] & 2) | (mask[2] & 4) | (mask[3] & 8));
#endif
}

}  // namespace glint

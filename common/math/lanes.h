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

// |x| lane by lane (Float4 or Float8) into out: the sign bit cleared, as
// std::abs (NaN too). Vectors by reference: an eight-lane vector is never
// passed or returned by value (see GLINT_AVX2).
template <typename V>
[[gnu::always_inline]] inline void absLanes(const V& x, V& out) {
  using Int = decltype(V{} < V{});
  out = __builtin_bit_cast(V, __builtin_bit_cast(Int, x) & 0x7fffffff);
}

// std::max({|a|, |b|, |c|}) lane by lane into out: the first of the
// largest, NaN as it.
template <typename V>
[[gnu::always_inline]] inline void maxAbsOf3(const V& a, const V& b, const V& c, V& out) {
  V absA, absB, absC;
  absLanes(a, absA);
  absLanes(b, absB);
  absLanes(c, absC);
  const V m = absA < absB ? absB : absA;
  out = m < absC ? absC : m;
}

// Eight lanes, one instruction per operation, for code compiled for CPUs
// with AVX2 and chosen at run time (common/geometry/bvh.h, BoxTestWidth); elsewhere
// the same code runs on Float4, eight lanes in two halves.
using Float8 = float __attribute__((vector_size(32)));
using Mask8 = std::int32_t __attribute__((vector_size(32)));

#if defined(__x86_64__)
// Where a CPU runs eight lanes in one instruction; only code that checked
// avx2Available() may run it. Eight-lane code is always inlined into such a
// function, and takes eight lanes by reference elsewhere (by value, x86-64
// passes them one way with AVX and another without).
#define GLINT_AVX2 [[gnu::target("avx2")]]
inline bool avx2Available() {
  static const bool available = __builtin_cpu_supports("avx2");
  return available;
}
#endif

// Bit i set where lane i of an eight-lane comparison is true, from its two
// halves. Not the one AVX2 instruction: the generic code of the slab and
// leaf tests is compiled without AVX2 (and always inlined into the AVX2
// queries), so GCC may not inline an AVX2 function into it, and the leaf
// test called it three times (a spill and a call each: slower rays).
[[gnu::always_inline]] inline unsigned laneBits(const Mask8& mask) {
  const Mask4 low = __builtin_shufflevector(mask, mask, 0, 1, 2, 3);
  const Mask4 high = __builtin_shufflevector(mask, mask, 4, 5, 6, 7);
  return laneBits(low) | laneBits(high) << 4;
}

// Lanes in a vector type (Float4: 4, Float8: 8).
template <typename V>
constexpr int kLanesOf = static_cast<int>(sizeof(V) / sizeof(float));

}  // namespace glint

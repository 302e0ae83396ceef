#pragma once

#include <array>
#include <cstddef>
#include <type_traits>

namespace glint {

// A hash of a std::array of integers, for unordered maps keyed by a few
// indices or bit patterns (a mesh's corners and vertices).
struct ArrayHash {
  template <typename T, std::size_t N>
  std::size_t operator()(const std::array<T, N>& key) const {
    static_assert(std::is_integral_v<T>);
    std::size_t h = 0;
    for (const T v : key) h = h * 0x9E3779B97F4A7C15ull + static_cast<std::size_t>(static_cast<std::make_unsigned_t<T>>(v));
    return h;
  }
};

}  // namespace glint

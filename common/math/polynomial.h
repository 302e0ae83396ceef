#pragma once

#include <array>
#include <cstddef>

namespace glint {

// sum c[k] x^k by Horner's rule: the same operations in the same order
// everywhere (the series of common/math/power.cpp and common/math/circular.cpp).
template <std::size_t N>
double horner(const std::array<double, N>& c, double x) {
  double p = c[N - 1];
  for (std::size_t k = N - 1; k-- > 0;) p = p * x + c[k];
  return p;
}

}  // namespace glint

#include "common/render/sobol.h"

#include <array>

namespace glint {
namespace {

// The bytes swapped, then the bits within each byte.
std::uint32_t reverseBits(std::uint32_t x) {
  x = __builtin_bswap32(x);
  x = ((x >> 1) & 0x55555555u) | ((x & 0x55555555u) << 1);
  x = ((x >> 2) & 0x33333333u) | ((x & 0x33333333u) << 2);
  return ((x >> 4) & 0x0f0f0f0fu) | ((x & 0x0f0f0f0fu) << 4);
}

// A hash in which each bit depends only on the bits below it (Laine and
// Karras' construction): applied to bit-reversed digits it permutes every
// subtree of the binary expansion, Owen's nested uniform scramble.
std::uint32_t laineKarras(std::uint32_t x, std::uint32_t seed) {
  x += seed;
  x ^= x * 0x6c50b47cu;
  x ^= x * 0xb82f1e52u;
  x ^= x * 0xc7afe638u;
  x ^= x * 0x8d22f6e6u;
  return x;
}

std::uint32_t owenScramble(std::uint32_t x, std::uint32_t seed) {
  return reverseBits(laineKarras(reverseBits(x), seed));
}

// The second Sobol dimension, bit-reversed (as its scramble takes it): its
// generator matrix is Pascal's triangle mod 2, whose column k is the k-th
// direction number. The index's bits pick columns to sum (xor); the sums
// for each byte of the index are tabled.
using ByteTables = std::array<std::array<std::uint32_t, 256>, 4>;
constexpr ByteTables secondDimensionTables() {
  std::array<std::uint32_t, 32> column{};
  std::uint32_t v = 1u;
  for (std::uint32_t& c : column) {
    c = v;
    v ^= v << 1;  // the direction numbers, reversed: 1, 3, 5, 15, ...
  }
  ByteTables tables{};
  for (int byte = 0; byte < 4; ++byte) {
    for (std::uint32_t bits = 0; bits < 256; ++bits) {
      for (int k = 0; k < 8; ++k) {
        if (bits & (1u << k)) tables[byte][bits] ^= column[8 * byte + k];
      }
    }
  }
  return tables;
}
constexpr ByteTables kSecond = secondDimensionTables();

std::uint32_t sobolSecondReversed(std::uint32_t index) {
  return kSecond[0][index & 0xffu] ^ kSecond[1][(index >> 8) & 0xffu] ^ kSecond[2][(index >> 16) & 0xffu] ^
         kSecond[3][index >> 24];
}

// A 32-bit fixed-point fraction as a float below 1 (its top 24 bits).
float fraction(std::uint32_t x) { return static_cast<float>(x >> 8) * 0x1p-24f; }

std::uint32_t hashSeed(std::uint32_t seed, std::uint32_t salt) {
  std::uint32_t h = seed ^ (salt * 0x9e3779b9u);
  h ^= h >> 16;
  h *= 0x7feb352du;
  h ^= h >> 15;
  h *= 0x846ca68bu;
  return h ^ (h >> 16);
}

}  // namespace

glm::vec2 scrambledSobol(std::uint32_t index, std::uint32_t seed) {
  const std::uint32_t shuffled = owenScramble(index, seed);
  // The first dimension is the index bit-reversed (van der Corput's), so
  // its scramble needs no reversal going in.
  return {fraction(reverseBits(laineKarras(shuffled, hashSeed(seed, 1)))),
          fraction(reverseBits(laineKarras(sobolSecondReversed(shuffled), hashSeed(seed, 2))))};
}

}  // namespace glint

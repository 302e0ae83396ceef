#pragma once

#include <cstdint>

#include <glm/vec2.hpp>

namespace glint {

// Point `index` of the two-dimensional Sobol sequence (a (0,2)-sequence in
// base 2: each power-of-two run of points puts one in every elementary
// interval of its area), with the index shuffled and each coordinate
// Owen-scrambled by hashing with `seed` (Burley, "Practical Hash-based Owen
// Scrambling", JCGT 2020, with Vegdahl's hash constants). The shuffle maps
// indices 0 to 2^k - 1 onto one aligned block of 2^k indices, and such a
// block of the sequence is a (0,2)-net: the first 2^k points of any seed
// are a scrambled net. Distinct seeds give independent sequences. In [0, 1)^2.
glm::vec2 scrambledSobol(std::uint32_t index, std::uint32_t seed);

}  // namespace glint

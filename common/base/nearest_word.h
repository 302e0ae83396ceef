#pragma once

#include <cstddef>
#include <span>
#include <string>
#include <string_view>

namespace glint {

// Edits (insertions, deletions, substitutions) that turn `a` into `b`
// (Levenshtein distance).
std::size_t editDistance(std::string_view a, std::string_view b);

// The word of `known` nearest to `typed`, if it is a likely misspelling of
// it: at most `kMostEdits` edits away, and fewer than the word is long
// ("rendr" -> "render"). Empty when none is; the first of equals wins.
constexpr std::size_t kMostEdits = 2;
std::string nearestWord(std::string_view typed, std::span<const std::string> known);

// The first of `args` that looks like an option ("--name[=value]" or "-x")
// and is none of `known`, in a usage error's words: "PROGRAM has no option
// --sampels; did you mean --samples?". Empty when every one is known.
std::string unknownOption(std::string_view program, std::span<const std::string> args,
                          std::span<const std::string> known);

}  // namespace glint

#pragma once

#include <array>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace glint {

// The words of an enum as users write them (scene files, the command line,
// --help, errors, stats): one table per enum, specialised next to the enum as
//   template <> struct EnumWords<FilterType> {
//     static constexpr std::array<std::pair<FilterType, std::string_view>, 4> kWords{...};
//   };
// and read only through the functions below.
template <typename Enum>
struct EnumWords;

template <typename Enum>
std::optional<Enum> enumFromWord(std::string_view word) {
  for (const auto& [value, w] : EnumWords<Enum>::kWords) {
    if (w == word) return value;
  }
  return std::nullopt;
}

template <typename Enum>
std::string_view enumWord(Enum value) {
  for (const auto& [v, w] : EnumWords<Enum>::kWords) {
    if (v == value) return w;
  }
  return "?";
}

template <typename Enum>
std::vector<std::string> enumWordList() {
  std::vector<std::string> words;
  for (const auto& entry : EnumWords<Enum>::kWords) words.emplace_back(entry.second);
  return words;
}

// "box, tent, gaussian, mitchell": for errors and --help.
template <typename Enum>
std::string enumWordsJoined() {
  std::string out;
  for (const auto& entry : EnumWords<Enum>::kWords) {
    if (!out.empty()) out += ", ";
    out.append(entry.second);
  }
  return out;
}

}  // namespace glint

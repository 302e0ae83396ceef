#include "common/scene/obj_colors.h"

#include <charconv>
#include <cstddef>

namespace glint {
namespace {

constexpr int kWithColor = 6;  // x y z r g b

bool blank(char c) {
  return c == ' ' || c == '\t' || c == '\r';
}

// The numbers of a `v` line's rest, up to kWithColor; how many were read.
int vertexNumbers(std::string_view line, float (&out)[kWithColor]) {
  int n = 0;
  std::size_t at = 0;
  while (n < kWithColor) {
    while (at < line.size() && blank(line[at])) ++at;
    if (at == line.size()) break;
    const auto [end, error] = std::from_chars(line.data() + at, line.data() + line.size(), out[n]);
    if (error != std::errc()) break;
    at = static_cast<std::size_t>(end - line.data());
    ++n;
  }
  return n;
}

// Calls f(rest) for each `v` line (the text after "v"), until f returns false.
template <typename F>
void eachVertexLine(std::string_view text, F f) {
  for (std::size_t at = 0; at < text.size();) {
    std::size_t end = text.find('\n', at);
    if (end == std::string_view::npos) end = text.size();
    std::string_view line = text.substr(at, end - at);
    at = end + 1;
    while (!line.empty() && blank(line.front())) line.remove_prefix(1);
    if (line.size() >= 2 && line[0] == 'v' && (line[1] == ' ' || line[1] == '\t') && !f(line.substr(2))) return;
  }
}

}  // namespace

std::vector<float> objVertexColors(std::string_view text) {
  float numbers[kWithColor];
  bool colored = false;
  eachVertexLine(text, [&](std::string_view rest) {
    colored = vertexNumbers(rest, numbers) == kWithColor;
    return false;  // the first line decides
  });
  std::vector<float> colors;
  if (!colored) return colors;
  eachVertexLine(text, [&](std::string_view rest) {
    const bool has = vertexNumbers(rest, numbers) == kWithColor;
    colors.insert(colors.end(), {has ? numbers[3] : 1.0f, has ? numbers[4] : 1.0f, has ? numbers[5] : 1.0f});
    return true;
  });
  return colors;
}

}  // namespace glint

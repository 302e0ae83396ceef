#include "common/base/nearest_word.h"

#include <algorithm>
#include <cctype>
#include <optional>
#include <vector>

namespace glint {

std::size_t editDistance(std::string_view a, std::string_view b) {
  // One row of the Wagner-Fischer table at a time.
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t above = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = above;
    }
  }
  return row[b.size()];
}

std::string nearestWord(std::string_view typed, std::span<const std::string> known) {
  std::string best;
  std::size_t bestDistance = kMostEdits + 1;
  for (const std::string& word : known) {
    const std::size_t d = editDistance(typed, word);
    if (d < bestDistance && d < word.size()) {
      bestDistance = d;
      best = word;
    }
  }
  return best;
}

namespace {

// An argument that looks like an option: "--name[=value]" or "-x".
std::optional<std::string> optionName(const std::string& arg) {
  if (arg.rfind("--", 0) == 0 && arg.size() > 2) return arg.substr(0, arg.find('='));
  if (arg.size() == 2 && arg[0] == '-' && std::isalpha(static_cast<unsigned char>(arg[1]))) return arg;
  return std::nullopt;
}

}  // namespace

std::string unknownOption(std::string_view program, std::span<const std::string> args,
                          std::span<const std::string> known) {
  for (const std::string& arg : args) {
    const std::optional<std::string> name = optionName(arg);
    if (!name || std::find(known.begin(), known.end(), *name) != known.end()) continue;
    const std::string near = nearestWord(*name, known);
    return std::string(program) + " has no option " + *name + (near.empty() ? "" : "; did you mean " + near + "?");
  }
  return {};
}

}  // namespace glint

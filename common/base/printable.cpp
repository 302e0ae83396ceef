#include "common/base/printable.h"

#include <cstdio>

namespace glint {

std::string printable(std::string_view text, std::size_t limit) {
  std::string out;
  const std::string_view kept = text.substr(0, limit);
  out.reserve(kept.size());
  for (const char c : kept) {
    const auto byte = static_cast<unsigned char>(c);
    if (c == '\\') {
      out += "\\\\";
    } else if (c == '\n') {
      out += "\\n";
    } else if (c == '\r') {
      out += "\\r";
    } else if (c == '\t') {
      out += "\\t";
    } else if (byte < 0x20 || byte == 0x7f || (byte >= 0x80 && byte <= 0x9f)) {
      char hex[5];
      std::snprintf(hex, sizeof hex, "\\x%02x", byte);
      out += hex;
    } else {
      out += c;
    }
  }
  if (text.size() > kept.size())
    out += "... (" + std::to_string(text.size() - kept.size()) + " more bytes)";
  return out;
}

}  // namespace glint

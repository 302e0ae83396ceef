#pragma once

#include <cstddef>
#include <string>
#include <string_view>

namespace glint {

// Text from the other end of a connection made fit for a terminal or a log
// line: control characters (bytes below 0x20, 0x7f and the 8-bit controls
// 0x80-0x9f, a terminal's escape sequences among them) written as \n, \r,
// \t or \xHH, so that a line stays one line and cannot forge another or
// drive the terminal; a backslash as \\, so that the escapes are unambiguous;
// cut after `limit` bytes of the text with "... (N more bytes)".
constexpr std::size_t kPrintableLimit = 2000;
std::string printable(std::string_view text, std::size_t limit = kPrintableLimit);

}  // namespace glint

#include "common/base/printable.h"

#include <gtest/gtest.h>

namespace glint {
namespace {

TEST(Printable, PlainTextPassesUnchanged) {
  EXPECT_EQ(printable("scene 1a2b: materials.gold: unknown key 'colour'"),
            "scene 1a2b: materials.gold: unknown key 'colour'");
  EXPECT_EQ(printable("caf\xc3\xa9"), "caf\xc3\xa9");  // UTF-8 outside the control range
}

// A forged log line stays on its line; a terminal's escape sequence (ESC,
// and the 8-bit CSI 0x9b) is written out, not sent.
TEST(Printable, ControlCharactersAreEscaped) {
  EXPECT_EQ(printable("key\n2026-12-03T00:00:00.000Z glintd: stopped"),
            "key\\n2026-12-03T00:00:00.000Z glintd: stopped");
  EXPECT_EQ(printable("\x1b[2J\x9b"
                      "31m\r\t\x7f"),
            "\\x1b[2J\\x9b31m\\r\\t\\x7f");
  EXPECT_EQ(printable(std::string("a\0b", 3)), "a\\x00b");
  EXPECT_EQ(printable("a\\nb"), "a\\\\nb");  // a backslash the text holds is not an escape
}

TEST(Printable, LongTextIsCut) {
  const std::string huge(62'900'000, 'x');
  const std::string out = printable(huge);
  EXPECT_EQ(out, std::string(kPrintableLimit, 'x') + "... (62898000 more bytes)");
  EXPECT_EQ(printable("abcdef", 3), "abc... (3 more bytes)");
}

}  // namespace
}  // namespace glint

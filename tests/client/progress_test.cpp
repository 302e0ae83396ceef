// A frame's progress line: what it prints, where and when, with time as
// an input.
#include "client/commands/progress.h"

#include <gtest/gtest.h>

namespace glint {
namespace {

using Clock = ProgressLine::Clock;
using std::chrono::milliseconds;

// What a progress line wrote to its file, once it is gone.
class Written {
 public:
  Written() : file_(std::tmpfile()) {}
  ~Written() { std::fclose(file_); }
  std::FILE* file() { return file_; }
  std::string text() {
    std::fflush(file_);
    std::rewind(file_);
    std::string s;
    for (int c; (c = std::fgetc(file_)) != EOF;) s.push_back(static_cast<char>(c));
    return s;
  }

 private:
  std::FILE* file_;
};

const Clock::time_point t0{};

TEST(ProgressLine, OnATerminalALongFrameIsRedrawnInPlaceAndClearedAtTheEnd) {
  Written out;
  {
    ProgressLine line(ProgressMode::kAuto, out.file(), true, "rendering", t0);
    line.update(1, 10, {}, t0 + milliseconds(500));  // under a second: nothing
    EXPECT_EQ(out.text(), "");
    line.update(
        4, 10, [] { return std::string("a 25 %, b 75 %"); }, t0 + milliseconds(2000));
  }
  EXPECT_EQ(out.text(), "\r\033[Krendering: 4/10 pixels (40 %), 2.0 s, about 3 s left; a 25 %, b 75 %\r\033[K");
}

TEST(ProgressLine, OffATerminalOnlyProgressPrintsLinesAtMostOneASecondAndTheLast) {
  Written automatic;
  {
    ProgressLine line(ProgressMode::kAuto, automatic.file(), false, "rendering", t0);
    line.update(5, 10, {}, t0 + milliseconds(3000));
  }
  EXPECT_EQ(automatic.text(), "");  // a log is not a terminal

  Written forced;
  {
    ProgressLine line(ProgressMode::kForced, forced.file(), false, "frame 2 of 3", t0);
    line.update(1, 4, {}, t0 + milliseconds(100));
    line.update(2, 4, {}, t0 + milliseconds(600));  // within a second of the last line
    line.update(3, 4, {}, t0 + milliseconds(1200));
    line.update(4, 4, {}, t0 + milliseconds(1300));  // the last: always
  }
  EXPECT_EQ(forced.text(),
            "frame 2 of 3: 1/4 pixels (25 %), 0.1 s\n"
            "frame 2 of 3: 3/4 pixels (75 %), 1.2 s, about 1 s left\n"
            "frame 2 of 3: 4/4 pixels (100 %), 1.3 s\n");
}

// The time left comes from the pace of the units after the first: a first
// unit that arrives late (the set-up, a server's latency) says nothing of the
// rest, and one unit is no pace.
TEST(ProgressLine, TheTimeLeftWaitsForThePaceOfTheUnits) {
  Written out;
  {
    ProgressLine line(ProgressMode::kForced, out.file(), false, "rendering", t0);
    line.update(1, 100, {}, t0 + milliseconds(680));    // the first, after the set-up
    line.update(2, 100, {}, t0 + milliseconds(1690));   // one more: no pace yet
    line.update(41, 100, {}, t0 + milliseconds(2700));  // 40 in 2.02 s: 59 x 50.5 ms left
    line.update(100, 100, {}, t0 + milliseconds(5700));
  }
  EXPECT_EQ(out.text(),
            "rendering: 1/100 pixels (1 %), 0.7 s\n"
            "rendering: 2/100 pixels (2 %), 1.7 s\n"
            "rendering: 41/100 pixels (41 %), 2.7 s, about 3 s left\n"
            "rendering: 100/100 pixels (100 %), 5.7 s\n");
}

// An irradiance field's probes, counted in their own word; the line is
// cleared when the step is over, before the frame's own line is drawn.
TEST(ProgressLine, CountsItsOwnUnitsAndIsClearedWhenTheStepEnds) {
  Written out;
  ProgressLine line(ProgressMode::kForced, out.file(), true, "irradiance field", t0, "probes");
  line.update(512, 1024, {}, t0 + milliseconds(1500));
  line.clear();
  EXPECT_EQ(out.text(), "\r\033[Kirradiance field: 512/1024 probes (50 %), 1.5 s\r\033[K");
  line.clear();  // nothing drawn since: nothing to clear
  EXPECT_EQ(out.text(), "\r\033[Kirradiance field: 512/1024 probes (50 %), 1.5 s\r\033[K");
}

TEST(ProgressLine, QuietPrintsNothingAnywhere) {
  Written out;
  {
    ProgressLine terminal(ProgressMode::kQuiet, out.file(), true, "rendering", t0);
    terminal.update(5, 10, {}, t0 + milliseconds(5000));
    ProgressLine log(ProgressMode::kQuiet, out.file(), false, "rendering", t0);
    log.update(5, 10, {}, t0 + milliseconds(5000));
  }
  EXPECT_EQ(out.text(), "");
}

}  // namespace
}  // namespace glint

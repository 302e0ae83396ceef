// The perceptual rule's colour edges: neighbours OpenGL shades whose colours
// differ visibly are both marked, a faint difference is not, masked pixels
// are neither compared nor re-marked.
#include "client/raster/colour_edges.h"

#include <vector>

#include <gtest/gtest.h>

#include "client/raster/pixel_mark.h"

namespace glint {
namespace {

// A 6 x 4 frame whose left three columns are `left` and right three `right` (grey bytes).
std::vector<std::uint8_t> halves(std::uint8_t left, std::uint8_t right) {
  std::vector<std::uint8_t> rgb;
  for (int y = 0; y < 4; ++y) {
    for (int x = 0; x < 6; ++x) rgb.insert(rgb.end(), 3, x < 3 ? left : right);
  }
  return rgb;
}

TEST(ColourEdges, AVisibleStepMarksBothSides) {
  std::vector<std::uint8_t> marks(24, kRasterPixel);
  EXPECT_EQ(markColourEdges(halves(60, 200), 6, 4, 0.3f, marks), 8u);
  for (int y = 0; y < 4; ++y) {
    for (int x = 0; x < 6; ++x) {
      EXPECT_EQ(marks[static_cast<std::size_t>(y * 6 + x)], x == 2 || x == 3 ? kRasterEdgePixel : kRasterPixel);
    }
  }
}

TEST(ColourEdges, AFaintStepIsLeftToTheRaster) {
  std::vector<std::uint8_t> marks(24, kRasterPixel);
  EXPECT_EQ(markColourEdges(halves(128, 130), 6, 4, 0.3f, marks), 0u);
  EXPECT_EQ(markColourEdges(halves(128, 130), 6, 4, 0.02f, marks), 8u);  // unless the threshold is lower
}

TEST(ColourEdges, MaskedPixelsAreNotCompared) {
  std::vector<std::uint8_t> marks(24, kRasterPixel);
  for (int y = 0; y < 4; ++y) marks[static_cast<std::size_t>(y * 6 + 3)] = kMaskedPixel;  // the right side's first column
  EXPECT_EQ(markColourEdges(halves(60, 200), 6, 4, 0.3f, marks), 0u);
  for (int y = 0; y < 4; ++y) EXPECT_EQ(marks[static_cast<std::size_t>(y * 6 + 3)], kMaskedPixel);
  marks.assign(24, kRasterPixel);
  marks[2] = kShadowEdgePixel;  // traced already: stays as it is
  EXPECT_EQ(markColourEdges(halves(60, 200), 6, 4, 0.3f, marks), 7u);
  EXPECT_EQ(marks[2], kShadowEdgePixel);
}

TEST(ColourEdges, SizesMustMatch) {
  std::vector<std::uint8_t> marks(23, kRasterPixel);
  EXPECT_THROW(markColourEdges(halves(0, 0), 6, 4, 0.3f, marks), std::invalid_argument);
}

}  // namespace
}  // namespace glint

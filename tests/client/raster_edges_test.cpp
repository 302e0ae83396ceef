// The raster's edges, found from each pixel's object and depth alone.
#include "client/raster/raster_edges.h"

#include <vector>

#include <gtest/gtest.h>

#include "client/raster/pixel_mark.h"

namespace glint {
namespace {

constexpr int kW = 8, kH = 6;

struct Raster {
  std::vector<std::uint32_t> surface = std::vector<std::uint32_t>(kW * kH, 0);
  std::vector<float> depth = std::vector<float>(kW * kH, 1.0f);
  std::vector<std::uint8_t> marks = std::vector<std::uint8_t>(kW * kH, 0);
  void set(int x, int y, std::uint32_t object, float d, std::uint8_t mark = kRasterPixel) {
    surface[static_cast<std::size_t>(y * kW + x)] = object << kPixelMarkBits | mark;
    depth[static_cast<std::size_t>(y * kW + x)] = d;
  }
  std::size_t mark() { return markRasterEdges(surface, depth, kW, kH, marks); }
  std::uint8_t at(int x, int y) const { return marks[static_cast<std::size_t>(y * kW + x)]; }
};

// A plane seen at a slant: depth changes linearly across the frame.
TEST(RasterEdges, APlaneHasNone) {
  Raster r;
  for (int y = 0; y < kH; ++y) {
    for (int x = 0; x < kW; ++x) r.set(x, y, 1, 10.0f + 0.5f * x + 0.25f * y);
  }
  EXPECT_EQ(r.mark(), 0u);
  for (std::uint8_t m : r.marks) EXPECT_EQ(m, kRasterPixel);
}

// Two objects side by side: both pixels of each pair across the boundary.
TEST(RasterEdges, ObjectsMeetAtAnEdge) {
  Raster r;
  for (int y = 0; y < kH; ++y) {
    for (int x = 0; x < kW; ++x) r.set(x, y, x < 3 ? 1 : 2, 10.0f);
  }
  EXPECT_EQ(r.mark(), static_cast<std::size_t>(2 * kH));
  for (int y = 0; y < kH; ++y) {
    for (int x = 0; x < kW; ++x) EXPECT_EQ(r.at(x, y), x == 2 || x == 3 ? kRasterEdgePixel : kRasterPixel) << x << "," << y;
  }
}

// One object folded over itself: its depth jumps between rows 2 and 3
// (an occluding contour); a crease where the slope turns sharply between
// two pixels is an edge too, a gentle curve is not.
TEST(RasterEdges, DepthJumpsAndCreases) {
  Raster jump;
  for (int y = 0; y < kH; ++y) {
    for (int x = 0; x < kW; ++x) jump.set(x, y, 1, y < 3 ? 10.0f + 0.1f * y : 20.0f + 0.1f * y);
  }
  EXPECT_EQ(jump.mark(), static_cast<std::size_t>(2 * kW));
  EXPECT_EQ(jump.at(4, 2), kRasterEdgePixel);
  EXPECT_EQ(jump.at(4, 3), kRasterEdgePixel);
  EXPECT_EQ(jump.at(4, 1), kRasterPixel);

  Raster crease, curve;
  for (int y = 0; y < kH; ++y) {
    for (int x = 0; x < kW; ++x) {
      crease.set(x, y, 1, 10.0f + (x < 4 ? 0.0f : 0.5f * (static_cast<float>(x) - 3.5f)));
      curve.set(x, y, 1, 10.0f + 1e-4f * static_cast<float>(x * x));
    }
  }
  EXPECT_EQ(crease.mark(), static_cast<std::size_t>(2 * kH));
  EXPECT_EQ(crease.at(3, 0), kRasterEdgePixel);
  EXPECT_EQ(crease.at(4, 0), kRasterEdgePixel);
  EXPECT_EQ(crease.at(2, 0), kRasterPixel);
  EXPECT_EQ(curve.mark(), 0u);
}

// The background beside an object is an edge; the background beside the
// background is not.
TEST(RasterEdges, SilhouettesAgainstTheBackground) {
  Raster r;
  r.set(4, 3, 1, 5.0f);
  EXPECT_EQ(r.mark(), 5u);  // the pixel and its four neighbours
  EXPECT_EQ(r.at(4, 3), kRasterEdgePixel);
  EXPECT_EQ(r.at(3, 3), kRasterEdgePixel);
  EXPECT_EQ(r.at(0, 0), kRasterPixel);
}

// A pixel beside a masked one is traced as the masked pixels are (its
// samples on the masked object see that object's reflections); pixels the
// raster marked for tracing keep their marks.
TEST(RasterEdges, TracedPixelsKeepTheirMarksAndLendThemToTheirNeighbours) {
  Raster r;
  for (int y = 0; y < kH; ++y) {
    for (int x = 0; x < kW; ++x) r.set(x, y, x < 4 ? 1 : 2, 10.0f, x < 4 ? kRasterPixel : kMaskedPixel);
  }
  r.set(1, 1, 1, 10.0f, kShadowEdgePixel);
  r.set(0, 1, 3, 10.0f);  // another object beside the shadow edge
  EXPECT_EQ(r.mark(), static_cast<std::size_t>(kH + 3));  // column 3; (0, 1) and the pixels above and below it
  for (int y = 0; y < kH; ++y) {
    EXPECT_EQ(r.at(3, y), kMaskedPixel);
    EXPECT_EQ(r.at(4, y), kMaskedPixel);
  }
  EXPECT_EQ(r.at(1, 1), kShadowEdgePixel);
  EXPECT_EQ(r.at(0, 1), kRasterEdgePixel);
  EXPECT_EQ(r.at(0, 0), kRasterEdgePixel);
  EXPECT_EQ(r.at(0, 2), kRasterEdgePixel);
}

TEST(RasterEdges, RefusesBuffersOfAnotherSize) {
  Raster r;
  r.depth.pop_back();
  EXPECT_THROW(r.mark(), std::invalid_argument);
}

}  // namespace
}  // namespace glint

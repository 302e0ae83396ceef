// FLIP (common/metrics/flip.h): identical images score 0, the paper's
// properties hold, and the mean agrees with NVIDIA's reference
// implementation on the pairs in tests/data/flip.
#include "common/metrics/flip.h"

#include <gtest/gtest.h>

#include "common/base/error.h"
#include "common/image/encoding.h"
#include "common/image/flip_colour.h"
#include "common/image/image_read.h"
#include "tests/support/test_support.h"

namespace glint {
namespace {

LinearImage flat(int width, int height, float r, float g, float b) {
  LinearImage image{width, height, {}};
  for (int i = 0; i < width * height; ++i) image.rgb.insert(image.rgb.end(), {r, g, b});
  return image;
}

LinearImage fixture(const std::string& name) {
  return displayedLight(readImageFile(test::sourcePath("tests/data/flip/" + name + ".png")));
}

double meanFlip(const LinearImage& reference, const LinearImage& test, double ppd = kFlipPixelsPerDegree) {
  return flipStats(flip(reference, test, ppd)).mean;
}

TEST(Flip, IdenticalImagesScoreZero) {
  const LinearImage image = fixture("room_full");
  const FlipMap map = flip(image, image);
  ASSERT_EQ(map.error.size(), 96u * 64u);
  for (const float e : map.error) ASSERT_EQ(e, 0.0f);
}

TEST(Flip, ImagesOfDifferentSizesAreAnError) {
  EXPECT_THROW(flip(flat(4, 4, 0, 0, 0), flat(4, 5, 0, 0, 0)), InputError);
}

// NVIDIA's FLIP tool 1.6 (github.com/NVlabs/flip, built from its C++ source,
// `flip -r REFERENCE.png -t TEST.png [-ppd 30]`) on the PNGs of
// tests/data/flip: its printed means. The pairs stress the colour term (red
// and green traded on half a gradient), edges (a blurred checker), points
// (single bright pixels on grey) and a render (the hybrid frame of the room
// against the 16-sample full trace).
TEST(Flip, MeanAgreesWithTheReferenceImplementation) {
  struct Pair {
    const char* reference;
    const char* test;
    double ppd;
    double mean;
  };
  const Pair pairs[] = {{"gradient", "gradient_shifted", kFlipPixelsPerDegree, 0.381952},
                        {"checker", "checker_blurred", kFlipPixelsPerDegree, 0.149318},
                        {"checker", "checker_blurred", 30.0, 0.223270},
                        {"flat", "dotted", kFlipPixelsPerDegree, 0.081237},
                        {"flat", "dotted", 30.0, 0.051512},
                        {"room_full", "room_hybrid", kFlipPixelsPerDegree, 0.043208}};
  for (const Pair& p : pairs) {
    const double mean = meanFlip(fixture(p.reference), fixture(p.test), p.ppd);
    EXPECT_NEAR(mean, p.mean, 1e-4 * p.mean) << p.reference << " / " << p.test << " at " << p.ppd << " ppd";
  }
}

// HDR-FLIP on two EXR renders of the room at +2 EV (16 samples against 1,
// linear, the brightest pixels above 1): NVIDIA's tool 1.6 (`flip -r
// room_full.exr -t room_one_sample.exr`) prints start exposure -1.2532, stop
// 0.5584, 2 exposures and a mean of 0.080763.
TEST(Flip, HdrFlipAgreesWithTheReferenceImplementation) {
  const LinearImage reference = readImageFile(test::sourcePath("tests/data/flip/room_full.exr")).values;
  const LinearImage test = readImageFile(test::sourcePath("tests/data/flip/room_one_sample.exr")).values;
  const HdrExposures e = hdrExposures(reference);
  EXPECT_NEAR(e.start, -1.2532, 1e-4);
  EXPECT_NEAR(e.stop, 0.5584, 1e-4);
  EXPECT_EQ(e.count, 2);
  EXPECT_NEAR(flipStats(hdrFlip(reference, test, e)).mean, 0.080763, 1e-4 * 0.080763);
  EXPECT_EQ(hdrExposures(flat(4, 4, 0, 0, 0)).count, 0);  // no median luminance: no range
}

// HyAB in L*a*b*: a colour further from the reference scores more.
TEST(Flip, ErrorGrowsWithColourDistance) {
  const LinearImage grey = flat(32, 32, 0.2f, 0.2f, 0.2f);
  double last = 0.0;
  for (const float red : {0.22f, 0.3f, 0.45f, 0.7f}) {
    const double mean = meanFlip(grey, flat(32, 32, red, 0.2f, 0.2f));
    EXPECT_GT(mean, last) << red;
    last = mean;
  }
}

// The Hunt effect: the same change of chromaticity weighs less in the dark.
TEST(Flip, ChromaWeighsLessInTheDark) {
  const double dark = meanFlip(flat(32, 32, 0.02f, 0.01f, 0.01f), flat(32, 32, 0.01f, 0.02f, 0.01f));
  const double bright = meanFlip(flat(32, 32, 0.6f, 0.3f, 0.3f), flat(32, 32, 0.3f, 0.6f, 0.3f));
  EXPECT_LT(dark, 0.5 * bright);
}

// Edges: a step moved by two pixels is an error along the step and nowhere
// far from it.
TEST(Flip, AMovedEdgeIsAnErrorAlongIt) {
  LinearImage a = flat(64, 32, 0.1f, 0.1f, 0.1f), b = a;
  for (int y = 0; y < 32; ++y) {
    for (int x = 0; x < 64; ++x) {
      for (int k = 0; k < 3; ++k) {
        a.rgb[static_cast<std::size_t>((y * 64 + x) * 3 + k)] = x >= 30 ? 0.8f : 0.1f;
        b.rgb[static_cast<std::size_t>((y * 64 + x) * 3 + k)] = x >= 32 ? 0.8f : 0.1f;
      }
    }
  }
  const FlipMap map = flip(a, b);
  EXPECT_GT(map.error[16 * 64 + 31], 0.5f);
  EXPECT_LT(map.error[16 * 64 + 2], 0.01f);
  EXPECT_LT(map.error[16 * 64 + 60], 0.01f);
}

// Point features: a single bright pixel on grey scores more at the point
// than a bright pixel inside a field of them (where the point is expected).
TEST(Flip, IsolatedPointsRaiseTheError) {
  const LinearImage grey = flat(32, 32, 0.2f, 0.2f, 0.2f);
  LinearImage dot = grey;
  for (int k = 0; k < 3; ++k) dot.rgb[static_cast<std::size_t>((16 * 32 + 16) * 3 + k)] = 1.0f;
  const FlipMap map = flip(grey, dot);
  EXPECT_GT(map.error[16 * 32 + 16], 0.3f);
  EXPECT_EQ(map.error[2 * 32 + 2], 0.0f);
}

// The perceptual pattern's test: grey 128 against 130 (8-bit, through sRGB)
// is below a just noticeable difference, black against white far above;
// at the threshold 1, green against blue (the largest difference) is not
// above it, and anything is above 0.
TEST(Flip, VisibleDifferenceFollowsTheColourTerm) {
  const auto lab = [](float byte) {
    const float v = srgbDecode(byte / 255.0f);
    return flipLab({v, v, v});
  };
  EXPECT_FALSE(VisibleDifference(0.3f)(lab(128), lab(130)));
  EXPECT_TRUE(VisibleDifference(0.02f)(lab(128), lab(130)));
  EXPECT_TRUE(VisibleDifference(1e-6f)(lab(128), lab(129)));
  // Black against white: HyAB 100, compressed 100^0.7 = 25.1 of green
  // against blue's 41.4, above the cut at 0.4 of it (16.6): 0.95 + 0.05 x
  // (25.1 - 16.6) / (41.4 - 16.6) = 0.967, from the paper's mapping.
  EXPECT_TRUE(VisibleDifference(0.96f)(lab(0), lab(255)));
  EXPECT_FALSE(VisibleDifference(0.975f)(lab(0), lab(255)));
  EXPECT_FALSE(VisibleDifference(1.0f)(flipLab({0, 1, 0}), flipLab({0, 0, 1})));
  EXPECT_TRUE(VisibleDifference(0.99f)(flipLab({0, 1, 0}), flipLab({0, 0, 1})));
}

TEST(Flip, PercentilesAreNearestRanks) {
  FlipMap map{10, 10, std::vector<float>(100)};
  for (int i = 0; i < 100; ++i) map.error[static_cast<std::size_t>(i)] = static_cast<float>(99 - i) / 100.0f;
  const FlipStats stats = flipStats(map);
  EXPECT_NEAR(stats.mean, 0.495, 1e-6);
  EXPECT_FLOAT_EQ(static_cast<float>(stats.p95), 0.94f);
  EXPECT_FLOAT_EQ(static_cast<float>(stats.p99), 0.98f);
}

TEST(Flip, MagmaRunsFromBlackToPaleYellow) {
  const FrameImage image = magmaImage({3, 1, {0.0f, 0.5f, 1.0f}});
  EXPECT_LT(image.rgb[0] + image.rgb[1] + image.rgb[2], 6);
  EXPECT_GT(image.rgb[3], image.rgb[5]);  // mid: red above blue (magenta-orange)
  EXPECT_EQ(image.rgb[6], 252);
  EXPECT_EQ(image.rgb[7], 253);
  EXPECT_EQ(image.rgb[8], 191);
}

}  // namespace
}  // namespace glint

#include "common/metrics/flip.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>

#include <glm/common.hpp>
#include <glm/vec3.hpp>

#include "common/base/error.h"
#include "common/image/flip_colour.h"
#include "common/math/power.h"

// The constants and the order of operations follow the paper and agree with
// NVIDIA's reference implementation (github.com/NVlabs/flip, FLIP.h v1.6),
// which filters separably, in single precision, clamping at the borders.
// The colour space is flip_colour's (common/image/flip_colour.h).

namespace glint {
namespace {

using namespace flip_colour;

constexpr float kPi = 3.14159265358979f;
// The paper's parameters: the feature filter's width in degrees, the
// feature exponent (the colour term's are flip_colour's).
constexpr float kFeatureWidthDeg = 0.082f;
constexpr float kFeatureExponent = 0.5f;
// The contrast sensitivity functions as sums of Gaussians a sqrt(pi / b)
// exp(-pi^2 x^2 / b), x in degrees: one each for Y and Cx, two for Cz.
struct Csf {
  float a;
  float b;
};
constexpr Csf kCsfY{1.0f, 0.0047f}, kCsfCx{1.0f, 0.0053f}, kCsfCz1{34.1f, 0.04f}, kCsfCz2{13.5f, 0.025f};
constexpr float kWidestB = 0.04f;

// One channel of an image.
struct Plane {
  int width = 0;
  int height = 0;
  std::vector<float> v;
  float at(int x, int y) const { return v[static_cast<std::size_t>(y) * width + x]; }
};

// Convolves rows (or columns) with a centred kernel, clamping at the borders.
Plane convolve(const Plane& in, const std::vector<float>& kernel, bool rows) {
  Plane out{in.width, in.height, std::vector<float>(in.v.size())};
  const int r = static_cast<int>(kernel.size() / 2);
  for (int y = 0; y < in.height; ++y) {
    for (int x = 0; x < in.width; ++x) {
      float sum = 0.0f;
      for (int i = -r; i <= r; ++i) {
        const int sx = rows ? std::clamp(x + i, 0, in.width - 1) : x;
        const int sy = rows ? y : std::clamp(y + i, 0, in.height - 1);
        sum += kernel[static_cast<std::size_t>(i + r)] * in.at(sx, sy);
      }
      out.v[static_cast<std::size_t>(y) * in.width + x] = sum;
    }
  }
  return out;
}

Plane separable(const Plane& in, const std::vector<float>& alongRows, const std::vector<float>& alongColumns) {
  return convolve(convolve(in, alongRows, true), alongColumns, false);
}

// The three YCxCz channels of an image clamped to [0, 1].
std::array<Plane, 3> toYcxcz(const LinearImage& image) {
  std::array<Plane, 3> planes;
  for (Plane& p : planes) p = {image.width, image.height, std::vector<float>(image.rgb.size() / 3)};
  for (std::size_t i = 0; i < planes[0].v.size(); ++i) {
    const glm::vec3 rgb = glm::clamp(glm::vec3(image.rgb[3 * i], image.rgb[3 * i + 1], image.rgb[3 * i + 2]), 0.0f, 1.0f);
    const glm::vec3 c = xyzToYcxcz(linearToXyz(rgb));
    for (int k = 0; k < 3; ++k) planes[static_cast<std::size_t>(k)].v[i] = c[k];
  }
  return planes;
}

// One Gaussian of a contrast sensitivity function sampled a pixel apart over
// a radius that covers the widest of them to three deviations. `root` takes
// the square root of the amplitude, for a term of a sum that is filtered
// separably as a whole.
std::vector<float> csfKernel(const Csf& csf, double ppd, bool root) {
  const int r = static_cast<int>(std::ceil(3.0f * std::sqrt(kWidestB / (2.0f * kPi * kPi)) * static_cast<float>(ppd)));
  std::vector<float> k(static_cast<std::size_t>(2 * r + 1));
  for (int i = -r; i <= r; ++i) {
    const float x = static_cast<float>(i) / static_cast<float>(ppd);
    const float amplitude = csf.a * std::sqrt(kPi / csf.b);
    k[static_cast<std::size_t>(i + r)] =
        (root ? std::sqrt(amplitude) : amplitude) * std::exp(-kPi * kPi * x * x / csf.b);
  }
  return k;
}

void scale(std::vector<float>& k, float by) {
  for (float& w : k) w *= by;
}

// The colour term of each pixel: both images filtered by the contrast
// sensitivity functions, back to linear RGB clamped to [0, 1], then the
// Hunt-adjusted HyAB distance in L*a*b*, compressed and mapped to [0, 1].
std::vector<float> colourTerm(const std::array<Plane, 3>& ref, const std::array<Plane, 3>& test, double ppd) {
  std::vector<float> kY = csfKernel(kCsfY, ppd, false), kCx = csfKernel(kCsfCx, ppd, false);
  std::vector<float> kCz1 = csfKernel(kCsfCz1, ppd, true), kCz2 = csfKernel(kCsfCz2, ppd, true);
  scale(kY, 1.0f / std::accumulate(kY.begin(), kY.end(), 0.0f));
  scale(kCx, 1.0f / std::accumulate(kCx.begin(), kCx.end(), 0.0f));
  const float s1 = std::accumulate(kCz1.begin(), kCz1.end(), 0.0f), s2 = std::accumulate(kCz2.begin(), kCz2.end(), 0.0f);
  const float czNorm = 1.0f / std::sqrt(s1 * s1 + s2 * s2);
  scale(kCz1, czNorm);
  scale(kCz2, czNorm);
  const auto filtered = [&](const std::array<Plane, 3>& p) {
    Plane cz = separable(p[2], kCz1, kCz1);
    const Plane cz2 = separable(p[2], kCz2, kCz2);
    for (std::size_t i = 0; i < cz.v.size(); ++i) cz.v[i] += cz2.v[i];
    return std::array<Plane, 3>{separable(p[0], kY, kY), separable(p[1], kCx, kCx), cz};
  };
  const std::array<Plane, 3> fr = filtered(ref), ft = filtered(test);
  std::vector<float> term(fr[0].v.size());
  for (std::size_t i = 0; i < term.size(); ++i) {
    const auto lab = [i](const std::array<Plane, 3>& p) {
      const glm::vec3 rgb = glm::clamp(xyzToLinear(ycxczToXyz({p[0].v[i], p[1].v[i], p[2].v[i]})), 0.0f, 1.0f);
      return hunt(xyzToLab(linearToXyz(rgb)));
    };
    term[i] = colourError(hyab(lab(fr), lab(ft)));
  }
  return term;
}

// A Gaussian of deviation half the feature width, its first and second
// derivatives; each derivative's positive and negative weights sum to +1
// and -1, the Gaussian's to 1.
struct FeatureKernels {
  std::vector<float> g, dg, ddg;
};

FeatureKernels featureKernels(double ppd) {
  const float sd = 0.5f * kFeatureWidthDeg * static_cast<float>(ppd);
  const int r = static_cast<int>(std::ceil(3.0f * sd));
  FeatureKernels k;
  float gSum = 0.0f, dPos = 0.0f, dNeg = 0.0f, ddPos = 0.0f, ddNeg = 0.0f;
  for (int i = -r; i <= r; ++i) {
    const auto x = static_cast<float>(i);
    const float g = std::exp(-(x * x) / (2.0f * sd * sd)), dg = -x * g, ddg = (x * x / (sd * sd) - 1.0f) * g;
    k.g.push_back(g);
    k.dg.push_back(dg);
    k.ddg.push_back(ddg);
    gSum += g;
    (dg > 0.0f ? dPos : dNeg) += std::abs(dg);
    (ddg > 0.0f ? ddPos : ddNeg) += std::abs(ddg);
  }
  for (std::size_t i = 0; i < k.g.size(); ++i) {
    k.g[i] /= gSum;
    k.dg[i] /= k.dg[i] > 0.0f ? dPos : dNeg;
    k.ddg[i] /= k.ddg[i] > 0.0f ? ddPos : ddNeg;
  }
  return k;
}

// Edge (first derivative) and point (second derivative) magnitudes of the
// luminance, normalised to [0, 1].
struct Features {
  std::vector<float> edge, point;
};

Features features(const Plane& y, const FeatureKernels& k) {
  Plane gray = y;
  for (float& v : gray.v) v = (v + 16.0f) / 116.0f;
  const Plane dx = separable(gray, k.dg, k.g), dy = separable(gray, k.g, k.dg);
  const Plane ddx = separable(gray, k.ddg, k.g), ddy = separable(gray, k.g, k.ddg);
  Features f{std::vector<float>(gray.v.size()), std::vector<float>(gray.v.size())};
  for (std::size_t i = 0; i < gray.v.size(); ++i) {
    f.edge[i] = std::sqrt(dx.v[i] * dx.v[i] + dy.v[i] * dy.v[i]);
    f.point[i] = std::sqrt(ddx.v[i] * ddx.v[i] + ddy.v[i] * ddy.v[i]);
  }
  return f;
}

}  // namespace

FlipMap flip(const LinearImage& reference, const LinearImage& test, double pixelsPerDegree) {
  if (reference.width != test.width || reference.height != test.height) {
    throw InputError("images of different sizes cannot be compared (" + std::to_string(reference.width) + "x" +
                     std::to_string(reference.height) + " and " + std::to_string(test.width) + "x" +
                     std::to_string(test.height) + ")");
  }
  const std::array<Plane, 3> ref = toYcxcz(reference), tst = toYcxcz(test);
  FlipMap map{reference.width, reference.height, colourTerm(ref, tst, pixelsPerDegree)};
  const FeatureKernels kernels = featureKernels(pixelsPerDegree);
  const Features fr = features(ref[0], kernels), ft = features(tst[0], kernels);
  for (std::size_t i = 0; i < map.error.size(); ++i) {
    const float difference = std::max(std::abs(fr.edge[i] - ft.edge[i]), std::abs(fr.point[i] - ft.point[i]));
    const float feature = std::pow(difference / std::sqrt(2.0f), kFeatureExponent);
    map.error[i] = std::pow(map.error[i], 1.0f - feature);
  }
  return map;
}

namespace {

// ACES as Narkowicz fits it, with its 0.6 pre-exposure cancelled:
// (a c^2 + b c) / (d c^2 + e c + f) per channel.
constexpr float kAces[6] = {0.6f * 0.6f * 2.51f, 0.6f * 0.03f, 0.0f, 0.6f * 0.6f * 2.43f, 0.6f * 0.59f, 0.14f};

float aces(float c) {
  return (kAces[0] * c * c + kAces[1] * c + kAces[2]) / (kAces[3] * c * c + kAces[4] * c + kAces[5]);
}

LinearImage exposedAndToneMapped(const LinearImage& image, float exposure) {
  LinearImage out = image;
  const float scale = twoToThe(exposure);
  for (float& v : out.rgb) v = std::clamp(aces(v * scale), 0.0f, 1.0f);
  return out;
}

}  // namespace

HdrExposures hdrExposures(const LinearImage& reference) {
  // The larger root of aces(x) = 0.85: where the curve reaches 0.85.
  constexpr float t = 0.85f;
  const float a = kAces[0] - t * kAces[3], b = kAces[1] - t * kAces[4], c = kAces[2] - t * kAces[5];
  const float half = -0.5f * b / a, x = half + std::sqrt(half * half - c / a);
  std::vector<float> luminance(reference.rgb.size() / 3);
  for (std::size_t i = 0; i < luminance.size(); ++i) {
    luminance[i] = 0.2126f * reference.rgb[3 * i] + 0.7152f * reference.rgb[3 * i + 1] + 0.0722f * reference.rgb[3 * i + 2];
  }
  if (luminance.empty()) return {};
  const float brightest = *std::max_element(luminance.begin(), luminance.end());
  const auto middle = luminance.begin() + static_cast<std::ptrdiff_t>(luminance.size() / 2);
  std::nth_element(luminance.begin(), middle, luminance.end());
  if (!(*middle > 0.0f) || !std::isfinite(brightest)) return {};
  HdrExposures e{std::log2(x / brightest), std::log2(x / *middle), 0};
  e.count = static_cast<int>(std::max(2.0f, std::ceil(e.stop - e.start)));
  return e;
}

FlipMap hdrFlip(const LinearImage& reference, const LinearImage& test, const HdrExposures& exposures,
                double pixelsPerDegree) {
  FlipMap worst;
  const float step = (exposures.stop - exposures.start) / static_cast<float>(exposures.count - 1);
  for (int i = 0; i < exposures.count; ++i) {
    const float e = exposures.start + static_cast<float>(i) * step;
    const FlipMap map =
        flip(exposedAndToneMapped(reference, e), exposedAndToneMapped(test, e), pixelsPerDegree);
    if (i == 0) worst = map;
    for (std::size_t p = 0; p < map.error.size(); ++p) worst.error[p] = std::max(worst.error[p], map.error[p]);
  }
  return worst;
}

FlipStats flipStats(const FlipMap& map) {
  if (map.error.empty()) return {};
  std::vector<float> sorted = map.error;
  std::sort(sorted.begin(), sorted.end());
  const auto rank = [&sorted](double share) {
    const auto n = static_cast<double>(sorted.size());
    return static_cast<double>(sorted[static_cast<std::size_t>(std::max(1.0, std::ceil(share * n))) - 1]);
  };
  double sum = 0.0;
  for (const float e : map.error) sum += e;
  return {sum / static_cast<double>(map.error.size()), rank(0.95), rank(0.99)};
}

FrameImage magmaImage(const FlipMap& map) {
  // Matplotlib's magma (sRGB values) at every 16th of its 256 entries and the
  // last, interpolated linearly between them.
  static constexpr std::array<glm::vec3, 17> kKnots{{{0.001462f, 0.000466f, 0.013866f},
                                                     {0.039608f, 0.031090f, 0.133515f},
                                                     {0.113094f, 0.065492f, 0.276784f},
                                                     {0.211718f, 0.061992f, 0.418647f},
                                                     {0.316654f, 0.071690f, 0.485380f},
                                                     {0.414709f, 0.110431f, 0.504662f},
                                                     {0.512831f, 0.148179f, 0.507648f},
                                                     {0.613617f, 0.181811f, 0.498536f},
                                                     {0.716387f, 0.214982f, 0.475290f},
                                                     {0.816914f, 0.255895f, 0.436461f},
                                                     {0.904281f, 0.319610f, 0.388137f},
                                                     {0.960949f, 0.418323f, 0.359630f},
                                                     {0.986700f, 0.535582f, 0.382210f},
                                                     {0.996096f, 0.653659f, 0.446213f},
                                                     {0.996898f, 0.769591f, 0.534892f},
                                                     {0.992440f, 0.884330f, 0.640099f},
                                                     {0.987053f, 0.991438f, 0.749504f}}};
  FrameImage image{map.width, map.height, std::vector<std::uint8_t>(map.error.size() * 3)};
  for (std::size_t p = 0; p < map.error.size(); ++p) {
    const float at = std::clamp(map.error[p], 0.0f, 1.0f) * 255.0f;
    const std::size_t k = std::min<std::size_t>(static_cast<std::size_t>(at / 16.0f), kKnots.size() - 2);
    const float from = static_cast<float>(k) * 16.0f, to = k + 2 == kKnots.size() ? 255.0f : from + 16.0f;
    const glm::vec3 c = glm::mix(kKnots[k], kKnots[k + 1], (at - from) / (to - from));
    for (int ch = 0; ch < 3; ++ch) image.rgb[3 * p + ch] = static_cast<std::uint8_t>(std::lround(c[ch] * 255.0f));
  }
  return image;
}

}  // namespace glint

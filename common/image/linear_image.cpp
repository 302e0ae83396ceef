#include "common/image/linear_image.h"

#include <algorithm>

#include "common/image/encoding.h"

namespace glint {

LinearImage average(const LinearImage& a, const LinearImage& b) {
  LinearImage out = a;
  for (std::size_t i = 0; i < out.rgb.size(); ++i) out.rgb[i] = 0.5f * (a.rgb[i] + b.rgb[i]);
  return out;
}

}  // namespace glint

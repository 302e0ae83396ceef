#include "common/render/area_light.h"

#include <glm/geometric.hpp>

namespace glint {

AreaLightPoints::AreaLightPoints(const Light& light, int count)
    : color(light.color / static_cast<float>(count)),
      normal(glm::normalize(glm::cross(light.u, light.v))),
      corner_(light.position - 0.5f * light.u - 0.5f * light.v),
      u_(light.u),
      v_(light.v) {
  for (int k = 0; k < count; ++k) {
    const Stratum s = jitteredStratum(count, k);
    strata.push_back(s);
    centres.push_back(corner_ + (0.5f * (s.x0 + s.x1)) * u_ + (0.5f * (s.y0 + s.y1)) * v_);
  }
}

glm::vec3 AreaLightPoints::jittered(int k, const glm::vec2& u) const {
  const glm::vec2 st = stratumPoint(strata[static_cast<std::size_t>(k)], u);
  return corner_ + st.x * u_ + st.y * v_;
}

bool AreaLightPoints::lights(const glm::vec3& point, const glm::vec3& p) const {
  return glm::dot(p - point, normal) > 0.0f;
}

}  // namespace glint

#include "server/scene_cache.h"

#include "common/scene/scene_budget.h"

namespace glint::server {

std::size_t memoryFootprint(const PreparedScene& p) {
  const Scene& s = p.scene();
  const Geometry& g = s.geometry;
  // The per-item costs the loader charged (SceneBudget), with the BVH as built.
  std::size_t bytes = g.positions().size() * SceneBudget::kBytesPerVertex +
                      g.triangles().size() * SceneBudget::kBytesPerTriangle +
                      g.spheres().size() * SceneBudget::kBytesPerSphere +
                      p.bvh().nodes().size() * sizeof(BvhNode) + p.bvh().primIds().size() * sizeof(std::uint32_t) +
                      p.bvh().blocks().size() * sizeof(TriangleBlock);
  for (const Texture& t : s.textures) {
    if (t.image) bytes += t.image->rgb.size();
  }
  return bytes + 4096;
}

}  // namespace glint::server

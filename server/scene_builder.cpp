#include "server/scene_builder.h"

#include "common/error.h"
#include "common/timing.h"

namespace glint::server {

BuiltScene buildScene(const SceneJob& job, std::size_t maxSceneBytes, MemoryGauge& buildMemory) {
  const auto start = Clock::now();
  BuiltScene built;
  built.hash = job.hash;
  try {
    if (job.bundle->hash() != job.hash) throw InputError("the scene's bytes do not match its hash");
    LoadLimits limits;
    limits.maxSceneBytes = maxSceneBytes;
    SceneBudget budget(limits, "glintd --max-scene-mb", &buildMemory);
    built.prepared = std::make_shared<const PreparedScene>(proto::loadBundle(*job.bundle, budget), BvhSettings{});
  } catch (const InputError& e) {
    built.error = e.what();
  } catch (const std::exception& e) {
    built.error = std::string("cannot load the scene: ") + e.what();
  }
  built.ms = msSince(start);
  return built;
}

}  // namespace glint::server

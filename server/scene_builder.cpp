#include "server/scene_builder.h"

#include "common/base/error.h"
#include "common/base/timing.h"

namespace glint::server {
namespace {

// Cuts `text` to kMaxErrorBytes, not inside a UTF-8 sequence.
void cut(std::string& text) {
  if (text.size() <= kMaxErrorBytes) return;
  std::size_t n = kMaxErrorBytes;
  while (n > 0 && (static_cast<unsigned char>(text[n]) & 0xc0) == 0x80) --n;
  text.resize(n);
  text += " ... (cut)";
}

}  // namespace

BuiltScene buildScene(const SceneJob& job, const BuildLimits& buildLimits, MemoryGauge& buildMemory) {
  const auto start = Clock::now();
  BuiltScene built;
  built.hash = job.hash;
  const bool ofTheHash = job.bundle->hash() == job.hash;
  try {
    if (!ofTheHash) throw InputError("the scene's bytes do not match its hash");
    LoadLimits limits;
    limits.maxSceneBytes = buildLimits.maxSceneBytes;
    const Deadline deadline(buildLimits.timeout, "the scene's build", "glintd --build-timeout");
    SceneBudget budget(limits, "glintd --max-scene-mb", &buildMemory);
    budget.keepTo(deadline);
    Scene scene = proto::loadBundle(*job.bundle, budget);
    budget.checkTime("the scene's BVH");
    built.prepared = std::make_shared<const PreparedScene>(std::move(scene), BvhSettings{});
  } catch (const BusyError& e) {
    built.error = e.what();
  } catch (const InputError& e) {
    built.error = e.what();
    built.lasting = ofTheHash;
  } catch (const std::exception& e) {  // out of memory, for one
    built.error = std::string("cannot load the scene: ") + e.what();
  }
  cut(built.error);
  built.ms = msSince(start);
  return built;
}

}  // namespace glint::server

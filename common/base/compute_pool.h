#pragma once

#include "common/base/thread_pool.h"

namespace glint {

// The process's one pool for compute: tracing, BVH builds, parsing, the
// raster's proofs. Sized once by the program's --threads (0: every hardware
// thread) before its first use; made at first use with every hardware
// thread where nothing sized it.
void setComputeThreads(int threads);
ThreadPool& computePool();

}  // namespace glint

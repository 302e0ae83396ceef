#include "common/base/heap_tuning.h"

#include <algorithm>
#include <cstdint>
#include <utility>
#include <cstdlib>  // defines __GLIBC__ under glibc

#if defined(__linux__)
#include <sys/mman.h>  // MADV_POPULATE_WRITE from glibc 2.35 on
#include <unistd.h>
#endif

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace glint {

void keepFreedMemoryForReuse() {
#if defined(__GLIBC__)
  mallopt(M_MMAP_THRESHOLD, 32 << 20);  // glibc's largest allowed value
  mallopt(M_TRIM_THRESHOLD, 256 << 20);
#endif
}

namespace {

// [begin, end) rounded inwards to multiples of `unit`, or an empty range.
std::pair<std::uintptr_t, std::uintptr_t> inside(std::uintptr_t begin, std::uintptr_t end, std::uintptr_t unit) {
  const std::uintptr_t first = (begin + unit - 1) / unit * unit;
  const std::uintptr_t last = end / unit * unit;
  return {first, std::max(first, last)};
}

}  // namespace

bool prefault(void* data, std::size_t bytes) {
#if defined(MADV_POPULATE_WRITE)
  const auto begin = reinterpret_cast<std::uintptr_t>(data);
  // Whole 2 MiB stretches as huge pages first: one fault each instead of 512.
  constexpr std::uintptr_t kHugePage = std::uintptr_t{2} << 20;
  const auto [hugeFirst, hugeLast] = inside(begin, begin + bytes, kHugePage);
  if (hugeLast > hugeFirst) madvise(reinterpret_cast<void*>(hugeFirst), hugeLast - hugeFirst, MADV_HUGEPAGE);
  const auto [first, last] = inside(begin, begin + bytes, static_cast<std::uintptr_t>(sysconf(_SC_PAGESIZE)));
  return last <= first || madvise(reinterpret_cast<void*>(first), last - first, MADV_POPULATE_WRITE) == 0;
#else
  (void)data;
  (void)bytes;
  return false;
#endif
}

}  // namespace glint

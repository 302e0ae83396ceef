#include "common/base/memory_gauge.h"

namespace glint {

bool MemoryGauge::take(std::size_t bytes) {
  std::size_t used = used_.load();
  do {
    if (bytes > capacity_ - used) return false;
  } while (!used_.compare_exchange_weak(used, used + bytes));
  return true;
}

}  // namespace glint

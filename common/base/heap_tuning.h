#pragma once

#include <algorithm>
#include <cstddef>
#include <iterator>
#include <vector>

namespace glint {

// Every frame allocates and frees the same megabytes again (tile results,
// the GL driver's pixel transfers). glibc by default hands freed memory at
// the top of the heap, and every block over 128 KiB, back to the kernel,
// and the next frame faults it in again page by page (its cost is measured
// in docs/hybrid.md). Called first thing by glint, glintd and
// glint-bench, this keeps freed memory in the process for reuse (blocks of
// 32 MiB and more, a large scene's arrays, still come straight from the
// kernel and go back to it). Does nothing where the C library is not glibc.
void keepFreedMemoryForReuse();

// Faults in the pages of [data, data + bytes), about to be written, in one
// system call (Linux's MADV_POPULATE_WRITE) instead of one page fault a
// page: on a virtual machine a fault costs about 10 us, 2.5 ms a megabyte,
// which made page faults the larger part of loading a large mesh
// (docs/performance.md). Whole 2 MiB stretches are asked for as huge pages
// (one fault each instead of 512). The contents do not change; pages
// already there cost nothing. False where the kernel or C library cannot
// (before Linux 5.14, glibc 2.35): then it did nothing.
bool prefault(void* data, std::size_t bytes);

// Room in v for n elements (at least twice its capacity when it must grow,
// so that growing it step by step stays linear), faulted in at once: the
// room beyond v.size() up to n, and where v moves to a larger block, the
// whole block before its elements are moved there.
template <typename T>
void reservePrefaulted(std::vector<T>& v, std::size_t n) {
  if (n <= v.size()) return;
  if (n <= v.capacity()) {
    prefault(v.data() + v.size(), (n - v.size()) * sizeof(T));
    return;
  }
  std::vector<T> grown;
  grown.reserve(std::max(n, 2 * v.capacity()));
  prefault(grown.data(), n * sizeof(T));
  grown.insert(grown.end(), std::make_move_iterator(v.begin()), std::make_move_iterator(v.end()));
  v.swap(grown);
}

}  // namespace glint

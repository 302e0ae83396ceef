#pragma once

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

}  // namespace glint

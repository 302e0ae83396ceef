#include "common/base/heap_tuning.h"

#include <cstdlib>

#if defined(__GLIBC__)
#include <malloc.h>
#endif

#include <gtest/gtest.h>

namespace glint {
namespace {

// After the tuning, a freed 4 MiB block stays in the heap for the next frame
// instead of being a mapping of its own that goes back to the kernel.
TEST(HeapTuning, FreedMegabytesStayInTheProcess) {
#if defined(__SANITIZE_ADDRESS__)
  GTEST_SKIP() << "AddressSanitizer replaces glibc's allocator";
#elif defined(__GLIBC__)
  keepFreedMemoryForReuse();
  const struct mallinfo2 before = mallinfo2();
  constexpr std::size_t kBlock = 4u << 20;
  void* block = std::malloc(kBlock);
  ASSERT_NE(block, nullptr);
  static_cast<volatile char*>(block)[kBlock - 1] = 1;
  const struct mallinfo2 during = mallinfo2();
  EXPECT_EQ(during.hblks, before.hblks) << "the block was mapped on its own";
  std::free(block);
  const struct mallinfo2 after = mallinfo2();
  EXPECT_GE(after.arena, before.arena + kBlock) << "the heap was trimmed";
  EXPECT_GE(after.fordblks, before.fordblks + kBlock);
#else
  GTEST_SKIP() << "the tuning applies to glibc only";
#endif
}

}  // namespace
}  // namespace glint

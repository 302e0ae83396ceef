#include "common/base/heap_tuning.h"

#include <cstdlib>
#include <vector>

#include <sys/mman.h>
#include <unistd.h>

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

// prefault makes every whole page of the range resident (mincore tells)
// and leaves its contents as they were; the pages around it stay out.
TEST(HeapTuning, PrefaultMakesTheRangeResidentAndKeepsItsBytes) {
  const std::size_t page = static_cast<std::size_t>(sysconf(_SC_PAGESIZE));
  const std::size_t size = 64 * page;
  auto* region = static_cast<unsigned char*>(mmap(nullptr, size, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0));
  ASSERT_NE(region, MAP_FAILED);
  region[10 * page + 5] = 42;  // one page written before
  const auto resident = [&] {
    std::vector<unsigned char> in(size / page);
    mincore(region, size, in.data());
    return in;
  };
  EXPECT_EQ(resident()[20], 0);
  if (!prefault(region + 8 * page + 100, 40 * page)) {
    munmap(region, size);
    GTEST_SKIP() << "the kernel cannot populate a range (Linux 5.14 and later can)";
  }
  const std::vector<unsigned char> in = resident();
  for (std::size_t p = 9; p < 48; ++p) EXPECT_TRUE(in[p] & 1) << "page " << p;
  for (std::size_t p : {0, 7, 49, 63}) EXPECT_FALSE(in[p] & 1) << "page " << p;
  EXPECT_EQ(region[10 * page + 5], 42);
  EXPECT_EQ(region[20 * page], 0);
  munmap(region, size);
}

// reservePrefaulted keeps the elements, makes room for n, and grows at
// least twofold (a loop of small reservations stays linear).
TEST(HeapTuning, ReservePrefaultedKeepsTheElementsAndGrowsGeometrically) {
  std::vector<int> v = {1, 2, 3};
  reservePrefaulted(v, 1000);
  EXPECT_EQ(v, (std::vector<int>{1, 2, 3}));
  EXPECT_GE(v.capacity(), 1000u);
  const std::size_t capacity = v.capacity();
  reservePrefaulted(v, capacity + 1);
  EXPECT_GE(v.capacity(), 2 * capacity);
  reservePrefaulted(v, 2);  // below the size: nothing
  EXPECT_EQ(v.size(), 3u);
}

}  // namespace
}  // namespace glint

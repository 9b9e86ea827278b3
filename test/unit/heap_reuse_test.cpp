// The solving processes keep the memory they free for their next allocations
// (numerics/heap_reuse.h): a block as large as a 10,000-vertex factor, freed, stays in the heap;
// with a heap per thread (curved_mesh_solver's), a second thread's block is new memory.
#include <gtest/gtest.h>
#include <malloc.h>

#include <cstdlib>

#include "heap_reuse_probe.h"
#include "virtual_origami/numerics/heap_reuse.h"

namespace
{
using virtual_origami::test::freshBytesOfASecondThread;

constexpr size_t kBlock = size_t(256) << 20;  // over the C library's largest own threshold (32 MiB)

struct Held
{
  size_t mapped;  // bytes in blocks mapped apart while the block is held
  size_t free;    // bytes free in the heap once it is freed
};

Held allocateAndFree()
{
  void* block = virtual_origami::test::allocated(kBlock);
  EXPECT_NE(block, nullptr);
  const size_t mapped = mallinfo2().hblkhd;
  std::free(block);
  return { mapped, mallinfo2().fordblks };
}
}  // namespace

TEST(HeapReuse, ALargeBlockFreedStaysInTheHeapForTheNextAllocation)
{
  // By default such a block is mapped on its own and given back when freed.
  const Held before = allocateAndFree();
  EXPECT_GE(before.mapped, kBlock);
  EXPECT_LT(before.free, kBlock);

  ASSERT_TRUE(virtual_origami::numerics::keepFreedMemory(virtual_origami::numerics::ThreadHeaps::PerThread));
  const Held after = allocateAndFree();
  EXPECT_LT(after.mapped, kBlock);
  EXPECT_GE(after.free, kBlock);

  // A heap per thread: what this thread freed is not where another thread allocates.
  EXPECT_GE(freshBytesOfASecondThread(), virtual_origami::test::kThreadBlock);
}

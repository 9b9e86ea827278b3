// paper_model's and spring_solver's threads share one heap (numerics/heap_reuse.h): a block one
// service thread freed serves the next frame on another thread, with no new memory.
#include <gtest/gtest.h>

#include "heap_reuse_probe.h"
#include "virtual_origami/numerics/heap_reuse.h"

TEST(SharedHeap, ABlockOneThreadFreedServesAnotherThreadWithoutNewMemory)
{
  ASSERT_TRUE(virtual_origami::numerics::keepFreedMemory(virtual_origami::numerics::ThreadHeaps::Shared));
  EXPECT_LT(virtual_origami::test::freshBytesOfASecondThread(), size_t(1) << 20);
}

#include "virtual_origami/numerics/heap_reuse.h"

#include <malloc.h>

#include <climits>

namespace virtual_origami::numerics
{
bool keepFreedMemory(ThreadHeaps heaps)
{
  // Above any one allocation a solve makes (a factor at 100,000 vertices is some hundreds of
  // megabytes), so none is mapped apart and unmapped when freed.
  bool taken = mallopt(M_MMAP_THRESHOLD, INT_MAX) == 1;
  taken = mallopt(M_TRIM_THRESHOLD, INT_MAX) == 1 && taken;
  if (heaps == ThreadHeaps::Shared)
    taken = mallopt(M_ARENA_MAX, 1) == 1 && taken;
  return taken;
}
}  // namespace virtual_origami::numerics

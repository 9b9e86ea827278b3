#include "virtual_origami/numerics/heap_reuse.h"

#include <malloc.h>

#include <climits>

namespace virtual_origami::numerics
{
bool keepFreedMemory()
{
  // Above any one allocation a solve makes (a factor at 100,000 vertices is some hundreds of
  // megabytes), so none is mapped apart and unmapped when freed.
  const bool no_maps = mallopt(M_MMAP_THRESHOLD, INT_MAX) == 1;
  const bool no_trim = mallopt(M_TRIM_THRESHOLD, INT_MAX) == 1;
  return no_maps && no_trim;
}
}  // namespace virtual_origami::numerics

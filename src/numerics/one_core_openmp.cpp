// CHOLMOD's OpenMP regions run on the calling thread, without libgomp's team around them.
//
// Debian's CHOLMOD enters an OpenMP parallel region for every supernode's loops, whatever the
// threads allowed. Kept to one thread (lockBlas), each region still costs libgomp a team's
// set-up and, at its closing barrier, a futex system call: about 18,600 of each in one
// factorisation of a 10,000-vertex Gauss–Newton matrix, where they took a third of its time on
// this machine (123 → 86 ms; 23 → 12.6 ms at 2,500 vertices: docs/SOLVERS.md). CHOLMOD is the
// only user of OpenMP in the process, and a region's outlined body asks OpenMP only for its
// thread's number and the team's size (omp_get_thread_num, omp_get_num_threads), which outside
// any team are 0 and 1: so a region kept to one thread runs its body directly, the same
// arithmetic in the same order. This library comes before libgomp in a process's symbol search
// (libgomp arrives as CHOLMOD's dependency), so CHOLMOD's calls land here. Where OMP_NUM_THREADS
// asks for more threads, libgomp's own GOMP_parallel runs the region.
#include <dlfcn.h>

#include "one_core_openmp.h"

namespace
{
using OutlinedRegion = void (*)(void*);
using Parallel = void (*)(OutlinedRegion, void*, unsigned, unsigned);
}  // namespace

extern "C" void GOMP_parallel(OutlinedRegion body, void* data, unsigned num_threads, unsigned flags)
{
  static const bool one_core = virtual_origami::numerics::factorisationsOnOneCore();
  static const auto libgomp = reinterpret_cast<Parallel>(dlsym(RTLD_NEXT, "GOMP_parallel"));
  if (one_core || !libgomp)
    body(data);
  else
    libgomp(body, data, num_threads, flags);
}

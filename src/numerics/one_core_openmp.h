// Whether this process keeps the OpenMP regions of its sparse factorisations to one core
// (inside the core only: spd_factorization.cpp and one_core_openmp.cpp share the rule).
#pragma once

namespace virtual_origami::numerics
{
/// True unless OMP_NUM_THREADS asks for more than one thread: the nodes and rviz share a
/// machine's cores, and CHOLMOD's own threads spun and switched there (docs/SOLVERS.md).
bool factorisationsOnOneCore();
}  // namespace virtual_origami::numerics

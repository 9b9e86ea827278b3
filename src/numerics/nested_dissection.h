// The fill-reducing ordering the large sparse Cholesky factorisations share (the crease
// driver's, the curved solver's, the rigid newton solver's). Inside the core only: CHOLMOD's
// headers are not part of its public interface.
#pragma once

#include <Eigen/CholmodSupport>

namespace virtual_origami::numerics
{
/// Analyses a's pattern for one of Eigen's CHOLMOD factorisations: nested dissection (METIS)
/// from 3,000 rows (a large mesh's matrix), where against CHOLMOD's own choice (minimum degree
/// there) it cuts the factorisation's flops by 30 to 50 % on a 10,000-node sheet for an analysis
/// done once per pattern; CHOLMOD's own choice below that, or where this CHOLMOD has no METIS.
template <class Factor, class Matrix>
void analyzeWithNestedDissection(Factor& factor, const Matrix& a)
{
  constexpr Eigen::Index kNestedDissectionRows = 3000;
  cholmod_common& common = factor.cholmod();
  common.nmethods = a.rows() >= kNestedDissectionRows ? 1 : 0;
  common.method[0].ordering = CHOLMOD_METIS;
  factor.analyzePattern(a);
  if (factor.info() != Eigen::Success && common.nmethods == 1)
  {
    common.nmethods = 0;
    factor.analyzePattern(a);
  }
}

}  // namespace virtual_origami::numerics

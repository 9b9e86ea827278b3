// The fill-reducing ordering the large sparse Cholesky factorisations share (the crease
// driver's, the curved solver's, the rigid newton solver's). Inside the core only: CHOLMOD's
// headers are not part of its public interface.
#pragma once

#include <vector>

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

/// The order analyzeWithNestedDissection's analysis gives the rows of the symmetric matrix
/// whose upper triangle `upper` stores (its fill-reducing ordering, postordered by CHOLMOD):
/// order[k] is the row that comes k-th; the rows as they are where the analysis failed.
inline std::vector<int> choleskyOrdering(const Eigen::SparseMatrix<double>& upper)
{
  struct Analysis : Eigen::CholmodSupernodalLLT<Eigen::SparseMatrix<double>, Eigen::Upper>
  {
    const cholmod_factor* symbolic() const { return m_cholmodFactor; }
  } analysis;
  analysis.cholmod().print = 0;
  analyzeWithNestedDissection(analysis, upper);
  std::vector<int> order(static_cast<size_t>(upper.rows()));
  const cholmod_factor* symbolic = analysis.symbolic();
  for (size_t k = 0; k < order.size(); ++k)
    order[k] = analysis.info() == Eigen::Success && symbolic ? static_cast<const int*>(symbolic->Perm)[k] :
                                                               static_cast<int>(k);
  return order;
}

/// Analyses a's pattern in the order its rows already have, not postordered (a matrix stored in
/// choleskyOrdering's order): CHOLMOD then factors a lower triangle's values as they are stored,
/// with the supernodes the ordering's own analysis finds, where in a permuted order it copies
/// the matrix (twice transposed) at every factorisation.
template <class Factor, class Matrix>
void analyzeInGivenOrder(Factor& factor, const Matrix& a)
{
  cholmod_common& common = factor.cholmod();
  common.nmethods = 1;
  common.method[0].ordering = CHOLMOD_NATURAL;
  common.postorder = 0;
  factor.analyzePattern(a);
}

}  // namespace virtual_origami::numerics

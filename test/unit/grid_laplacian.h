// A sparse symmetric positive definite matrix with supernodes: the 2-D Laplacian of a grid plus
// the identity, for tests of the factorisations (the BLAS kernels, CHOLMOD's OpenMP regions).
#pragma once

#include <vector>

#include <Eigen/Sparse>

namespace virtual_origami::test
{
/// The lower triangle of 5 on the diagonal and −1 between grid neighbours, `side` × `side` rows.
inline Eigen::SparseMatrix<double> gridLaplacianLower(int side)
{
  const int n = side * side;
  std::vector<Eigen::Triplet<double>> entries;
  for (int i = 0; i < side; ++i)
    for (int j = 0; j < side; ++j)
    {
      const int k = i * side + j;
      entries.emplace_back(k, k, 5.0);
      if (i + 1 < side)
        entries.emplace_back(k + side, k, -1.0);
      if (j + 1 < side)
        entries.emplace_back(k + 1, k, -1.0);
    }
  Eigen::SparseMatrix<double> lower(n, n);
  lower.setFromTriplets(entries.begin(), entries.end());
  return lower;
}
}  // namespace virtual_origami::test

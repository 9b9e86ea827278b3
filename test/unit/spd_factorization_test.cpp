// SpdFactorization: the supernodal Cholesky behind the curved solver and the crease drivers, and
// the symbolic analysis a driver's clones share.
#include "virtual_origami/numerics/spd_factorization.h"

#include <thread>
#include <vector>

#include <gtest/gtest.h>

namespace virtual_origami::numerics
{
namespace
{
/// The lower triangle of a grid's graph Laplacian ⊗ I₃ plus a little of the identity: SPD, with
/// the pattern of a sheet's matrix (3 rows per node).
Eigen::SparseMatrix<double> gridMatrix(int n, double weight)
{
  std::vector<Eigen::Triplet<double>> t;
  const auto node = [n](int i, int j) { return i * n + j; };
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int axis = 0; axis < 3; ++axis)
      {
        const int row = 3 * node(i, j) + axis;
        double diagonal = 1e-3 + 0.1 * axis;
        for (const auto& [di, dj] : { std::pair{ 1, 0 }, std::pair{ 0, 1 }, std::pair{ -1, 0 }, std::pair{ 0, -1 } })
        {
          const int ni = i + di, nj = j + dj;
          if (ni < 0 || nj < 0 || ni >= n || nj >= n)
            continue;
          diagonal += weight;
          const int col = 3 * node(ni, nj) + axis;
          if (col < row)
            t.emplace_back(row, col, -weight);
        }
        t.emplace_back(row, row, diagonal);
      }
  Eigen::SparseMatrix<double> m(3 * n * n, 3 * n * n);
  m.setFromTriplets(t.begin(), t.end());
  m.makeCompressed();
  return m;
}

Eigen::VectorXd ramp(Eigen::Index rows)
{
  return Eigen::VectorXd::LinSpaced(rows, -1.0, 2.0);
}
}  // namespace

// Small (CHOLMOD's own ordering) and large (nested dissection) patterns: a factorisation that
// takes its analysis from another gives exactly the solution a fresh analysis gives, analyses
// nothing itself, and a new pattern is analysed afresh.
TEST(SpdFactorization, ASharedAnalysisGivesTheFactorAFreshOneGives)
{
  for (const int n : { 10, 40 })
  {
    const Eigen::SparseMatrix<double> a = gridMatrix(n, 1.0);
    const Eigen::SparseMatrix<double> b = gridMatrix(n, 3.0);  // same pattern, other values
    SpdFactorization fresh;
    ASSERT_TRUE(fresh.factorize(b, 1e-6));
    const Eigen::VectorXd expected = fresh.solve(ramp(b.rows()));

    const auto shared = SpdFactorization::makeSharedAnalysis();
    SpdFactorization first, second;
    first.shareAnalysis(shared);
    second.shareAnalysis(shared);
    ASSERT_TRUE(first.factorize(a, 1e-6));
    EXPECT_EQ(first.analyses(), 1);
    ASSERT_TRUE(second.factorize(b, 1e-6));
    EXPECT_EQ(second.analyses(), 0) << "n " << n;
    const Eigen::VectorXd solved = second.solve(ramp(b.rows()));
    EXPECT_EQ((solved - expected).cwiseAbs().maxCoeff(), 0.0) << "n " << n;
    EXPECT_LT((b.selfadjointView<Eigen::Lower>() * solved + 1e-6 * solved - ramp(b.rows())).norm(),
              1e-8 * ramp(b.rows()).norm());

    const Eigen::SparseMatrix<double> other = gridMatrix(n + 1, 1.0);
    ASSERT_TRUE(second.factorize(other, 1e-6));
    EXPECT_EQ(second.analyses(), 1) << "a new pattern is analysed";
  }
}

// Clones factorise on several threads at once (paper_model computes operations on several):
// each gets the factor of its own matrix. Without lockBlas() the installed serial OpenBLAS
// mixed the threads' buffers: wrong solutions and failed factorisations, every run.
TEST(SpdFactorization, FactorisationsSharingAnAnalysisRunOnSeveralThreads)
{
  const auto shared = SpdFactorization::makeSharedAnalysis();
  std::vector<Eigen::VectorXd> solved(4);
  std::vector<std::thread> threads;
  for (int k = 0; k < 4; ++k)
    threads.emplace_back([&, k]() {
      SpdFactorization f;
      f.shareAnalysis(shared);
      if (f.factorize(gridMatrix(30, 1.0 + k), 0.0))
        solved[k] = f.solve(ramp(3 * 30 * 30));
    });
  for (std::thread& t : threads)
    t.join();
  for (int k = 0; k < 4; ++k)
  {
    SpdFactorization fresh;
    ASSERT_TRUE(fresh.factorize(gridMatrix(30, 1.0 + k), 0.0));
    ASSERT_EQ(solved[k].size(), 3 * 30 * 30) << "thread " << k;
    EXPECT_EQ((solved[k] - fresh.solve(ramp(3 * 30 * 30))).cwiseAbs().maxCoeff(), 0.0) << "thread " << k;
  }
}

}  // namespace virtual_origami::numerics

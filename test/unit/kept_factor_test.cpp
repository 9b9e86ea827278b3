// KeptFactor (kept_factor.h): the factor the anytime frames correct with, made in one thread and
// back-substituted in others. Its solves are its own (supernode by supernode, no BLAS): checked
// against the residual of the matrix and CHOLMOD's own solve, on sheets above and below the size
// where the ordering turns to nested dissection, and from threads solving while the next factor
// is made.
#include "virtual_origami/curved/kept_factor.h"

#include <atomic>
#include <cmath>
#include <mutex>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "virtual_origami/numerics/spd_factorization.h"

namespace virtual_origami::core
{
namespace
{
/// The lower triangle of a grid's graph Laplacian ⊗ K (K a coupled 3 × 3 stiffness) times
/// `weight`, plus a little of the identity: SPD, with the pattern and coupled blocks of a sheet's
/// matrix (3 rows per node).
Eigen::SparseMatrix<double> sheetMatrix(int n, double weight)
{
  Eigen::Matrix3d k;
  k << 2.0, 0.5, 0.2, 0.5, 1.5, 0.3, 0.2, 0.3, 1.0;
  std::vector<Eigen::Triplet<double>> t;
  const auto node = [n](int i, int j) { return i * n + j; };
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
    {
      int neighbours = 0;
      for (const auto& [di, dj] : { std::pair{ 1, 0 }, std::pair{ 0, 1 }, std::pair{ -1, 0 }, std::pair{ 0, -1 } })
      {
        const int ni = i + di, nj = j + dj;
        if (ni < 0 || nj < 0 || ni >= n || nj >= n)
          continue;
        ++neighbours;
        if (node(ni, nj) < node(i, j))
          for (int a = 0; a < 3; ++a)
            for (int b = 0; b < 3; ++b)
              t.emplace_back(3 * node(i, j) + a, 3 * node(ni, nj) + b, -weight * k(a, b));
      }
      for (int a = 0; a < 3; ++a)
        for (int b = 0; b <= a; ++b)
          t.emplace_back(3 * node(i, j) + a, 3 * node(i, j) + b, neighbours * weight * k(a, b) + (a == b ? 1e-3 : 0.0));
    }
  Eigen::SparseMatrix<double> m(3 * n * n, 3 * n * n);
  m.setFromTriplets(t.begin(), t.end());
  m.makeCompressed();
  return m;
}

Eigen::VectorXd ramp(Eigen::Index size)
{
  Eigen::VectorXd b(size);
  for (Eigen::Index i = 0; i < size; ++i)
    b[i] = std::sin(0.37 * static_cast<double>(i)) + 0.1;
  return b;
}

/// |(a + shift·I)·x − b| / |b|, a's lower triangle given.
double relativeResidual(const Eigen::SparseMatrix<double>& a, double shift, const Eigen::VectorXd& x,
                        const Eigen::VectorXd& b)
{
  const Eigen::VectorXd ax = a.selfadjointView<Eigen::Lower>() * x + shift * x;
  return (ax - b).norm() / b.norm();
}

// Below 3,000 rows (CHOLMOD's own ordering) and above (nested dissection), with a shift: the
// solve is (a + shift·I)⁻¹ b to rounding, as CHOLMOD's own supernodal solve gives it.
TEST(KeptFactor, SolvesTheShiftedMatrixAsCholmodsOwnSolveDoes)
{
  for (const int n : { 12, 40 })
  {
    const Eigen::SparseMatrix<double> a = sheetMatrix(n, 1.0);
    const double shift = 0.25;
    KeptFactor kept;
    ASSERT_TRUE(kept.factorize(a, shift, 7)) << n;
    EXPECT_EQ(kept.rows(), a.rows());
    const Eigen::VectorXd b = ramp(a.rows());
    long tag = 0;
    const Eigen::VectorXd x = kept.solve(b, &tag);
    EXPECT_EQ(tag, 7);
    ASSERT_EQ(x.size(), b.size());
    EXPECT_LT(relativeResidual(a, shift, x, b), 1e-12) << n;
    numerics::SpdFactorization reference;
    ASSERT_TRUE(reference.factorize(a, shift));
    const Eigen::VectorXd expected = reference.solve(b);
    EXPECT_LT((x - expected).norm(), 1e-11 * expected.norm()) << n;
    EXPECT_EQ(kept.solve(Eigen::VectorXd::Ones(a.rows() + 1)).size(), 0) << "another size: no solve";
  }
}

// A matrix that is not positive definite keeps the last good factor, and its tag.
TEST(KeptFactor, AFailedFactorisationKeepsTheLastGoodFactor)
{
  const Eigen::SparseMatrix<double> a = sheetMatrix(10, 1.0);
  KeptFactor kept;
  ASSERT_TRUE(kept.factorize(a, 0.0, 3));
  Eigen::SparseMatrix<double> indefinite = a;
  indefinite.coeffRef(5, 5) = -10.0;
  EXPECT_FALSE(kept.factorize(indefinite, 0.0, 4));
  EXPECT_EQ(kept.tag(), 3);
  const Eigen::VectorXd b = ramp(a.rows());
  EXPECT_LT(relativeResidual(a, 0.0, kept.solve(b), b), 1e-12);
}

// Threads solve while the factor is made anew, again and again, for one of two matrices: each
// solve is that of the factor whose tag it reports, never a mix, and none waits for the BLAS
// (the lock is held by this test's thread throughout: a solve that took it would never return).
TEST(KeptFactor, SolvesFromOtherThreadsWhileTheNextFactorIsMadeUseOneWholeFactor)
{
  const int n = 30;
  const Eigen::SparseMatrix<double> soft = sheetMatrix(n, 1.0), stiff = sheetMatrix(n, 3.0);
  const Eigen::VectorXd b = ramp(soft.rows());
  KeptFactor kept;
  ASSERT_TRUE(kept.factorize(soft, 0.0, 1));
  std::atomic<bool> stop{ false };
  std::atomic<int> solves{ 0 }, wrong{ 0 };
  std::vector<std::thread> solvers;
  for (int k = 0; k < 2; ++k)
    solvers.emplace_back([&] {
      while (!stop)
      {
        long tag = 0;
        const Eigen::VectorXd x = kept.solve(b, &tag);
        const Eigen::SparseMatrix<double>& a = tag % 2 == 1 ? soft : stiff;
        if (x.size() != b.size() || !(relativeResidual(a, 0.0, x, b) < 1e-12))
          ++wrong;
        ++solves;
      }
    });
  std::unique_lock<std::mutex> blas = numerics::lockBlas();
  // The factorisations take the lock themselves: made in a thread of their own once this test
  // lets go of it, while the solves run on.
  std::thread maker([&] {
    for (long tag = 2; tag <= 20; ++tag)
      kept.factorize(tag % 2 == 1 ? soft : stiff, 0.0, tag);
  });
  while (solves < 20)
    std::this_thread::yield();
  blas.unlock();
  maker.join();
  const int before = solves;
  while (solves < before + 4)
    std::this_thread::yield();
  stop = true;
  for (std::thread& t : solvers)
    t.join();
  EXPECT_EQ(wrong, 0) << "of " << solves << " solves";
  EXPECT_EQ(kept.tag(), 20);
}

}  // namespace
}  // namespace virtual_origami::core

// L-BFGS's memory and two-loop recursion (lbfgs_history.h), the engine the rigid-face driver
// and the curved solver share: the secant equation, BFGS's exact inverse on a quadratic, the
// pairs it refuses and the memory it keeps, for both vector types.
#include <gtest/gtest.h>

#include <Eigen/Dense>

#include "virtual_origami/numerics/lbfgs_history.h"

namespace virtual_origami::numerics
{
namespace
{
/// A symmetric positive definite matrix with eigenvalues 1 … 9 (well away from the identity
/// the recursion starts from).
Eigen::MatrixXd spd(int n)
{
  Eigen::MatrixXd m = Eigen::MatrixXd::Random(n, n);
  const Eigen::HouseholderQR<Eigen::MatrixXd> qr(m);
  const Eigen::MatrixXd q = qr.householderQ();
  Eigen::VectorXd eigenvalues = Eigen::VectorXd::LinSpaced(n, 1.0, 9.0);
  return q * eigenvalues.asDiagonal() * q.transpose();
}

const auto identity = [](const auto& v) { return v; };

TEST(LbfgsHistory, TheNewestPairMeetsTheSecantEquation)
{
  const Eigen::MatrixXd a = spd(6);
  LbfgsHistory<Eigen::VectorXd> history(3);
  Eigen::VectorXd s;
  for (int k = 0; k < 4; ++k)
  {
    s = Eigen::VectorXd::Random(6);
    ASSERT_TRUE(history.add(s, a * s));
  }
  // H·y = s for the last pair, whatever the pairs before it.
  EXPECT_LT((history.apply(Eigen::VectorXd(a * s), identity) - s).norm(), 1e-12 * s.norm());
}

TEST(LbfgsHistory, ConjugateStepsOfAQuadraticGiveItsExactInverse)
{
  // BFGS from the identity along n A-conjugate steps of a quadratic ends at A⁻¹ exactly.
  const int n = 5;
  const Eigen::MatrixXd a = spd(n);
  const Eigen::LLT<Eigen::MatrixXd> llt(a);
  // Conjugate directions: A^{-1/2}-images of an orthonormal basis, through A's Cholesky factor.
  const Eigen::MatrixXd conjugate = llt.matrixU().solve(Eigen::MatrixXd::Identity(n, n));
  LbfgsHistory<Eigen::VectorXd> history(n);
  for (int k = 0; k < n; ++k)
    ASSERT_TRUE(history.add(conjugate.col(k), a * conjugate.col(k)));
  const Eigen::VectorXd q = Eigen::VectorXd::Random(n);
  EXPECT_LT((history.apply(q, identity) - llt.solve(q)).norm(), 1e-10 * llt.solve(q).norm());
}

TEST(LbfgsHistory, RowsPerVertexGiveTheSameStepsAsAFlatVector)
{
  // The rigid-face driver's vectors (a row per vertex) and the curved solver's (flat): the same
  // numbers in another shape give the same step.
  const int vertices = 4;
  const Eigen::MatrixXd a = spd(3 * vertices);
  LbfgsHistory<Eigen::VectorXd> flat(2);
  LbfgsHistory<Eigen::MatrixX3d> rows(2);
  const auto asRows = [&](const Eigen::VectorXd& v) {
    return Eigen::MatrixX3d(Eigen::Map<const Eigen::MatrixX3d>(v.data(), vertices, 3));
  };
  for (int k = 0; k < 3; ++k)
  {
    const Eigen::VectorXd s = Eigen::VectorXd::Random(3 * vertices);
    flat.add(s, a * s);
    rows.add(asRows(s), asRows(a * s));
  }
  const Eigen::VectorXd q = Eigen::VectorXd::Random(3 * vertices);
  const Eigen::VectorXd by_flat = flat.apply(q, identity);
  const Eigen::MatrixX3d by_rows = rows.apply(asRows(q), identity);
  EXPECT_LT((asRows(by_flat) - by_rows).norm(), 1e-12 * by_flat.norm());
}

TEST(LbfgsHistory, PairsWithoutPositiveCurvatureAreRefusedAndTheOldestGoes)
{
  LbfgsHistory<Eigen::VectorXd> history(2);
  const Eigen::VectorXd s = Eigen::VectorXd::Unit(3, 0);
  // Negative and zero curvature: refused, the recursion left the initial inverse.
  EXPECT_FALSE(history.add(s, -s));
  EXPECT_FALSE(history.add(s, Eigen::VectorXd::Unit(3, 1)));
  EXPECT_TRUE(history.empty());
  const Eigen::VectorXd q(Eigen::Vector3d(1.0, 2.0, 3.0));
  EXPECT_EQ(history.apply(q, identity), q);
  // Memory 2: a third pair pushes the first out, whose secant no longer holds.
  const Eigen::Vector3d stiffness(2.0, 3.0, 5.0);
  for (int k = 0; k < 3; ++k)
  {
    const Eigen::VectorXd step = Eigen::VectorXd::Unit(3, k);
    ASSERT_TRUE(history.add(step, stiffness.cwiseProduct(step)));
  }
  // Pairs along axes 1 and 2 kept: those directions exact, axis 0 left to the identity.
  EXPECT_NEAR(history.apply(Eigen::VectorXd(Eigen::Vector3d(0, 3, 0)), identity)(1), 1.0, 1e-14);
  EXPECT_NEAR(history.apply(Eigen::VectorXd(Eigen::Vector3d(0, 0, 5)), identity)(2), 1.0, 1e-14);
  EXPECT_NEAR(history.apply(Eigen::VectorXd(Eigen::Vector3d(2, 0, 0)), identity)(0), 2.0, 1e-14);
  // No memory: nothing kept.
  LbfgsHistory<Eigen::VectorXd> none(0);
  EXPECT_FALSE(none.add(s, s));
  history.clear();
  EXPECT_TRUE(history.empty());
}
}  // namespace
}  // namespace virtual_origami::numerics

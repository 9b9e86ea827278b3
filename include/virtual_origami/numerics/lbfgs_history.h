// L-BFGS's memory and its two-loop recursion on top of a factorised matrix, shared by the
// rigid-face driver (QuasiNewtonDriver, one row per vertex) and the curved solver's constant
// matrix (CurvedSolver, one flat vector): the same engine for both, as Liu, Bouaziz & Kavan
// (2017) use it, the factorisation's inverse as the initial Hessian at its own scale.
#pragma once

#include <cmath>
#include <deque>
#include <utility>
#include <vector>

#include <Eigen/Core>

namespace virtual_origami::numerics
{
/// The inner product of two states' worth of coordinates, per vector type (each solver's own
/// summation order, so its steps are what they were before the engine was shared).
inline double innerProduct(const Eigen::VectorXd& a, const Eigen::VectorXd& b)
{
  return a.dot(b);
}
inline double innerProduct(const Eigen::MatrixX3d& a, const Eigen::MatrixX3d& b)
{
  return (a.array() * b.array()).sum();
}

/// The last `memory` pairs of step s = Δx and gradient change y = Δ∇E, oldest first.
template <class Vector>
class LbfgsHistory
{
public:
  explicit LbfgsHistory(int memory) : memory_(memory) {}

  /// Keeps the pair when its curvature sᵀy is positive beyond rounding (only such pairs keep
  /// the inverse positive definite), dropping the oldest past `memory`; false when not kept.
  bool add(Vector step, Vector change)
  {
    const double curvature = innerProduct(step, change);
    if (memory_ <= 0 || !(curvature > 1e-12 * std::sqrt(innerProduct(step, step) * innerProduct(change, change))))
      return false;
    steps_.push_back(std::move(step));
    changes_.push_back(std::move(change));
    rho_.push_back(1.0 / curvature);
    if (static_cast<int>(steps_.size()) > memory_)
    {
      steps_.pop_front();
      changes_.pop_front();
      rho_.pop_front();
    }
    return true;
  }

  void clear()
  {
    steps_.clear();
    changes_.clear();
    rho_.clear();
  }
  bool empty() const { return steps_.empty(); }

  /// The inverse Hessian L-BFGS has made of the pairs applied to `q` (a gradient: the step is
  /// its negative), `initial_inverse` the inverse of the matrix it starts from.
  template <class InitialInverse>
  Vector apply(Vector q, const InitialInverse& initial_inverse) const
  {
    std::vector<double> alpha(steps_.size());
    for (size_t k = steps_.size(); k-- > 0;)
    {
      alpha[k] = rho_[k] * innerProduct(steps_[k], q);
      q -= alpha[k] * changes_[k];
    }
    Vector r = initial_inverse(q);
    for (size_t k = 0; k < steps_.size(); ++k)
    {
      const double beta = rho_[k] * innerProduct(changes_[k], r);
      r += (alpha[k] - beta) * steps_[k];
    }
    return r;
  }

private:
  int memory_;
  std::deque<Vector> steps_, changes_;
  std::deque<double> rho_;
};

}  // namespace virtual_origami::numerics

#include "rigid_motions.h"

#include <cmath>

#include "virtual_origami/numerics/lbfgs_history.h"

namespace virtual_origami::core
{
RigidMotions::RigidMotions(const Positions& x, const std::vector<int>& free)
{
  const Eigen::Index n = static_cast<Eigen::Index>(free.size());
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  for (int v : free)
    centre += x.col(v);
  centre /= static_cast<double>(n);
  for (int axis = 0; axis < 6; ++axis)
  {
    Eigen::MatrixX3d b(n, 3);
    for (Eigen::Index i = 0; i < n; ++i)
    {
      const Eigen::Vector3d unit = Eigen::Vector3d::Unit(axis % 3);
      b.row(i) = (axis < 3 ? unit : unit.cross(x.col(free[i]) - centre)).transpose();
    }
    for (const Eigen::MatrixX3d& c : basis_)
      b -= numerics::innerProduct(c, b) * c;
    const double norm = std::sqrt(numerics::innerProduct(b, b));
    if (norm > 1e-12)
      basis_.push_back(b / norm);
  }
}

void RigidMotions::remove(Eigen::MatrixX3d& step) const
{
  for (const Eigen::MatrixX3d& c : basis_)
    step -= numerics::innerProduct(c, step) * c;
}

}  // namespace virtual_origami::core

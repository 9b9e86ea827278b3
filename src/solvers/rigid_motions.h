// The six rigid motions of a floating sheet, to clear a crease driver's steps of (private to
// src/solvers).
#pragma once

#include <vector>

#include <Eigen/Core>

#include "virtual_origami/core/positions.h"

namespace virtual_origami::core
{
/// The six rigid motions of the sheet at x over the free vertices (every vertex free), made
/// orthonormal once per state: the energy does not see them, so without an anchor they are
/// only rounding noise the shift of the matrix would blow up into a drift, and every step is
/// cleared of them.
class RigidMotions
{
public:
  RigidMotions(const Positions& x, const std::vector<int>& free);
  void remove(Eigen::MatrixX3d& step) const;

private:
  std::vector<Eigen::MatrixX3d> basis_;
};

}  // namespace virtual_origami::core

// Rigid origami on fold angles: every face is placed by composing rigid turns about the
// creases of a spanning tree of faces, so faces are exact by construction (zero strain);
// Levenberg–Marquardt on the fold angles and the root's pose closes the loops around the
// vertices and meets the held vertices. The zero-strain ground truth, slow on big models
// (its Jacobian is dense: a crease near the root moves everything beyond it).
#pragma once

#include <string>
#include <vector>

#include "virtual_origami/core/shape_solver.h"

namespace virtual_origami::core
{
struct RigidKinematicsOptions
{
  /// Weight of a pull towards the positions the solve starts from, divided by ten every
  /// iteration until it vanishes: it picks the branch nearest the start and leaves the
  /// solution exact.
  double stay_weight = 1e-2;
  double damping = 1e-3;  // Levenberg–Marquardt μ relative to the largest diagonal entry
};

class RigidKinematicsSolver : public ShapeSolver
{
public:
  explicit RigidKinematicsSolver(RigidKinematicsOptions options = {});
  std::string name() const override
  {
    return "rigid_kinematics";
  }
  /// Starts from the fold angles the edges record (rotate() sets the turned crease's).
  SolveReport solve(Paper& paper, const std::vector<char>& fixed) override;

private:
  RigidKinematicsOptions options_;
};

}  // namespace virtual_origami::core

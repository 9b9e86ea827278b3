// Pulling vertices to given points (pins that follow tf frames, a robot's gripper): the
// pulled vertices are set there and the solver restores the faces around them, turning them
// about the creases as far as the held vertices let it.
#pragma once

#include <vector>

#include "virtual_origami/core/paper.h"
#include "virtual_origami/core/result.h"
#include "virtual_origami/core/shape_solver.h"

namespace virtual_origami::core
{
struct PullTarget
{
  int vertex = -1;
  Vec3 position = Vec3::Zero();  // in the `paper` frame
  bool operator==(const PullTarget& o) const
  {
    return vertex == o.vertex && position == o.position;
  }
};

struct PullResult
{
  SolveReport solve;
  /// Largest distance between a pulled vertex and its target after the solve (0 when the
  /// solver holds them exactly; the rigid-kinematics solver meets them in least squares).
  double residual = 0.0;
};

/// Moves every target's vertex to its position and lets `solver` restore the face shapes,
/// holding the targets and `held` vertices. Fails with a message, leaving `paper` as it was,
/// on an unknown or repeated vertex, a position that is not finite, no solver, or a solve
/// that does not converge (a target the faces cannot reach without stretching). Fold angles
/// follow the new shape; faces that come to lie on each other get the layer order they
/// approached from.
Expected<PullResult> pull(Paper& paper, const std::vector<PullTarget>& targets, ShapeSolver* solver,
                          const std::vector<int>& held = {});

}  // namespace virtual_origami::core

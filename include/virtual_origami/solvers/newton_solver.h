// Gauss–Newton (Newton's method without the residual-curvature term, exact at the zero-
// residual solution) with Levenberg–Marquardt damping and a backtracking line search on
// the rigid-face energy of rigid_faces.h. Each face's rotation is fitted exactly before every
// step and eliminated from the linear system (variable projection), so the sparse system is
// over the free vertices only and converges quadratically.
#pragma once

#include <string>
#include <vector>

#include "virtual_origami/solvers/shape_solver.h"

namespace virtual_origami::core
{
struct NewtonOptions
{
  /// Levenberg–Marquardt damping μ = damping · |gradient| (floored at min_damping): it fades
  /// as the solution nears, keeping quadratic convergence, and picks the smallest move along
  /// the free directions of a mechanism (a fold with degrees of freedom left).
  double damping = 1.0;
  double min_damping = 1e-12;
  int max_line_search = 40;
  double armijo = 1e-4;
};

class NewtonSolver : public ShapeSolver
{
public:
  explicit NewtonSolver(NewtonOptions options = {});
  std::string name() const override
  {
    return "newton";
  }
  SolveReport solve(Paper& paper, const std::vector<char>& fixed) override;

private:
  NewtonOptions options_;
};

}  // namespace virtual_origami::core

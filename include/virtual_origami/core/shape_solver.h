// The interface every rigid-face solver implements: restore face shapes around held vertices.
#pragma once

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "virtual_origami/core/paper.h"

namespace virtual_origami::core
{
struct SolveReport
{
  bool converged = false;
  bool diverged = false;  // NaN or growing energy: the solver rolled the paper back
  int iterations = 0;
  double max_strain = 0.0;  // |l/l0 − 1| over every vertex pair of each face, at the end
  double seconds = 0.0;     // wall time of the solve
  // The linear algebra it paid for, where a solver counts it (the crease drivers do): sparse
  // factorisations, and back-substitutions with the factors (each a conjugate-gradient step).
  int factorizations = 0;
  int back_substitutions = 0;
  std::string message;
};

/// When a solver stops. Every solver is anytime: it stops at whichever limit comes first and
/// leaves its best usable shape in the paper (converged false when the tolerance was not met).
struct SolveLimits
{
  double tolerance = 1e-10;  // max strain that counts as converged
  int max_iterations = 1000;
  double max_seconds = 0.0;  // wall-time budget; 0: none
  /// Iterative rigid solvers (newton): more than a hundred times the tolerance away, stop once
  /// the energy fell less than 1 % over this many iterations ("stalled"); 0: never. For a
  /// caller that takes only a rigid state near where the solve starts (closing a balance,
  /// core/assignment_fold.cpp): a solve may still converge after such a stall, drifting far
  /// (the 6-point hypar's closures), so a caller that would take any rigid state leaves it off.
  int stall_window = 0;
};

/// A solve's time budget for a paper of `vertices`: `seconds` up to 10,000 vertices, growing
/// beyond as a step's sparse factorisation of a sheet's mesh does (nested dissection: as the
/// vertices to the power 1.5). At 100,000 vertices a release's rigid closure took 1 s a step and a
/// 3-s budget stopped it after three; a budget in proportion (30 s) stopped it after 20 steps, 31.7
/// s through spring_solver beside the other nodes, at strain 1.6e-9 against its 1e-10, and the
/// release went on to minutes of stiffened balances in paper_model (docs/BENCHMARKS.md).
inline double budgetForSize(double seconds, size_t vertices)
{
  return seconds * std::pow(std::max(1.0, static_cast<double>(vertices) / 1e4), 1.5);
}

class ShapeSolver
{
public:
  virtual ~ShapeSolver() = default;
  virtual std::string name() const = 0;
  /// Moves the vertices not in `fixed` (one flag per vertex; an empty vector holds none) so
  /// that every face regains its crease-pattern shape. On divergence the paper is left as it
  /// was given (rolled back) and the report says so; a diverged shape is never published.
  virtual SolveReport solve(Paper& paper, const std::vector<char>& fixed) = 0;
  /// As solve(), converged at the strain `looser` where that is looser than the solver's own
  /// tolerance: a frame of a drag, balanced again when it is committed (`looser` 0: a frame
  /// balanced to the solver's own tolerance). A solver that cannot stop there solves as solve() does.
  virtual SolveReport solveLoosely(Paper& paper, const std::vector<char>& fixed, double looser)
  {
    (void)looser;
    return solve(paper, fixed);
  }

  /// Makes ready what a solve of `paper` around `fixed` would make first (a factorising solver:
  /// the pattern's ordering and symbolic factor), moving nothing: a model readies its solver
  /// for a pattern just loaded, so the first fold's closure does not pay for it. A solver that
  /// keeps nothing between solves does nothing.
  virtual void prepare(const Paper& paper, const std::vector<char>& fixed)
  {
    (void)paper;
    (void)fixed;
  }
  const SolveLimits& limits() const { return limits_; }
  void setLimits(const SolveLimits& limits) { limits_ = limits; }

protected:
  SolveLimits limits_;
};

}  // namespace virtual_origami::core

// Gauss–Newton (Newton's method without the residual-curvature term, exact at the zero-
// residual solution) with Levenberg–Marquardt damping and a backtracking line search on
// the rigid-face energy of rigid_faces.h. Each face's rotation is fitted exactly before every
// step and eliminated from the linear system (variable projection), so the sparse system is
// over the free vertices only and converges quadratically.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "virtual_origami/core/shape_solver.h"

namespace virtual_origami::core
{
struct NewtonOptions
{
  /// Levenberg–Marquardt damping μ = damping · |gradient| / scale, at least min_damping (the
  /// matrix's entries are of order 1): it fades as the solution nears, keeping the quadratic
  /// convergence, while the floor keeps steps along the free directions of a mechanism (a
  /// fold with degrees of freedom left) from blowing up rounding errors.
  double damping = 1e-4;
  double min_damping = 1e-8;
  /// A solve whose whole steps at that floor creep (each cuts the energy by less than half)
  /// lowers the floor a hundredfold per step down to this (min_damping: never); a step the line
  /// search must shorten restores min_damping. Near a flat sheet a large mechanism's soft modes
  /// are less stiff than 1e-8, and the floor, not the model, held its steps back. (A lower floor
  /// lets rounding move an unheld exact mechanism further: docs/SOLVERS.md, Known limits.)
  double lowest_damping = 1e-12;
  /// The floor a drag's frame starts at and returns to (solveLoosely): near the flat sheet its
  /// steps crept at min_damping until the floor was lowered, three of a preview's four
  /// iterations at 1,681 vertices; at 10,000 a drag's later previews now take one step, not four.
  /// Lower for every solve (1e-10 or 1e-12), rigid closures drifted along their mechanism's free
  /// motion (a degree-4 vertex's crease angles 1.4e-6 from the driver's balance) or failed; a
  /// frame is balanced again, at min_damping, when its turn is committed.
  double frame_damping = 1e-12;
  /// A frame's whole step that creeps is tried longer while the energy falls (up to 32 times).
  bool extend_creeping_frames = true;
  /// Keep a factorisation for the next steps while each cuts the energy below
  /// refactor_ratio of what it was (a chord step: one back-substitution instead of a
  /// factorisation); refactor when progress slows.
  bool reuse_factorization = true;
  double refactor_ratio = 0.1;
  int max_line_search = 40;
  double armijo = 1e-4;
};

class NewtonSolver : public ShapeSolver
{
public:
  explicit NewtonSolver(NewtonOptions options = {});
  ~NewtonSolver() override;
  std::string name() const override
  {
    return "newton";
  }
  SolveReport solve(Paper& paper, const std::vector<char>& fixed) override;
  SolveReport solveLoosely(Paper& paper, const std::vector<char>& fixed, double looser) override;
  void prepare(const Paper& paper, const std::vector<char>& fixed) override;

private:
  /// `frame`: a drag's frame (solveLoosely): NewtonOptions::frame_damping, creeping steps
  /// tried longer, the analysis readied.
  SolveReport solveWithin(Paper& paper, const std::vector<char>& fixed, const SolveLimits& limits, bool frame);

  struct Setup;  // sparse pattern and symbolic factorisation, kept while faces and held vertices stay
  /// The set-up for `paper` around `fixed`: a kept one that matches, else a new one.
  Setup& setupFor(const Paper& paper, const std::vector<char>& fixed);

  NewtonOptions options_;
  // The last set-ups used, the latest first: a model alternates between a turn's held face and
  // its folds' closures around none, and each new set-up orders the pattern again (at 10,000
  // vertices its analysis is 70 ms, the whole first closure through spring_solver 0.6 s).
  std::vector<std::unique_ptr<Setup>> setups_;
};

}  // namespace virtual_origami::core

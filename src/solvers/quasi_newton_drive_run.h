// One call of QuasiNewtonDriver::drive (private to src/solvers): the frame's state as members,
// its work as named steps. run() starts the frame (a prediction along the last frames' motion,
// or the energy where it stands), then iterates: a direction (Newton–Krylov, subspace or
// L-BFGS), a line search along it, the step taken; then restores the faces of a frame its
// limits stopped, and reports (docs/SOLVERS.md).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "quasi_newton_setup.h"
#include "rigid_motions.h"
#include "virtual_origami/numerics/lbfgs_history.h"
#include "virtual_origami/numerics/solve_budget.h"

namespace virtual_origami::core
{
class QuasiNewtonDriver::DriveRun
{
public:
  /// Makes (or keeps) the driver's set-up for this pattern, holds and driven creases.
  DriveRun(QuasiNewtonDriver& driver, Paper& paper, const std::vector<double>& target, const std::vector<char>& fixed);
  SolveReport run();
  /// What the first frame would factorise, made without a frame (QuasiNewtonDriver::prepare).
  void prepareFirstFrame();

private:
  /// Where the line search ended: the trial taken, if any.
  struct Trial
  {
    bool accepted = false;
    bool restored = false;  // the accepted trial is a restored one, off the line
    double step_length = 1.0;
    DrivenFaces::Evaluation energy;
  };
  /// A subspace step so far: H-orthonormal directions u_i and H u_i, the step and its residual.
  struct Galerkin
  {
    std::vector<Eigen::MatrixX3d> basis, basis_product;
    Eigen::MatrixX3d step, residual;
  };

  static Setup& prepare(QuasiNewtonDriver& driver, const Paper& paper, const std::vector<double>& target,
                        const std::vector<char>& fixed);

  // run()'s steps (quasi_newton_drive_run.cpp).
  bool nothingToSolve();
  SolveReport unsolved();
  void planFrame();
  void start();
  void evaluateStart();
  void predict();
  bool iterate();
  Eigen::MatrixX3d direction();
  bool descends(Eigen::MatrixX3d& direction, double& slope, const RigidMotions* drift);
  Trial lineSearch(const Eigen::MatrixX3d& direction, double slope);
  void take(const Eigen::MatrixX3d& direction, const Trial& trial, double step_size);
  void restoreFinalFaces();
  void rememberFrameStep(int k, double length);
  SolveReport finish();

  // The directions and the matrices they use (quasi_newton_steps.cpp).
  Eigen::MatrixX3d lbfgsStep();
  Eigen::MatrixX3d newtonKrylovStep(const DrivenFaces::Linearization& l, const RigidMotions* rigid);
  void followMotion(const DrivenFaces::Linearization& l, const RigidMotions* rigid, Eigen::MatrixX3d& direction);
  Eigen::MatrixX3d subspaceStep(const DrivenFaces::Linearization& l, const RigidMotions* rigid);
  void addToSubspace(Galerkin& galerkin, Eigen::MatrixX3d v, const DrivenFaces::Linearization& l,
                     const RigidMotions* rigid);
  Eigen::MatrixX3d multiply(const DrivenFaces::Linearization& l, const Eigen::MatrixX3d& v);
  Eigen::MatrixX3d precondition(const Eigen::MatrixX3d& q);
  Eigen::MatrixX3d solveConstant(const Eigen::MatrixX3d& rhs);
  void restoreFaces(Positions& at, Positions& at_gradient, DrivenFaces::Evaluation& at_energy);
  bool refactor();
  void refactorAfresh();
  void assembleGaussNewton();
  bool fits(double work) const;
  bool roomForFactor() const;
  double turnedSinceFactor(const DrivenFaces::Linearization& l) const;

  /// The free vertices' rows of x (the layout of the solves), and x moved by length · step there.
  Eigen::MatrixX3d gather(const Positions& x) const;
  void moveFree(Positions& x, double length, const Eigen::MatrixX3d& step) const;

  // What the call was given.
  QuasiNewtonDriver& driver_;
  const QuasiNewtonOptions& options_;
  const SolveLimits limits_;
  numerics::SolveBudget budget_;
  Setup& setup_;
  DrivenFaces& energy_;
  Paper& paper_;
  const std::vector<double>& target_;
  const std::vector<char>& fixed_;
  const std::vector<int>& free_;
  SolveReport report_;

  // The frame: where it starts and what kind it is (planFrame).
  Positions start_;
  double scale_ = 1.0;
  bool anchored_ = false;
  // Start from a prediction along the motion when this is the frame after the last two (the
  // last went on from the one before it: a new slide's second frame has no motion to go by).
  bool continues_ = false;
  // The first frame on this set-up (none returned yet).
  bool first_frame_ = false;
  // A frame whose budget cannot pay for a factorisation of the Gauss–Newton matrix, going on
  // from the last frame along its motion: its steps come from the subspace of that motion and
  // the constant matrix's conjugate directions (subspaceStep), no factorisation used.
  bool subspace_frame_ = false;
  bool predicts_ = false;

  // Where the iterates stand.
  Positions x_, gradient_;
  Eigen::MatrixX3d g_;  // the gradient at the free vertices
  DrivenFaces::Evaluation now_;
  bool start_evaluated_ = false;
  // A subspace frame linearises where it starts in the same pass (the faces' fits shared).
  DrivenFaces::Linearization start_linearization_;
  bool start_linearized_ = false;
  Positions trial_, trial_gradient_;
  // The last frame's own motion, where this frame goes on from it: the direction a mechanism
  // is turning in (see followMotion).
  Eigen::MatrixX3d motion_;
  // A subspace frame's rigid motions, made once where it starts (they only keep the steps from
  // drifting the floating sheet: a frame's small motion does not change them measurably).
  std::optional<RigidMotions> frame_rigid_;
  // Any other frame's, made afresh at every iterate where nothing is held.
  std::optional<RigidMotions> step_rigid_;
  numerics::LbfgsHistory<Eigen::MatrixX3d> history_;

  // What an energy pass and a back-substitution cost here: a frame's budget is spent only on
  // work that ends within it (the last step's line search and the report come after).
  double evaluate_seconds_ = 0.0;
  double solve_seconds_ = 0.0;
  double subspace_add_seconds_ = 0.0;
  // A frame stopped by its budget ends with a restoring step (restore_final_faces): kept room.
  double final_reserve_ = 0.0;

  // The iteration's bookkeeping.
  bool refresh_ = false;         // factorise afresh before the next direction
  bool frames_pending_ = false;  // the next linearisation records the faces' frames of the factorisation
  bool krylov_slow_ = false;     // the last step's conjugate gradients took more than half their iterations
  bool krylov_cut_ = false;      // the budget ended the last step's conjugate gradients
  // Newton–Krylov steps multiply by the energy's own Hessian (exact_hessian) once the steps
  // converge (two whole steps in a row, neither shortened nor restored, the second less than
  // half the first). Far from a balance it is indefinite, and near-singular along a mechanism
  // starting to turn, where Gauss–Newton's convex model takes the better steps (a turn from the
  // flat sheet). A step it gives that is not taken whole hands back to Gauss–Newton for the
  // rest of the frame. Subspace frames multiply by the Gauss–Newton matrix (their Galerkin
  // model must be convex).
  bool exact_allowed_ = false, exact_products_ = false, exact_refused_ = false, last_whole_ = false;
  bool last_restored_ = false;     // the last step taken was a trial with its faces restored
  Positions spread_, product_;     // multiply's work space
  Eigen::MatrixX3d step_product_;  // H times the step newtonKrylovStep or subspaceStep returned
  double last_step_ = INFINITY;
  bool diverged_ = false;
  bool stopped_by_limits_ = false;
  std::string stuck_;
};

}  // namespace virtual_origami::core

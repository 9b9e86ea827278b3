// The crease drivers: L-BFGS on the energy of driven_faces.h with a factorised matrix as its
// initial Hessian (after Liu, Bouaziz & Kavan 2017), in three kinds:
// - constant: the face Laplacian with rotations frozen plus the driven hinges' flat-state
//   stiffness, factorised once per pattern and held set (their design, kept for comparison:
//   it calls a mechanism's turns stiff, so L-BFGS crawls along them);
// - lagged (the default, "quasi_newton"): Newton–Krylov. Each step solves the Gauss–Newton
//   system at the current state (each face's rotation eliminated, never assembled) by
//   conjugate gradients, preconditioned by that matrix factorised at an earlier state and
//   kept across iterations and frames; refactorised when the iterations grow (not within a
//   frame's time budget). Once the steps converge, the conjugate gradients run on the
//   energy's own Hessian instead (exact_hessian: quadratic convergence near the balance);
// - exact ("newton", the reference): that matrix refactorised every iteration (damped
//   Gauss–Newton).
// Each frame starts from a prediction along the motion of the frames before it. Anytime.
// A lagged driver's frame whose time budget cannot pay for a factorisation (a preview's) is a
// subspace frame: the Galerkin step over the last motion and the constant matrix's conjugate
// directions, with no back-substitution of the Gauss–Newton matrix (docs/SOLVERS.md).
#pragma once

#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "virtual_origami/core/assignment_fold.h"
#include "virtual_origami/numerics/spd_factorization.h"

namespace virtual_origami::core
{
enum class DriverHessian
{
  Constant,
  Lagged,
  Exact,
};

struct QuasiNewtonOptions
{
  DriverHessian hessian = DriverHessian::Lagged;
  /// Lagged: refactorise when an iteration leaves more than this share of the step it started
  /// from (the kept matrix no longer predicts the energy well).
  double refresh_ratio = 0.5;
  /// Lagged: refactorise before a step where some face has turned by δ since the kept
  /// factorisation with K·δ² above this (K the face stiffness; 0: never). That matrix's face
  /// term then charges the mechanism's present turn more than the hinges do.
  double refactor_turn = 1.0;
  /// Lagged: conjugate-gradient iterations per Newton step, and the residual (relative to the
  /// gradient) that ends them early. 1 %: at 5 % a 40 × 40 Miura-ori's first corner turn from
  /// the flat sheet took 22 steps (linear convergence), at 1 % it takes 12 like the later ones.
  int krylov_iterations = 8;
  double krylov_tolerance = 0.01;
  /// The driver's initial face stiffness (CreaseDriver::setFaceStiffness changes it).
  double face_stiffness = 1e4;
  int memory = 8;  // L-BFGS correction pairs
  double armijo = 1e-4;
  int max_line_search = 30;
  /// Extrapolate each frame from the last two this driver returned (when the paper it gets
  /// is the last it returned).
  bool predict = true;
  /// Restore the faces of a frame's prediction by one step of the constant matrix (a local–
  /// global step) where the straight prediction costs more energy than it gains, or after a
  /// frame that its budget stopped before balance.
  bool restore_predicted_faces = true;
  /// A step whose linear trial the line search refuses is tried once more with its faces
  /// restored (one step of the constant matrix) before it is shortened: a turn's first steps
  /// from the flat sheet then go the whole way, not a quarter (a 40 × 40 Miura-ori's corner
  /// turn: 8 steps and 5 factorisations instead of 13 and 8). Subspace frames too: a
  /// 10,000-vertex slide in 5 % steps then keeps up with the handle.
  bool restore_trial_faces = true;
  /// Lagged: each Newton–Krylov step also moves along the last frame's motion as far as the
  /// Gauss–Newton model says (a kept matrix calls a mechanism's present turn stiff, and a
  /// slide's frames fall behind along it).
  bool follow_motion = true;
  /// Lagged: Newton–Krylov steps solve with the energy's own Hessian (DrivenFaces::
  /// hessianProduct), the kept Gauss–Newton factorisation as preconditioner. Gauss–Newton
  /// leaves out the faces' residual stress and the hinges' curvature, which along a mechanism
  /// are as large as the hinges' stiffness: its steps converge only linearly.
  bool exact_hessian = true;
  /// End a frame its limits stopped short of balance with one step of the constant matrix that
  /// restores the faces its last (linear) step stretched; room for it is kept in a time budget.
  /// A last step taken with its faces restored (restore_trial_faces) needs none.
  bool restore_final_faces = true;
  /// Lagged: a frame whose time budget is below `subspace_below_seconds` and that goes on from
  /// the last frame's motion takes its steps in the subspace of that motion and up to
  /// `subspace_directions` conjugate directions of the constant matrix (no factorisation).
  bool subspace_frames = true;
  double subspace_below_seconds = 0.1;
  int subspace_directions = 6;
  /// A subspace frame that ends with more strain than this restores its faces once more.
  double restore_strain = 5e-4;
  /// A subspace frame's line search starts at the step length the frames before it took, not
  /// the whole step: in a fast slide (5 % a frame) the whole step overshoots frame after frame,
  /// and each halving costs an energy pass and a restoring step (a third of a frame). The
  /// length grows back to whole after `frame_step_growth_frames` frames that took their first trial.
  bool remember_frame_step = true;
  int frame_step_growth_frames = 2;
};

class QuasiNewtonDriver : public CreaseDriver
{
public:
  explicit QuasiNewtonDriver(QuasiNewtonOptions options = {});
  ~QuasiNewtonDriver() override;
  std::string name() const override;
  /// Converged when a preconditioned step would move no vertex more than
  /// limits().tolerance · the sheet's scale (balance), whatever strain the faces keep.
  /// Calls from several threads take turns (the set-up and the kept factorisation are shared).
  SolveReport drive(Paper& paper, const std::vector<double>& target, const std::vector<char>& fixed) override;
  /// The set-up for this pattern, held vertices and driven creases, its constant matrix
  /// factorised and (lagged) the Gauss–Newton matrix at the paper's state, where the kept ones
  /// do not serve: a preview's first frame then pays for no factorisation and is a subspace
  /// frame (the kept matrix's step among its directions). The last frames stay as they were.
  void prepare(const Paper& paper, const std::vector<double>& target, const std::vector<char>& fixed) override;
  std::unique_ptr<CreaseDriver> clone() const override;
  /// The last frames set aside and the kept Gauss–Newton factorisation forgotten; the set-up
  /// (the energy, the constant matrix's factor, the matrices' memory) kept for the next calls.
  void setFramesAside() override;
  /// The frames back; the factorisation the calls since kept stays (where they made it), and a
  /// first frame no longer takes prepare's.
  void putFramesBack() override;

  const QuasiNewtonOptions& options() const { return options_; }

private:
  struct Setup;
  class DriveRun;  // one call of drive(): its state and named steps
  QuasiNewtonOptions options_;
  std::mutex mutex_;
  std::unique_ptr<Setup> setup_;
  struct Frames;
  std::unique_ptr<Frames> aside_;  // setFramesAside's, until putFramesBack
  // The Gauss–Newton matrix's symbolic analysis, shared with this driver's clones (a commit's
  // fresh clone copies it instead of analysing again; it depends on the pattern alone).
  std::shared_ptr<numerics::SpdFactorization::SharedAnalysis> analysis_;
  // Where each entry of the Gauss–Newton matrix lands in its compressed pattern, shared with
  // the clones as well (sorting a 10,000-vertex pattern's million entries takes 60 ms).
  struct AssemblyPlan;
  std::shared_ptr<AssemblyPlan> assembly_;
};

}  // namespace virtual_origami::core

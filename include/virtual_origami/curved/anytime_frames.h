// Curved paper at the mouse: one displayed frame per pointer event within a fixed wall-time
// budget. Each frame carries the last shape on along the pins' path and corrects it by
// conjugate gradients preconditioned by the last factorisation of the Hessian that a
// background thread made (back-substitutions and gradients, no Hessian in the frame); every
// step is checked against the true energy and force at the frame's own state, so a factor made
// for an older state is used only where it still descends. The thread renews the factor at the
// latest shown state. Where the Hessian there is not positive definite (the sheet buckles or
// snaps), the frames turn inertial: the paper's mass over the frame time squared, M/h², is added
// to the matrix and each frame is a step of implicit Euler from rest, until a static
// factorisation succeeds again. On release the shape is polished to balance.
#pragma once

#include <atomic>
#include <condition_variable>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

#include "virtual_origami/core/result.h"
#include "virtual_origami/curved/contact.h"
#include "virtual_origami/curved/curved_forces.h"
#include "virtual_origami/curved/curved_solver.h"
#include "virtual_origami/curved/kept_factor.h"
#include "virtual_origami/curved/surroundings.h"

namespace virtual_origami::core
{
struct AnytimeFrameOptions
{
  /// Wall time a frame may spend on corrections after its prediction (seconds); a correction
  /// is begun only when the time it took last fits in what is left. At least one is made.
  double frame_seconds = 0.026;
  int max_corrections = 6;
  /// The budget counted in the frame thread's CPU time instead of the wall's (on a machine
  /// shared with other work, the frames then do what an unshared one would in that time).
  bool budget_in_thread_cpu = false;
  /// A new factorisation is asked for at the shown state every this many frames (and at once
  /// after a correction the residual check refused).
  int refactor_frames = 1;
  /// Factorisations in a thread of their own; false: in frame() itself when due (for tests:
  /// the same frames every run).
  bool background = true;
  /// h of the inertial frames: one pointer event at 30 Hz.
  double time_step = 1.0 / 30.0;
  /// The share of its velocity an inertial frame carries into the next (1: implicit Euler;
  /// 0: each step from rest, the paper's mass as a proximal term, so the energy falls with every
  /// frame however stale the factor: a snap animated, fully damped).
  double kept_velocity = 0.0;
  /// Mass per area of the inertial frames; 0: the material's own for a physical paper
  /// (thickness given, SI), else the mass that gives this sheet kami's bending time scale.
  double density = 0.0;
  /// The frames stop correcting below this force (over stretch × spacing, as the solver's).
  double frame_tolerance = 1e-10;
  /// release(): the force to reach, and the wall time it may take.
  double release_tolerance = 1e-8;
  double release_seconds = 6.0;
  /// Negative curvature below this × stretch is rounding (the free turn about two pins): the
  /// static factorisation's shift.
  double static_shift = 1e-10;
  /// The static factorisation's shift (× stretch; one try, none smaller where it fails); a
  /// matrix indefinite there makes the frames inertial (a loss of stability: the curvatures of
  /// the snaps of curved_speed_bench's drag are −1e-9 to −1e-7, an off-balance frame's a little
  /// below zero).
  double static_shift_limit = 1e-10;
  /// Inertial frames turn static again, after return_frames of them, where the matrix
  /// factorises with this shift × stretch (they lag the pointer: a little off balance).
  double return_shift_limit = 1e-8;
  int return_frames = 5;
  /// A frame shown with a force above this (over stretch × spacing) is off balance: the next
  /// frame's carry is a straight one (a polynomial through shapes off balance magnifies their
  /// errors).
  double off_balance_force = 1e-6;
  /// release(): rounds of corrections with a factor made for the state they start at, before
  /// Newton (CurvedSolver, saddles left) finishes.
  int release_rounds = 3;
  /// A correction moves no node farther than this × the contact range.
  double max_step = 0.4;
};

struct FrameReport
{
  double seconds = 0.0;         // wall time of the frame
  double start_force = 0.0;     // largest force at the predicted start, over stretch × spacing
  double start_energy = 0.0;    // the frame's objective there (inertial: with M/h²)
  double energy = 0.0;          // and at the shown shape
  double max_force = 0.0;       // at the shown shape (static: the balance's force, weight and contact in)
  int corrections = 0;          // taken
  int refused = 0;              // refused by the residual check (the step did not lower the energy)
  bool inertial = false;        // an implicit Euler step (the static matrix did not factorise)
  long factor_frame = -1;       // the frame whose shown state the factor used was made at
  double solve_seconds = 0.0;   // of it in back-substitutions with the factor
  bool contact_search = false;  // the contact candidates were searched in the frame
};

struct ReleaseReport
{
  bool converged = false;
  double max_force = 0.0;
  double seconds = 0.0;
  int corrections = 0;
  int factorizations = 0;
  int frame_factorizations = 0;  // of them, made for the rounds of corrections (static only)
  int newton_iterations = 0;     // of the Newton solve that finished it, if one did
};

class AnytimeFrames
{
public:
  /// `mesh` and `paper` must outlive the frames.
  AnytimeFrames(const CurvedMesh& mesh, const Paper& paper, const CurvedMaterial& material = {},
                const ContactOptions& contact = {}, const AnytimeFrameOptions& options = {},
                const Surroundings& surroundings = {});
  ~AnytimeFrames();
  AnytimeFrames(const AnytimeFrames&) = delete;
  AnytimeFrames& operator=(const AnytimeFrames&) = delete;

  /// Takes the shape `x` (one column per node) with `pins` (the held nodes for every later
  /// frame) and makes the first factorisation there, before any frame. Refused, nothing taken,
  /// for positions of another mesh or pins off the sheet or not finite.
  Status start(const Positions& x, const std::vector<CurvedPin>& pins);

  /// One displayed frame with the pins at `pins` (the same nodes as start's, in order).
  /// Refused (an empty report with refused set by the returned status) for other nodes.
  Expected<FrameReport> frame(const std::vector<CurvedPin>& pins);

  /// The pointer let go: the shape is brought to release_tolerance at the last pins, by rounds
  /// of corrections each with a factor made for the state it starts at, and where those do not
  /// get there (the sheet still snapping, release_rounds spent) by Newton.
  ReleaseReport release();

  /// Makes the factor the frames correct with at `x` now, static (or inertial where that fails),
  /// as the background would; tagged as made for frame `tag_frame`.
  void keepFactorAt(const Positions& x, long tag_frame);

  const Positions& positions() const
  {
    return x_;
  }
  long frames() const
  {
    return frame_;
  }
  int factorizations() const
  {
    return factorizations_;
  }
  /// CPU time the factorising thread (or frame() when not in the background) spent on factors.
  double factorCpuSeconds() const
  {
    return factor_cpu_;
  }
  /// The mass per area of the inertial frames.
  double density() const
  {
    return density_;
  }
  /// Energy of `x` (terms, contact, weight and table) and its gradient over the free nodes.
  double energy(const Positions& x, Eigen::VectorXd* gradient);

private:
  struct Request
  {
    Positions x;
    long frame = 0;
    bool search_contact = false;
    double h = 0.0;
    double static_limit = 0.0;
    bool static_only = false;  // no inertial factor where the static one fails (the release)
  };
  void backgroundLoop();
  void makeFactor(const Positions& x, long frame, double h, double static_limit, bool static_only = false);
  /// The largest static shift the next factor may take (see return_shift_limit).
  double staticLimit() const;
  void ask(bool search_contact, bool static_only = false);
  void waitForFactor(long frame);
  /// Modified Newton corrections of x_ with the kept factor toward the objective's balance
  /// (inertial: around y with M/h²), within `seconds` (at least one); the report filled in.
  void correct(const Positions* y, double seconds, int max_corrections, double tolerance, FrameReport& report);
  double objective(const Positions& x, const Positions* y, Eigen::VectorXd* gradient, Eigen::VectorXd* static_gradient);
  double forceOf(const Eigen::VectorXd& g) const;

  const CurvedMesh& mesh_;
  const Paper& paper_;
  CurvedMaterial material_;
  ContactOptions contact_options_;
  AnytimeFrameOptions options_;
  Surroundings surroundings_;
  CurvedTerms terms_;
  LayerContact contact_;
  double density_ = 0.0;
  std::vector<double> mass_;  // per node, of the inertial frames
  std::vector<int> pinned_;
  std::vector<int> free_index_;
  int free_count_ = 0;
  Positions x_, x_before_, older_;  // shown now, one frame before, two (static frames only)
  std::vector<CurvedPin> pins_, pins_before_, pins_older_;
  Eigen::VectorXd velocity_;
  bool inertial_ = false;
  int inertial_frames_ = 0;     // in a row, to this one
  double shown_force_ = 0.0;    // the static force at the shape shown last
  double step_h_ = 1.0 / 30.0;  // of the inertial matrix and objective (release lengthens it)
  bool started_ = false;
  long frame_ = 0;
  long last_request_ = -1000;
  double correction_seconds_ = 0.0;  // the last correction's wall time
  // The factor and the thread that makes it.
  KeptFactor factor_;
  Eigen::SparseMatrix<double> hessian_;  // the factorising side's
  double inertial_shift_ = 0.0;          // the shift the last inertial factor took
  std::atomic<int> factorizations_{ 0 };
  std::atomic<double> factor_cpu_{ 0.0 };
  std::mutex mutex_;
  std::condition_variable wake_, made_;
  bool has_request_ = false, stop_ = false;
  Request request_;
  long made_frame_ = -1;
  std::unique_ptr<LayerContact::Candidates> found_;  // candidates the thread found, not yet taken
  std::unique_ptr<CurvedSolver> newton_;             // the release's last resort
  std::thread thread_;
};

}  // namespace virtual_origami::core

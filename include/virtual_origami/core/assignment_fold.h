// Folding by assignment (Origami Simulator's "fold percent"): every assigned crease is driven
// towards a fraction of its target fold angle at once, and the faces follow as far as they can
// keep their crease-pattern shape.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "virtual_origami/core/paper.h"
#include "virtual_origami/core/positions.h"
#include "virtual_origami/core/result.h"
#include "virtual_origami/core/shape_solver.h"

namespace virtual_origami::core
{
/// Where each edge is meant to go, FOLD sign (positive valley): the file's edges_foldAngle when
/// it gave one (Edge::target_angle), else +π for a valley, −π for a mountain, 0 for a flat crease;
/// NaN for an edge no target drives (unassigned, cut, boundary).
std::vector<double> creaseTargets(const Paper& paper);

/// Strain |l/l0 − 1| of each face: the largest over its vertex pairs (for colouring by strain).
std::vector<double> faceStrains(const Paper& paper);

/// A solver that drives creases: it moves the vertices not in `fixed` to balance the faces'
/// shape (stiff) against every crease whose target is finite (a spring of stiffness
/// `crease_stiffness` · its length towards target[e]); NaN targets are free hinges. Anytime:
/// it stops at its limits with its best shape so far. `converged` means balanced (the energy's
/// gradient below the tolerance), not rigid: max_strain reports what the faces kept.
class CreaseDriver
{
public:
  virtual ~CreaseDriver() = default;
  virtual std::string name() const = 0;
  virtual SolveReport drive(Paper& paper, const std::vector<double>& target, const std::vector<char>& fixed) = 0;
  /// A fresh driver of the same kind, limits and stiffness, sharing no state with this one that
  /// could change what it computes (for a computation that changes its stiffness while others
  /// use this one); what depends on the pattern alone, like a factorisation's ordering, may be
  /// shared.
  virtual std::unique_ptr<CreaseDriver> clone() const = 0;
  /// Readies what this driver's first call on `paper` with these targets' driven creases and
  /// `fixed` would make before it could move anything (a set-up, a factorisation at the paper's
  /// state), so that a caller can pay for it ahead of that call (in the background, after a new
  /// pattern). Moves nothing and leaves what later calls go on from (the last frames) as it
  /// was. Nothing by default.
  virtual void prepare(const Paper& /*paper*/, const std::vector<double>& /*target*/,
                       const std::vector<char>& /*fixed*/)
  {}
  /// Sets aside what later calls would go on from (the last frames) and forgets a kept
  /// factorisation, keeping what the pattern alone decides (a set-up): the next calls compute
  /// what a fresh clone's would, without making the set-up again. Called again before
  /// putFramesBack, it forgets the calls since and keeps the first frames aside. Nothing by
  /// default.
  virtual void setFramesAside() {}
  /// The frames set aside back, as if the calls since had not been made (they leave only the
  /// factorisation they kept, where they made it). Nothing by default.
  virtual void putFramesBack() {}

  const SolveLimits& limits() const { return limits_; }
  void setLimits(const SolveLimits& limits) { limits_ = limits; }
  /// Face stiffness K against the creases' (dimensionless, per cell): a crease kept δ radians
  /// from its target leaves a strain of about δ / K in the faces beside it.
  double faceStiffness() const { return face_stiffness_; }
  void setFaceStiffness(double stiffness) { face_stiffness_ = stiffness; }

protected:
  SolveLimits limits_;
  double face_stiffness_ = 1e4;
};

struct AssignmentFoldRequest
{
  /// 0: every driven crease towards its flat state, 1: towards its full target, −1: towards
  /// the opposite of its target (every mountain a valley; Origami Simulator's −100 %).
  double fraction = 1.0;
  /// False for a preview frame: one call of the driver within its limits (a time budget), from
  /// the paper as given (the last frame). True to commit: staged in the fraction from the one
  /// the paper's angles fit (foldFraction; no crease's target moves more than `max_stage_angle`
  /// per stage), balanced, then made rigid by `rigid` when a rigid shape lies within reach
  /// (strain ≤ its tolerance); else the balanced shape is kept with its strain reported.
  bool converge = true;
  double max_stage_angle = 0.17453292519943295;  // 10°
  /// Face stiffness on the way of a commit of more than one stage (below the driver's own): a
  /// pattern that is no rigid mechanism, like a square twist, folds only through strained
  /// faces, which stiff faces never enter. The stages run with it, then the goal is balanced
  /// again with the driver's stiffness. A one-stage commit (a slide's step) stays stiff, and so
  /// does a paper with compliant faces (they bend instead).
  double path_stiffness = 100.0;
  /// A commit's driver runs in pieces (100 iterations, then 20) and stops once a piece moves no
  /// vertex further than this share of the sheet: settled as far as any figure measures
  /// (flatness and crossings are judged at 1e-6 of the sheet), where the driver's own tolerance
  /// (a step of 1e-9) near a singular balance is reached only linearly or not at all. 0: each
  /// stage one call of the driver, to its tolerance or its limit (2,000 iterations).
  double settled_move = 1e-6;
  /// A recorded commit's result (a replay): the folded positions to take instead of driving
  /// anything, one column per vertex. Its figures are measured as a solve's are, so a replay
  /// is answered as the commit was; rigid when its faces keep their shape to kRigidStrain.
  const Positions* result = nullptr;
  /// The committed paper a commit goes on from when it starts at a preview frame: the creases
  /// asked to turn, and those that did not, are counted from it (from the paper given if null).
  const Paper* committed = nullptr;
  /// A commit in `driver` itself (the driver of the previews it goes on from, under a commit's
  /// limits), its frames set aside meanwhile (CreaseDriver::setFramesAside): it computes what
  /// fresh clones would, on the set-up the previews made, where a clone makes that set-up again;
  /// the previews after it go on as they would have. False: in fresh clones.
  bool in_driver = false;
};

/// The strain below which a taken result counts as rigid (what the rigid solver closes to).
constexpr double kRigidStrain = 1e-9;

struct AssignmentFoldResult
{
  double fraction = 0.0;
  SolveReport solve;          // the driver's, iterations and seconds summed over stages
  bool rigid = false;         // the rigid solver closed the faces exactly
  double max_strain = 0.0;    // of the result
  double angle_error = 0.0;   // RMS distance of the driven creases from fraction · target (rad)
  std::vector<double> face_strain;
  /// A committed result with faces lying flat on each other: how many such pairs its recorded
  /// layer order (faceOrders, layer_order.h) orders, and, where no stacking of them exists (the
  /// layers would cross), why.
  int ordered_pairs = 0;
  std::string layer_problem;
  /// A committed result with faces lying flat on each other whose order was not worked out
  /// (a stack over the bounds recordLayerOrder sets, or a search that gave up): why. Its layers
  /// are then neither ordered nor checked against crossing, and the answer says so.
  std::string layers_unordered;
  /// Driven creases left on the other side of flat from where they were driven (further than
  /// kAgainstTargetAngle): a fold that went the wrong way.
  int against_target = 0;
  /// A commit's pairs of faces passing through each other (face_crossings.h); previews are
  /// not checked (a frame's budget is for the solve).
  int crossings = 0;
  /// A commit's driven creases asked to turn (their goal more than 0.05 rad from where they
  /// were), and those of them that turned less than a hundredth of the way (held by faces that
  /// cannot bend, or waiting for others, as a bird base's petal creases near flat).
  int asked_to_turn = 0;
  int stuck = 0;
  /// Faces of the file that rigid faces would lock (curved bands) and that bend instead, cut
  /// into triangles whose facets bend (core/compliant_faces.h), and their largest bend (rad).
  int compliant_faces = 0;
  double largest_bend = 0.0;
};

/// How far past flat a driven crease may lie before it counts as folded against its target.
constexpr double kAgainstTargetAngle = 1e-3;
/// At ±100 %, the RMS distance of the driven creases from their targets that counts as there.
constexpr double kTargetReached = 1e-3;

/// When a commit's result is right for paper (SPEC §2): its strain within `max_strain`, no
/// crease against its target, no faces crossing, its layers stackable, most creases asked to
/// turn turned, and at ±100 % every driven crease at its target (within kTargetReached).
struct AssignmentFoldAcceptance
{
  double max_strain = 1e-3;
  /// True: the state is kept whatever it is (the caller asked for it), its figures reported.
  bool keep = false;
};

/// Readies `driver` for foldByAssignment's preview frames (converge false) on `paper` with
/// `held` vertices, as their first frame would (CreaseDriver::prepare): the same faces (locked
/// ones made compliant on a copy), driven creases and held vertices. Nothing where `held` names
/// a vertex not on the paper (the frame refuses it).
void prepareAssignmentPreviews(const Paper& paper, CreaseDriver& driver, const std::vector<int>& held = {});

/// Readies `rigid` (ShapeSolver::prepare) for the closures of folds by assignment of `paper`
/// around `held`: the paper and held vertices a commit closes rigidly. Nothing where `held` names
/// a vertex not on the paper.
void prepareAssignmentClosure(const Paper& paper, ShapeSolver& rigid, const std::vector<int>& held = {});

/// What makes `result` wrong by `acceptance` (figures included, for the answer), or "" when
/// nothing does or the caller keeps it anyway.
std::string assignmentFoldProblems(const AssignmentFoldResult& result, const AssignmentFoldAcceptance& acceptance);

/// Folds `paper` by assignment. Fails (paper untouched) on a fraction outside [−1, 1] or not
/// finite, a paper without a driven crease, a driver that diverged, or a given result that does
/// not fit the paper (one finite position per vertex, held vertices where they are).
Expected<AssignmentFoldResult> foldByAssignment(Paper& paper, const AssignmentFoldRequest& request,
                                                CreaseDriver& driver, ShapeSolver* rigid,
                                                const std::vector<int>& held = {});

}  // namespace virtual_origami::core

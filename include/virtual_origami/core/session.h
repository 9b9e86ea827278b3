// One folding session: the current paper, its operation log and undo/redo history.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "virtual_origami/core/assignment_fold.h"
#include "virtual_origami/core/crease.h"
#include "virtual_origami/core/flat_fold.h"
#include "virtual_origami/core/paper.h"
#include "virtual_origami/core/pull.h"
#include "virtual_origami/core/kept_bend.h"
#include "virtual_origami/core/rotate.h"
#include "virtual_origami/core/snap.h"
#include "virtual_origami/core/squash.h"
#include "virtual_origami/core/shape_solver.h"

namespace virtual_origami::core
{
/// A committed operation with its parameters: enough to apply it again (replay, logs).
struct Operation
{
  enum class Kind
  {
    Crease,
    Rotate,
    Squash,
    Undo,
    Redo,
    Reset,
    Load,
    Pull,
    AssignmentFold,
    FlatFold,    // fold on chosen creases (flat_fold.h)
    DragVertex,  // one vertex dragged to a point, the faces following (pull.h)
    KeepBend,    // the curved model's bent sheet kept as the paper's state (kept_bend.h)
  };
  Kind kind = Kind::Crease;
  CreaseRequest crease;   // Crease: the request as given (before snapping)
  RotateRequest rotate;   // Rotate: with face and axis resolved
  double size = 1.0;      // Reset: the sheet's side
  std::string path;       // Load: where the model came from
  std::vector<PullTarget> pull;  // Pull: where the vertices were pulled to (pins following frames)
  double fraction = 0.0;  // AssignmentFold: how far towards the creases' targets, −1 to 1
  /// AssignmentFold and Rotate: where every vertex ended, when a recording gives it
  /// (Operation.msg's `folded`); applying the operation then takes these positions instead of
  /// solving again.
  /// Not kept in the history's log (the state after the operation holds them).
  std::vector<Vec3> folded;
  FlatFoldRequest flat_fold;  // FlatFold: the creases, their angles and the face that stays
  PullTarget drag;            // DragVertex: the vertex and where it was dragged to
  BentSheet bend;             // KeepBend: the sheet as it was let go
  uint64_t revision = 0;  // the revision it produced
};

const char* kindName(Operation::Kind kind);

/// Said by a load refused because the model is the paper as it is (no new revision).
constexpr const char* kNothingLoaded = "nothing loaded (no new revision)";

/// Sheet sizes reset() accepts, in metres.
constexpr double kMinSheetSize = 1e-6;
constexpr double kMaxSheetSize = 1e6;

/// Everything a session remembers: the current paper, the states undo and redo go back
/// and forth through, and the log of operations.
struct History
{
  Paper paper;
  uint64_t revision = 0;
  std::vector<Paper> undo, redo;
  std::vector<Operation> log;
};

/// A change computed away from the session, committed only onto the revision it started from:
/// a node computes solver-bound changes outside its lock and journals them before committing.
struct Change
{
  Operation operation;        // with the revision it will produce
  std::optional<Paper> next;  // the state it makes; none for undo and redo
  uint64_t base_revision = 0;
};

/// A computed operation: what it reports and the change it makes.
template <class Result>
struct Computed
{
  Result result;
  Change change;
};

/// What computing an operation needs, copied out of a session (so that the computation may
/// run while the session serves others). The solver is shared, not copied: computations that
/// run at once need one that takes concurrent calls (paper_model's RemoteSolver does).
struct Workspace
{
  Paper paper;
  uint64_t revision = 0;
  std::shared_ptr<ShapeSolver> solver;
  SnapSettings snap;
  std::vector<int> held;
  /// Folding by assignment: the driver that commits (converges), and the one previews use (a
  /// time budget); without a preview driver previews use `driver`. Shared like the solver.
  std::shared_ptr<CreaseDriver> driver, preview_driver;
  /// The last fold-by-assignment preview on this revision: the next preview goes on from it
  /// (one solve from the last frame), while a commit starts from `paper`.
  std::optional<Paper> assignment_preview;
  /// The crease driver that guides turn previews (rotate.h, TurnGuide), kept across calls so
  /// that a drag's previews follow its last frames; commits (and previews without one) guide
  /// with a fresh clone of `driver`.
  std::shared_ptr<CreaseDriver> turn_driver;
  /// The last turn preview on this revision with the held vertices as now, and what made it
  /// (face and axis resolved): a preview of the same turn goes on from it (rotate.h, TurnStart).
  std::optional<Paper> rotate_preview;
  RotateRequest rotate_preview_request;
  /// The previews of the same turn before rotate_preview (at most two, oldest first), each with
  /// its request angle (TurnStart::before).
  std::vector<std::pair<Paper, double>> rotate_previews_before;
  /// The strain a turn preview's solve converges at, where looser than the solver's own (0: the
  /// solver's): a preview is a frame of the drag, and its commit is balanced to the solver's.
  double turn_preview_tolerance = 0.0;
};

/// The operations as functions of a workspace; none touches a session. A rotation's change is
/// its preview too.
Expected<Computed<CreaseResult>> computeCrease(Workspace workspace, const CreaseRequest& request);
/// `preview` true: a drag's preview, which goes on from the workspace's rotate_preview of the
/// same turn. A commit goes on from that preview too (none solved when it showed this turn at this
/// angle), and its state is the turn from the committed paper to where the vertices ended, which
/// is what a replay takes (`recorded`, Operation::folded): the replay lands on it bit for bit.
Expected<Computed<RotateResult>> computeRotate(Workspace workspace, const RotateRequest& request, bool preview = false,
                                               const std::vector<Vec3>* recorded = nullptr);
/// Refused when the paper is flat already (pressing it would change nothing).
Expected<Computed<SquashResult>> computeSquash(Workspace workspace);
Expected<Computed<PullResult>> computePull(Workspace workspace, const std::vector<PullTarget>& targets);
/// Folds every driven crease to `fraction` (−1 to 1) of its target (assignment_fold.h).
/// `commit` true: converged from the last preview on this revision (the branch the user saw as
/// the slider moved; from the committed paper when there is none, or when the driver diverges
/// from the preview), and refused when the result is wrong for paper by `acceptance`
/// (assignmentFoldProblems: strain, creases against their target, crossings, layers) unless it
/// keeps it. The change's state is the result, and its positions are what a replay takes
/// (`recorded`, Operation::folded): a replay lands where the commit did, bit for bit, without
/// solving again. `commit` false: a preview frame from the last preview, within the preview
/// driver's budget, never refused for its figures. Pins are held. `figures`, when given,
/// receives the result's figures whether or not it is refused.
Expected<Computed<AssignmentFoldResult>> computeFoldByAssignment(Workspace workspace, double fraction,
                                                                 bool commit = true,
                                                                 const AssignmentFoldAcceptance& acceptance = {},
                                                                 AssignmentFoldResult* figures = nullptr,
                                                                 const std::vector<Vec3>* recorded = nullptr);
/// Folds on chosen creases (flat_fold.h). Refused when the fold moves nothing or would move a
/// held vertex (a pin). The change's state is the folded paper.
Expected<Computed<FlatFoldResult>> computeFlatFold(Workspace workspace, const FlatFoldRequest& request);
/// A preview frame of that fold, `fraction` (0 to 1) of the way from the paper now
/// (flatFoldFrame): refused exactly when computeFlatFold would be, the result that of the whole
/// fold, the change's state the frame (for Session::setPreview; never to commit).
Expected<Computed<FlatFoldResult>> computeFlatFoldPreview(Workspace workspace, const FlatFoldRequest& request,
                                                          double fraction);
/// Keeps the curved model's bent sheet as the paper's state (keepBend). Refused as keepBend
/// refuses, and when the sheet would move a held vertex (a pin).
Expected<Computed<KeptBend>> computeKeepBend(Workspace workspace, const BentSheet& sheet);
/// Drags one vertex to a point: the solver restores the faces around it, the held vertices
/// (pins) hold (pull.h). Refused on an unknown vertex, a point that is not finite, a pinned
/// vertex, no solver, or when no shape of rigid faces follows. Previews and commits both start
/// from the committed paper, so a commit is what its last preview showed and what replay makes.
Expected<Computed<PullResult>> computeDragVertex(Workspace workspace, const PullTarget& target);
Expected<Change> computeReset(uint64_t base_revision, double size);
Expected<Change> computeLoad(uint64_t base_revision, Paper paper, const std::string& path);

/// Approximate heap bytes a paper holds (the history's memory is counted with it).
size_t approximateBytes(const Paper& paper);

/// Every change is a transaction: it succeeds fully and gets a new revision and a history
/// entry, or fails with a message and leaves the paper and the revision as they were.
class Session
{
public:
  explicit Session(Paper initial = Paper::square(1.0));
  /// A session that goes on from a recorded history (see session_journal.h).
  explicit Session(History history);

  const Paper& paper() const { return history_.paper; }
  uint64_t revision() const { return history_.revision; }
  const std::vector<Operation>& log() const { return history_.log; }
  const History& history() const { return history_; }
  bool canUndo() const { return !history_.undo.empty(); }
  bool canRedo() const { return !history_.redo.empty(); }

  void setSolver(std::shared_ptr<ShapeSolver> solver) { solver_ = std::move(solver); }
  ShapeSolver* solver() const { return solver_.get(); }
  SnapSettings& snapSettings() { return snap_settings_; }
  /// Vertices no operation may move (pins): solvers hold them, and a rotation that would
  /// carry one away is refused.
  void setHeldVertices(std::vector<int> held) { held_ = std::move(held); }
  /// The crease drivers folding by assignment uses (see Workspace).
  void setCreaseDrivers(std::shared_ptr<CreaseDriver> driver, std::shared_ptr<CreaseDriver> preview_driver = nullptr)
  {
    driver_ = std::move(driver);
    preview_driver_ = std::move(preview_driver);
    turn_driver_.reset();
    if (driver_)
    {
      turn_driver_ = driver_->clone();
      turn_driver_->setFaceStiffness(TurnGuide{}.face_stiffness);
    }
  }

  Expected<CreaseResult> crease(const CreaseRequest& request);
  /// With commit false the result is a preview (`preview()`), not in history, and the
  /// committed paper stays as it is; the next preview starts again from it.
  /// `recorded`: a commit's positions as a recording gives them (computeRotate).
  Expected<RotateResult> rotate(const RotateRequest& request, bool commit = true,
                                const std::vector<Vec3>* recorded = nullptr);
  const std::optional<Paper>& preview() const { return preview_; }
  Expected<SquashResult> squash();
  Status undo();
  Status redo();
  Status reset(double size);
  Status load(Paper paper, const std::string& path);
  /// Pulls vertices to points (see pull.h), holding the held vertices.
  Expected<PullResult> pull(const std::vector<PullTarget>& targets);
  /// Folds by assignment to `fraction`; with commit false a preview, as for rotate.
  Expected<AssignmentFoldResult> foldByAssignment(double fraction, bool commit = true,
                                                  const AssignmentFoldAcceptance& acceptance = {},
                                                  const std::vector<Vec3>* recorded = nullptr);
  /// Folds on chosen creases; with commit false a preview (`preview()`) `fraction` of the way.
  Expected<FlatFoldResult> flatFold(const FlatFoldRequest& request, bool commit = true, double fraction = 1.0);
  /// Drags a vertex to a point; with commit false a preview, as for rotate.
  Expected<PullResult> dragVertex(const PullTarget& target, bool commit = true);
  /// Keeps a bent sheet (computeKeepBend); always a commit.
  Expected<KeptBend> keepBend(const BentSheet& sheet);

  /// Applies a logged operation again (its parameters as logged).
  Status apply(const Operation& operation);

  /// A copy of what computing an operation needs.
  Workspace workspace() const;
  Expected<Change> prepareUndo() const;
  Expected<Change> prepareRedo() const;
  /// Whether commit would take `change`: refused when the session has moved on from the
  /// revision it was computed from, an undo or redo with nothing to step to, and a load of the
  /// paper as it is (a new revision that changes nothing). A node checks before it journals.
  Status check(const Change& change) const;
  /// Commits a computed change; refused (nothing changed) as check refuses.
  Status commit(Change change);
  /// Shows a computed rotation, fold or drag as the preview, unless the session has
  /// moved on since.
  bool setPreview(Change change);

  /// Undo states beyond this many bytes (the undo and redo states together, by approximateBytes)
  /// are forgotten, oldest first; 0: no limit. The operation log and the journal keep every
  /// operation all the same.
  void setHistoryLimit(size_t bytes);
  /// Workspace::turn_preview_tolerance (0, the default: previews converge as commits do).
  void setTurnPreviewTolerance(double strain) { turn_preview_tolerance_ = strain; }
  /// Bytes the undo and redo states hold, and how many undo states the limit has dropped.
  size_t historyBytes() const { return history_bytes_; }
  size_t forgottenStates() const { return forgotten_; }

private:
  void trimHistory();


  History history_;
  std::optional<Paper> preview_;
  Operation::Kind preview_kind_ = Operation::Kind::Rotate;  // what made preview_
  RotateRequest preview_rotate_;                            // a turn preview's request, resolved
  std::vector<int> preview_held_;                           // the held vertices preview_ kept
  std::vector<std::pair<Paper, double>> previews_before_;  // turn previews before preview_ on its drag
  std::shared_ptr<CreaseDriver> turn_driver_;               // a clone of driver_ (Workspace)
  double turn_preview_tolerance_ = 0.0;
  std::shared_ptr<ShapeSolver> solver_;
  std::shared_ptr<CreaseDriver> driver_, preview_driver_;
  SnapSettings snap_settings_;
  std::vector<int> held_;
  size_t history_limit_ = 0;
  size_t history_bytes_ = 0;  // of history_.undo and history_.redo
  size_t forgotten_ = 0;
};

}  // namespace virtual_origami::core

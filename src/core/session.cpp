#include "virtual_origami/core/session.h"

#include <cmath>
#include <optional>
#include <sstream>

#include "virtual_origami/core/bend_reach.h"
#include "virtual_origami/core/validity.h"

namespace virtual_origami::core
{
const char* kindName(Operation::Kind kind)
{
  switch (kind)
  {
    case Operation::Kind::Crease:
      return "crease";
    case Operation::Kind::Rotate:
      return "rotate";
    case Operation::Kind::Squash:
      return "squash";
    case Operation::Kind::Undo:
      return "undo";
    case Operation::Kind::Redo:
      return "redo";
    case Operation::Kind::Reset:
      return "reset";
    case Operation::Kind::Load:
      return "load";
    case Operation::Kind::Pull:
      return "pull";
    case Operation::Kind::AssignmentFold:
      return "fold_by_assignment";
    case Operation::Kind::FlatFold:
      return "flat_fold";
    case Operation::Kind::DragVertex:
      return "drag_vertex";
    case Operation::Kind::KeepBend:
      return "keep_bend";
  }
  return "unknown";
}

size_t approximateBytes(const Paper& paper)
{
  size_t bytes = sizeof(Paper) + paper.vertices.size() * sizeof(Vertex) + paper.edges.size() * sizeof(Edge) +
                 paper.face_orders.size() * sizeof(FaceOrder) + paper.faces.size() * sizeof(Face);
  for (const Face& face : paper.faces)
    bytes += (face.vertices.size() + face.edges.size()) * sizeof(int);
  return bytes;
}

namespace
{
Change makeChange(uint64_t base_revision, Operation::Kind kind, std::optional<Paper> next)
{
  Change change;
  change.operation.kind = kind;
  change.operation.revision = base_revision + 1;
  change.base_revision = base_revision;
  change.next = std::move(next);
  return change;
}
}  // namespace

Expected<Computed<CreaseResult>> computeCrease(Workspace workspace, const CreaseRequest& request)
{
  const std::vector<char> kept_bend = keptBendFaces(workspace.paper);
  Expected<CreaseResult> result = core::crease(workspace.paper, request, workspace.snap);
  if (!result)
    return Expected<Computed<CreaseResult>>::failure(result.message());
  // A crease through a kept bend would fold a curved face along a line that is not in it:
  // refused, the bend kept (undo the bend to crease there).
  for (int f : result->split_faces)
    if (f < static_cast<int>(kept_bend.size()) && kept_bend[f])
      return Expected<Computed<CreaseResult>>::failure(
          "the crease crosses a kept bend (face " + std::to_string(f) +
          "): paper that is bent cannot take a straight crease there; undo the bend to crease it flat");
  Change change = makeChange(workspace.revision, Operation::Kind::Crease, std::move(workspace.paper));
  change.operation.crease = request;
  return Computed<CreaseResult>{ std::move(*result), std::move(change) };
}

Expected<Computed<RotateResult>> computeRotate(Workspace workspace, const RotateRequest& request, bool preview,
                                               const std::vector<Vec3>* recorded)
{
  using Answer = Expected<Computed<RotateResult>>;
  if (recorded && recorded->size() != workspace.paper.vertices.size())
    return Answer::failure("a recorded turn gives " + std::to_string(recorded->size()) + " positions for " +
                           std::to_string(workspace.paper.vertices.size()) + " vertices; the model is unchanged");
  if (recorded)
    for (const Vec3& p : *recorded)
      if (!p.allFinite())
        return Answer::failure("a recorded turn gives a position that is not finite; the model is unchanged");
  std::vector<std::pair<int, Vec3>> held_at;
  for (int v : workspace.held)
    if (v >= 0 && v < static_cast<int>(workspace.paper.vertices.size()))
      held_at.emplace_back(v, workspace.paper.vertices[v].folded);
  // A big model's turn starts its solver where a crease driver took the turned creases
  // (rotate.h, TurnGuide); the guide's driver is a clone, its stiffness its own. Previews share
  // the session's turn driver, whose last frames predict the next; a commit takes a fresh clone.
  TurnGuide guide;
  std::unique_ptr<CreaseDriver> guide_driver;
  if (preview && workspace.turn_driver && workspace.paper.vertices.size() >= guide.min_vertices)
    guide.driver = workspace.turn_driver.get();
  else if (workspace.driver && workspace.paper.vertices.size() >= guide.min_vertices)
  {
    guide_driver = workspace.driver->clone();
    guide.driver = guide_driver.get();
  }
  // A drag's preview, and its commit, go on from the drag's last preview of the same turn
  // (rotate() checks that the request resolves to that preview's face and axis), the previews
  // before it predicting the next stage's start.
  TurnStart start;
  const RotateRequest& last = workspace.rotate_preview_request;
  const bool after_preview = workspace.rotate_preview && request.carry_stack == last.carry_stack;
  if (after_preview)
  {
    start = TurnStart{ &*workspace.rotate_preview, last.angle, last.face, last.axis_edge };
    for (const auto& [state, angle] : workspace.rotate_previews_before)
      start.before.emplace_back(&state, angle);
  }
  Expected<RotateResult> result = Expected<RotateResult>::failure("not turned");
  if (preview)
    result = core::rotate(workspace.paper, request, workspace.solver.get(), workspace.held, guide, start,
                          workspace.turn_preview_tolerance);
  else
  {
    // A commit's state is made from where its vertices end (recorded by a replay; the last
    // preview's when it showed this very turn; else solved now) by the one call a replay makes:
    // the turn taken from the model with those positions as the solved start of its last stage,
    // which the solver finds balanced. A replay with the recorded positions lands on the
    // commit's state bit for bit, and no commit solves what its preview solved already.
    std::vector<Vec3> ended;
    int face = request.face, axis_edge = request.axis_edge;
    if (recorded)
      ended = *recorded;
    else if (after_preview && request.angle == last.angle &&
             (request.face < 0 || request.face == last.face) && (request.axis_edge < 0 || request.axis_edge == last.axis_edge))
    {
      for (const Vertex& v : workspace.rotate_preview->vertices)
        ended.push_back(v.folded);
      face = last.face;
      axis_edge = last.axis_edge;
    }
    else
    {
      Paper solved = workspace.paper;
      result = core::rotate(solved, request, workspace.solver.get(), workspace.held, guide, start);
      if (!result)
        return Answer::failure(result.message());
      for (const Vertex& v : solved.vertices)
        ended.push_back(v.folded);
      face = result->face;
      axis_edge = result->axis_edge;
    }
    Paper ending = workspace.paper;
    for (size_t v = 0; v < ending.vertices.size(); ++v)
      ending.vertices[v].folded = ended[v];
    const SolveReport solving = result ? result->solve : SolveReport{};
    // (The guide runs only where the start is not taken: a request that resolves elsewhere.)
    result = core::rotate(workspace.paper, request, workspace.solver.get(), workspace.held, guide,
                          TurnStart{ &ending, request.angle, face, axis_edge });
    if (result && solving.iterations > 0)
    {
      // What the commit solved, with the check of its end summed in.
      result->solve.iterations += solving.iterations;
      result->solve.seconds += solving.seconds;
    }
  }
  if (!result)
    return Answer::failure(result.message());
  for (const auto& [v, at] : held_at)
    if ((workspace.paper.vertices[v].folded - at).norm() > 1e-9 * workspace.paper.scale())
      return Answer::failure("vertex " + std::to_string(v) + " is pinned and the rotation would move it; release it first");
  Change change = makeChange(workspace.revision, Operation::Kind::Rotate, std::move(workspace.paper));
  change.operation.rotate = request;
  change.operation.rotate.face = result->face;
  change.operation.rotate.axis_edge = result->axis_edge;
  return Computed<RotateResult>{ std::move(*result), std::move(change) };
}

namespace
{
/// Whether `after` is `before` to within rounding: every vertex where it was, every crease at its angle.
bool samePaper(const Paper& before, const Paper& after)
{
  if (before.vertices.size() != after.vertices.size() || before.edges.size() != after.edges.size() ||
      before.faces.size() != after.faces.size())
    return false;
  const double still = 1e-12 * before.scale();
  for (size_t v = 0; v < before.vertices.size(); ++v)
    if ((before.vertices[v].folded - after.vertices[v].folded).norm() > still ||
        (before.vertices[v].crease_pattern - after.vertices[v].crease_pattern).norm() > still)
      return false;
  for (size_t e = 0; e < before.edges.size(); ++e)
    if (std::abs(before.edges[e].fold_angle - after.edges[e].fold_angle) > 1e-12 ||
        before.edges[e].assignment != after.edges[e].assignment)
      return false;
  return true;
}

/// A driver under other limits for one call, its own put back after it.
class LimitsForACall
{
public:
  LimitsForACall(CreaseDriver& driver, const SolveLimits& limits) : driver_(driver), own_(driver.limits())
  {
    driver_.setLimits(limits);
  }
  ~LimitsForACall() { driver_.setLimits(own_); }
  LimitsForACall(const LimitsForACall&) = delete;
  LimitsForACall& operator=(const LimitsForACall&) = delete;

private:
  CreaseDriver& driver_;
  SolveLimits own_;
};
}  // namespace

Expected<Computed<SquashResult>> computeSquash(Workspace workspace)
{
  const Paper before = workspace.paper;
  Expected<SquashResult> result = core::squash(workspace.paper, workspace.solver.get());
  if (!result)
    return Expected<Computed<SquashResult>>::failure(result.message());
  // Found by the round-3 probe: a flat sheet answered "pressed flat" with a new revision.
  if (samePaper(before, workspace.paper))
    return Expected<Computed<SquashResult>>::failure("the paper is flat already: pressing it changes nothing");
  return Computed<SquashResult>{ std::move(*result),
                                 makeChange(workspace.revision, Operation::Kind::Squash, std::move(workspace.paper)) };
}

Expected<Computed<PullResult>> computePull(Workspace workspace, const std::vector<PullTarget>& targets)
{
  // A pull of nothing would make a new revision of the same state.
  if (targets.empty())
    return Expected<Computed<PullResult>>::failure("pull needs at least one vertex to pull");
  Expected<PullResult> result = core::pull(workspace.paper, targets, workspace.solver.get(), workspace.held);
  if (!result)
    return Expected<Computed<PullResult>>::failure(result.message());
  Change change = makeChange(workspace.revision, Operation::Kind::Pull, std::move(workspace.paper));
  change.operation.pull = targets;
  return Computed<PullResult>{ std::move(*result), std::move(change) };
}

Expected<Computed<AssignmentFoldResult>> computeFoldByAssignment(Workspace workspace, double fraction, bool commit,
                                                                 const AssignmentFoldAcceptance& acceptance,
                                                                 AssignmentFoldResult* figures,
                                                                 const std::vector<Vec3>* recorded)
{
  using Answer = Expected<Computed<AssignmentFoldResult>>;
  if (!(fraction >= -1.0 && fraction <= 1.0))  // NaN fails both
  {
    std::ostringstream given;
    given << fraction;
    return Answer::failure("the fold fraction must be a number from -1 to 1 (-100 % to 100 %), not " + given.str());
  }
  const std::shared_ptr<CreaseDriver>& driver =
      !commit && workspace.preview_driver ? workspace.preview_driver : workspace.driver;
  if (!driver)
    return Answer::failure("folding by assignment needs a crease driver, and none is set");
  std::vector<std::pair<int, Vec3>> held_at;
  for (int v : workspace.held)
    if (v >= 0 && v < static_cast<int>(workspace.paper.vertices.size()))
      held_at.emplace_back(v, workspace.paper.vertices[v].folded);
  AssignmentFoldRequest request;
  request.fraction = fraction;
  request.converge = commit;
  Positions given;
  if (recorded && commit)
  {
    given.resize(3, static_cast<Eigen::Index>(recorded->size()));
    for (size_t v = 0; v < recorded->size(); ++v)
      given.col(static_cast<Eigen::Index>(v)) = (*recorded)[v];
    request.result = &given;
  }
  // Previews and commits go on from the last preview frame: a preview is one solve per frame,
  // and a commit polishes the state the user saw (a release after a long slide solves the last
  // step, not the whole slide again from flat). The commit records where it ended, which is
  // what replays take; from flat when no preview is on show, or when the driver fails from it.
  const bool from_preview = workspace.assignment_preview && !request.result;
  Paper paper = from_preview ? std::move(*workspace.assignment_preview) : workspace.paper;
  if (from_preview && commit)
    request.committed = &workspace.paper;
  // Such a commit goes on in the previews' driver, under the commit driver's limits: the set-up
  // and factorisation its frames kept are the state's it starts at (a fresh clone making both
  // again was most of a 10,000-vertex Miura-ori's release at 40 %, docs/SOLVERS.md).
  CreaseDriver* fold_driver = driver.get();
  std::optional<LimitsForACall> commit_limits;
  if (from_preview && commit && workspace.preview_driver)
  {
    fold_driver = workspace.preview_driver.get();
    commit_limits.emplace(*fold_driver, driver->limits());
    request.in_driver = true;
  }
  Expected<AssignmentFoldResult> result =
      core::foldByAssignment(paper, request, *fold_driver, workspace.solver.get(), workspace.held);
  if (!result && from_preview && commit)
  {
    const std::string from_frame = result.message();
    request.committed = nullptr;
    paper = std::move(workspace.paper);
    result = core::foldByAssignment(paper, request, *fold_driver, workspace.solver.get(), workspace.held);
    if (result)
      result->solve.message = "not from the last preview (" + from_frame + "): from the committed paper";
  }
  if (!result)
    return Answer::failure(result.message());
  if (figures)
    *figures = *result;
  for (const auto& [v, at] : held_at)
    if ((paper.vertices[v].folded - at).norm() > 1e-9 * paper.scale())
      return Answer::failure("vertex " + std::to_string(v) +
                             " is pinned and folding by assignment would move it; release it first");
  if (commit)
  {
    const std::string problems = assignmentFoldProblems(*result, acceptance);
    if (!problems.empty())
    {
      std::ostringstream said;
      said << "not folded to " << 100.0 * fraction << " %: " << problems
           << " (keep the state with the service's keep flag)";
      return Answer::failure(said.str());
    }
  }
  Change change = makeChange(workspace.revision, Operation::Kind::AssignmentFold, std::move(paper));
  change.operation.fraction = fraction;
  return Computed<AssignmentFoldResult>{ std::move(*result), std::move(change) };
}

namespace
{
/// The first held vertex `next` puts elsewhere than `before`, or -1.
int movedHeldVertex(const Paper& before, const Paper& next, const std::vector<int>& held)
{
  for (int v : held)
    if (v >= 0 && v < static_cast<int>(before.vertices.size()) &&
        (next.vertices[v].folded - before.vertices[v].folded).norm() > 1e-9 * before.scale())
      return v;
  return -1;
}

Expected<Computed<FlatFoldResult>> flatFoldChange(Workspace& workspace, const FlatFoldRequest& request, Paper& folded)
{
  using Answer = Expected<Computed<FlatFoldResult>>;
  folded = workspace.paper;
  Expected<FlatFoldResult> result = core::flatFold(folded, request);
  if (!result)
    return Answer::failure(result.message());
  if (result->moved_faces.empty())
    return Answer::failure("the fold moves nothing: the chosen creases are at those angles already");
  const int pinned = movedHeldVertex(workspace.paper, folded, workspace.held);
  if (pinned >= 0)
    return Answer::failure("vertex " + std::to_string(pinned) + " is pinned and the fold would move it; release it first");
  Change change = makeChange(workspace.revision, Operation::Kind::FlatFold, std::nullopt);
  change.operation.flat_fold = request;
  return Computed<FlatFoldResult>{ std::move(*result), std::move(change) };
}
}  // namespace

Expected<Computed<FlatFoldResult>> computeFlatFold(Workspace workspace, const FlatFoldRequest& request)
{
  Paper folded;
  auto computed = flatFoldChange(workspace, request, folded);
  if (computed)
    computed->change.next = std::move(folded);
  return computed;
}

Expected<Computed<FlatFoldResult>> computeFlatFoldPreview(Workspace workspace, const FlatFoldRequest& request,
                                                          double fraction)
{
  using Answer = Expected<Computed<FlatFoldResult>>;
  Paper folded;
  auto computed = flatFoldChange(workspace, request, folded);
  if (!computed)
    return computed;
  Expected<Paper> frame = fraction == 1.0 ? Expected<Paper>(std::move(folded)) :
                                            flatFoldFrame(workspace.paper, request, fraction);
  if (!frame)
    return Answer::failure(frame.message());
  computed->change.next = std::move(*frame);
  return computed;
}

Expected<Computed<PullResult>> computeDragVertex(Workspace workspace, const PullTarget& target)
{
  using Answer = Expected<Computed<PullResult>>;
  const int count = static_cast<int>(workspace.paper.vertices.size());
  if (target.vertex < 0 || target.vertex >= count)
    return Answer::failure("vertex " + std::to_string(target.vertex) + " does not exist (the model has " +
                           std::to_string(count) + ")");
  if (!target.position.allFinite())
    return Answer::failure("the point to drag vertex " + std::to_string(target.vertex) + " to is not a finite point");
  for (int v : workspace.held)
    if (v == target.vertex)
      return Answer::failure("vertex " + std::to_string(v) + " is pinned; release it before dragging it");
  const Paper before = workspace.paper;
  Expected<PullResult> result = core::pull(workspace.paper, { target }, workspace.solver.get(), workspace.held);
  if (!result)
  {
    // Said too when bent paper (the curved model, which could take the drag over) cannot get there.
    const Status bends = bendingReaches(before, target, workspace.held);
    return Answer::failure("no shape of the faces follows vertex " + std::to_string(target.vertex) + " there: " +
                           result.message() + (bends ? "" : "; bent, " + bends.message()));
  }
  const int pinned = movedHeldVertex(before, workspace.paper, workspace.held);
  if (pinned >= 0)
    return Answer::failure("vertex " + std::to_string(pinned) + " is pinned and the drag would move it");
  Change change = makeChange(workspace.revision, Operation::Kind::DragVertex, std::move(workspace.paper));
  change.operation.drag = target;
  return Computed<PullResult>{ std::move(*result), std::move(change) };
}

Expected<Computed<KeptBend>> computeKeepBend(Workspace workspace, const BentSheet& sheet)
{
  using Answer = Expected<Computed<KeptBend>>;
  const Paper before = workspace.paper;
  Expected<KeptBend> result = keepBend(workspace.paper, sheet);
  if (!result)
    return Answer::failure("the bend is not kept: " + result.message());
  const int pinned = movedHeldVertex(before, workspace.paper, workspace.held);
  if (pinned >= 0)
    return Answer::failure("the bend is not kept: vertex " + std::to_string(pinned) +
                           " is pinned and the bent sheet moved it");
  Change change = makeChange(workspace.revision, Operation::Kind::KeepBend, std::move(workspace.paper));
  change.operation.bend = sheet;
  return Computed<KeptBend>{ std::move(*result), std::move(change) };
}

Expected<Change> computeReset(uint64_t base_revision, double size)
{
  // Tolerances are relative to the sheet's scale and its area is size²: keep both far from
  // overflow and underflow (a size of 1e308 made an infinite area, found by fuzzing).
  if (!(size >= kMinSheetSize && size <= kMaxSheetSize))
    return Expected<Change>::failure("the sheet size must be a number between 1e-6 and 1e6 m");
  Change change = makeChange(base_revision, Operation::Kind::Reset, Paper::square(size));
  change.operation.size = size;
  return change;
}

Expected<Change> computeLoad(uint64_t base_revision, Paper paper, const std::string& path)
{
  const double side = std::sqrt(paper.sheet_area);
  if (!(side >= kMinSheetSize && side <= kMaxSheetSize))
    return Expected<Change>::failure("the model in " + path + " is not a sheet between 1e-6 and 1e6 m across");
  const ValidityReport report = checkValidity(paper, { 1e-4, 1e-6, 1e-12 });
  if (!report.ok())
    return Expected<Change>::failure("the model in " + path + " is not valid: " + report.problems.front());
  Change change = makeChange(base_revision, Operation::Kind::Load, std::move(paper));
  change.operation.path = path;
  return change;
}

Session::Session(Paper initial) { history_.paper = std::move(initial); }

Session::Session(History history) : history_(std::move(history))
{
  for (const Paper& p : history_.undo)
    history_bytes_ += approximateBytes(p);
  for (const Paper& p : history_.redo)
    history_bytes_ += approximateBytes(p);
}

Workspace Session::workspace() const
{
  Workspace workspace{ history_.paper,
                       history_.revision,
                       solver_,
                       snap_settings_,
                       held_,
                       driver_,
                       preview_driver_,
                       {},
                       turn_driver_,
                       {},
                       {} };
  workspace.turn_preview_tolerance = turn_preview_tolerance_;
  if (preview_ && preview_kind_ == Operation::Kind::AssignmentFold)
    workspace.assignment_preview = *preview_;
  if (preview_ && preview_kind_ == Operation::Kind::Rotate && preview_held_ == held_)
  {
    workspace.rotate_preview = *preview_;
    workspace.rotate_preview_request = preview_rotate_;
    workspace.rotate_previews_before = previews_before_;
  }
  return workspace;
}

Expected<Change> Session::prepareUndo() const
{
  if (history_.undo.empty())
    return Expected<Change>::failure(forgotten_ > 0 ? "nothing more to undo (older states were forgotten to stay "
                                                      "within the history's memory limit)" :
                                                      "nothing to undo");
  return makeChange(history_.revision, Operation::Kind::Undo, std::nullopt);
}

Expected<Change> Session::prepareRedo() const
{
  if (history_.redo.empty())
    return Expected<Change>::failure("nothing to redo");
  return makeChange(history_.revision, Operation::Kind::Redo, std::nullopt);
}

Status Session::check(const Change& change) const
{
  if (change.base_revision != history_.revision)
    return failure("the model changed (revision " + std::to_string(change.base_revision) + " to " +
                   std::to_string(history_.revision) + ") while this was computed; try again");
  const Operation::Kind kind = change.operation.kind;
  if (kind == Operation::Kind::Undo || kind == Operation::Kind::Redo)
  {
    if ((kind == Operation::Kind::Undo ? history_.undo : history_.redo).empty())
      return failure(std::string("nothing to ") + kindName(kind));
    return success();
  }
  if (!change.next)
    return failure(std::string("a ") + kindName(kind) + " without the state it makes");
  // A load answered "loaded" must have changed the paper (found by the round-3 probe).
  if (kind == Operation::Kind::Load && *change.next == history_.paper)
    return failure("the model in " + change.operation.path + " is the paper as it is: " + kNothingLoaded);
  return success();
}

Status Session::commit(Change change)
{
  const Status checked = check(change);
  if (!checked)
    return checked;
  const Operation::Kind kind = change.operation.kind;
  if (kind == Operation::Kind::Undo || kind == Operation::Kind::Redo)
  {
    std::vector<Paper>& from = kind == Operation::Kind::Undo ? history_.undo : history_.redo;
    std::vector<Paper>& to = kind == Operation::Kind::Undo ? history_.redo : history_.undo;
    history_bytes_ += approximateBytes(history_.paper);
    history_bytes_ -= approximateBytes(from.back());
    to.push_back(std::move(history_.paper));
    history_.paper = std::move(from.back());
    from.pop_back();
  }
  else
  {
    for (const Paper& p : history_.redo)
      history_bytes_ -= approximateBytes(p);
    history_.redo.clear();
    history_bytes_ += approximateBytes(history_.paper);
    history_.undo.push_back(std::move(history_.paper));
    history_.paper = std::move(*change.next);
  }
  preview_.reset();
  previews_before_.clear();
  change.operation.revision = ++history_.revision;
  history_.log.push_back(std::move(change.operation));
  // Undo and redo only move states between the two stacks: trimming then would forget states
  // a user is stepping through.
  if (kind != Operation::Kind::Undo && kind != Operation::Kind::Redo)
    trimHistory();
  return success();
}

bool Session::setPreview(Change change)
{
  if (change.base_revision != history_.revision || !change.next)
    return false;
  // The two turn previews before this one on the same drag are kept: the next preview starts
  // where the parabola through them leads (rotate.h, TurnStart::before).
  const RotateRequest& turn = change.operation.rotate;
  const bool same_turn = preview_ && preview_kind_ == Operation::Kind::Rotate &&
                         change.operation.kind == Operation::Kind::Rotate && preview_held_ == held_ &&
                         preview_rotate_.face == turn.face && preview_rotate_.axis_edge == turn.axis_edge &&
                         preview_rotate_.carry_stack == turn.carry_stack;
  if (!same_turn)
    previews_before_.clear();
  else
  {
    previews_before_.emplace_back(std::move(*preview_), preview_rotate_.angle);
    if (previews_before_.size() > 2)
      previews_before_.erase(previews_before_.begin());
  }
  preview_ = std::move(change.next);
  preview_kind_ = change.operation.kind;
  preview_rotate_ = change.operation.rotate;
  preview_held_ = held_;
  return true;
}

void Session::setHistoryLimit(size_t bytes)
{
  history_limit_ = bytes;
  trimHistory();
}

void Session::trimHistory()
{
  // Redo states are the newest undone ones: the oldest undo states go first.
  size_t drop = 0;
  while (history_limit_ > 0 && drop < history_.undo.size() && history_bytes_ > history_limit_)
    history_bytes_ -= approximateBytes(history_.undo[drop++]);
  if (drop == 0)
    return;
  history_.undo.erase(history_.undo.begin(), history_.undo.begin() + static_cast<std::ptrdiff_t>(drop));
  forgotten_ += drop;
}

Expected<CreaseResult> Session::crease(const CreaseRequest& request)
{
  auto computed = computeCrease(workspace(), request);
  if (!computed)
    return Expected<CreaseResult>::failure(computed.message());
  commit(std::move(computed->change));
  return std::move(computed->result);
}

Expected<RotateResult> Session::rotate(const RotateRequest& request, bool commit_it, const std::vector<Vec3>* recorded)
{
  auto computed = computeRotate(workspace(), request, !commit_it, commit_it ? recorded : nullptr);
  if (!computed)
    return Expected<RotateResult>::failure(computed.message());
  if (commit_it)
    commit(std::move(computed->change));
  else
    setPreview(std::move(computed->change));
  return std::move(computed->result);
}

Expected<SquashResult> Session::squash()
{
  auto computed = computeSquash(workspace());
  if (!computed)
    return Expected<SquashResult>::failure(computed.message());
  commit(std::move(computed->change));
  return std::move(computed->result);
}

Status Session::undo()
{
  const Expected<Change> change = prepareUndo();
  return change ? commit(*change) : failure(change.message());
}

Status Session::redo()
{
  const Expected<Change> change = prepareRedo();
  return change ? commit(*change) : failure(change.message());
}

Status Session::reset(double size)
{
  Expected<Change> change = computeReset(history_.revision, size);
  return change ? commit(std::move(*change)) : failure(change.message());
}

Status Session::load(Paper paper, const std::string& path)
{
  Expected<Change> change = computeLoad(history_.revision, std::move(paper), path);
  return change ? commit(std::move(*change)) : failure(change.message());
}

Expected<PullResult> Session::pull(const std::vector<PullTarget>& targets)
{
  auto computed = computePull(workspace(), targets);
  if (!computed)
    return Expected<PullResult>::failure(computed.message());
  commit(std::move(computed->change));
  return std::move(computed->result);
}

Expected<AssignmentFoldResult> Session::foldByAssignment(double fraction, bool commit_it,
                                                         const AssignmentFoldAcceptance& acceptance,
                                                         const std::vector<Vec3>* recorded)
{
  auto computed = computeFoldByAssignment(workspace(), fraction, commit_it, acceptance, nullptr, recorded);
  if (!computed)
    return Expected<AssignmentFoldResult>::failure(computed.message());
  if (commit_it)
    commit(std::move(computed->change));
  else
    setPreview(std::move(computed->change));
  return std::move(computed->result);
}

Expected<FlatFoldResult> Session::flatFold(const FlatFoldRequest& request, bool commit_it, double fraction)
{
  auto computed = commit_it ? computeFlatFold(workspace(), request) : computeFlatFoldPreview(workspace(), request, fraction);
  if (!computed)
    return Expected<FlatFoldResult>::failure(computed.message());
  if (commit_it)
    commit(std::move(computed->change));
  else
    setPreview(std::move(computed->change));
  return std::move(computed->result);
}

Expected<PullResult> Session::dragVertex(const PullTarget& target, bool commit_it)
{
  auto computed = computeDragVertex(workspace(), target);
  if (!computed)
    return Expected<PullResult>::failure(computed.message());
  if (commit_it)
    commit(std::move(computed->change));
  else
    setPreview(std::move(computed->change));
  return std::move(computed->result);
}

Expected<KeptBend> Session::keepBend(const BentSheet& sheet)
{
  auto computed = computeKeepBend(workspace(), sheet);
  if (!computed)
    return Expected<KeptBend>::failure(computed.message());
  commit(std::move(computed->change));
  return std::move(computed->result);
}

Status Session::apply(const Operation& operation)
{
  switch (operation.kind)
  {
    case Operation::Kind::Crease:
    {
      const auto r = crease(operation.crease);
      return r ? success() : failure(r.message());
    }
    case Operation::Kind::Rotate:
    {
      const auto r = rotate(operation.rotate, true, operation.folded.empty() ? nullptr : &operation.folded);
      return r ? success() : failure(r.message());
    }
    case Operation::Kind::Squash:
    {
      const auto r = squash();
      return r ? success() : failure(r.message());
    }
    case Operation::Kind::Undo:
      return undo();
    case Operation::Kind::Redo:
      return redo();
    case Operation::Kind::Reset:
      return reset(operation.size);
    case Operation::Kind::Load:
      return failure("a load is replayed by loading the file itself");
    case Operation::Kind::Pull:
    {
      const auto r = pull(operation.pull);
      return r ? success() : failure(r.message());
    }
    case Operation::Kind::AssignmentFold:
    {
      // A recorded fold was accepted when it was made (or kept on purpose): its replay keeps it.
      AssignmentFoldAcceptance recorded;
      recorded.keep = true;
      const auto r = foldByAssignment(operation.fraction, true, recorded,
                                      operation.folded.empty() ? nullptr : &operation.folded);
      return r ? success() : failure(r.message());
    }
    case Operation::Kind::FlatFold:
    {
      const auto r = flatFold(operation.flat_fold, true);
      return r ? success() : failure(r.message());
    }
    case Operation::Kind::DragVertex:
    {
      const auto r = dragVertex(operation.drag, true);
      return r ? success() : failure(r.message());
    }
    case Operation::Kind::KeepBend:
    {
      const auto r = keepBend(operation.bend);
      return r ? success() : failure(r.message());
    }
  }
  return failure("unknown operation");
}

}  // namespace virtual_origami::core

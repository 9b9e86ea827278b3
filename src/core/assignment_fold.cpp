#include "virtual_origami/core/assignment_fold.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <optional>

#include "virtual_origami/core/compliant_faces.h"
#include "virtual_origami/core/face_crossings.h"
#include "virtual_origami/core/face_springs.h"
#include "virtual_origami/core/fold_fraction.h"
#include "virtual_origami/core/layer_order.h"
#include "virtual_origami/core/positions.h"

namespace virtual_origami::core
{
namespace
{
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
}

std::vector<double> creaseTargets(const Paper& paper)
{
  std::vector<double> targets(paper.edges.size(), kNaN);
  for (size_t e = 0; e < paper.edges.size(); ++e)
  {
    const Edge& edge = paper.edges[e];
    if (!edge.isCrease() || edge.split)
      continue;
    if (edge.target_angle && std::isfinite(*edge.target_angle) &&
        (edge.assignment == Assignment::Mountain || edge.assignment == Assignment::Valley ||
         edge.assignment == Assignment::Flat))
    {
      targets[e] = *edge.target_angle;
      continue;
    }
    switch (edge.assignment)
    {
      case Assignment::Valley:
        targets[e] = M_PI;
        break;
      case Assignment::Mountain:
        targets[e] = -M_PI;
        break;
      case Assignment::Flat:
        targets[e] = 0.0;
        break;
      default:
        break;
    }
  }
  return targets;
}

std::vector<double> faceStrains(const Paper& paper)
{
  std::vector<double> strain(paper.faces.size(), 0.0);
  for (size_t f = 0; f < paper.faces.size(); ++f)
  {
    const std::vector<int>& vs = paper.faces[f].vertices;
    for (size_t i = 0; i < vs.size(); ++i)
      for (size_t j = i + 1; j < vs.size(); ++j)
      {
        const double rest = (paper.vertices[vs[i]].crease_pattern - paper.vertices[vs[j]].crease_pattern).norm();
        const double now = (paper.vertices[vs[i]].folded - paper.vertices[vs[j]].folded).norm();
        const double s = rest > 0 ? std::abs(now / rest - 1.0) : 0.0;
        strain[f] = std::isfinite(s) ? std::max(strain[f], s) : std::numeric_limits<double>::infinity();
      }
  }
  return strain;
}

namespace
{
/// Fold angles from the positions, each on the branch nearest its last value. Every crease
/// keeps its assignment: a driven one the one it is driven by (a flat crease that bends a little
/// on the way stays flat), a free hinge stays unassigned, so the next fold leaves it free too
/// (after any other operation a free crease takes the sign it folded to).
void measureAngles(Paper& paper)
{
  std::vector<Assignment> kept;
  for (const Edge& e : paper.edges)
    kept.push_back(e.assignment);
  updateFoldAngles(paper);
  for (size_t e = 0; e < paper.edges.size(); ++e)
    paper.edges[e].assignment = kept[e];
}

int againstTarget(const Paper& paper, const std::vector<double>& goal)
{
  int count = 0;
  for (size_t e = 0; e < goal.size(); ++e)
    if (std::isfinite(goal[e]) && goal[e] != 0.0 &&
        paper.edges[e].fold_angle * (goal[e] > 0 ? 1.0 : -1.0) < -kAgainstTargetAngle)
      ++count;
  return count;
}

void countStuck(const Paper& before, const Paper& after, const std::vector<double>& goal, AssignmentFoldResult& result)
{
  for (size_t e = 0; e < goal.size(); ++e)
  {
    if (!std::isfinite(goal[e]))
      continue;
    const double asked = std::abs(goal[e] - before.edges[e].fold_angle);
    if (asked <= 0.05)
      continue;
    ++result.asked_to_turn;
    const double turned = std::abs(after.edges[e].fold_angle - before.edges[e].fold_angle);
    result.stuck += turned < 0.01 * asked ? 1 : 0;
  }
}

double angleError(const Paper& paper, const std::vector<double>& goal)
{
  double sum = 0.0;
  int count = 0;
  for (size_t e = 0; e < goal.size(); ++e)
    if (std::isfinite(goal[e]))
    {
      sum += std::pow(paper.edges[e].fold_angle - goal[e], 2);
      ++count;
    }
  return count ? std::sqrt(sum / count) : 0.0;
}

double largest(const std::vector<double>& values)
{
  return values.empty() ? 0.0 : *std::max_element(values.begin(), values.end());
}

double largestMove(const Paper& a, const Paper& b)
{
  double move = 0.0;
  for (size_t v = 0; v < a.vertices.size(); ++v)
    move = std::max(move, (a.vertices[v].folded - b.vertices[v].folded).norm());
  return move;
}

void addStage(SolveReport& total, const SolveReport& stage)
{
  const int iterations = total.iterations + stage.iterations;
  const double seconds = total.seconds + stage.seconds;
  total = stage;
  total.iterations = iterations;
  total.seconds = seconds;
}

/// Iterations of the driver's first run towards a balance and of each later run. Nearly every
/// stage of Origami Simulator's library balances within the first run, which is then the
/// driver's whole call as before (with first runs of 50, restarting the few stages that take
/// 50–100 iterations changed their path: a Rotating Star's 100 % 1.3 -> 3.1 s).
constexpr int kFirstRun = 100;
constexpr int kLaterRun = 20;

/// A driver's frames set aside for a commit made in it, and put back after it however it ends.
class FramesAside
{
public:
  explicit FramesAside(CreaseDriver& driver) : driver_(driver) { driver_.setFramesAside(); }
  ~FramesAside() { driver_.putFramesBack(); }
  FramesAside(const FramesAside&) = delete;
  FramesAside& operator=(const FramesAside&) = delete;

private:
  CreaseDriver& driver_;
};

/// The driver run towards a balance within its own limits (their iterations and seconds count
/// over all its runs): a first run of kFirstRun iterations, then runs of kLaterRun, stopped once a
/// run moves no vertex further than `settled_move` of the sheet (AssignmentFoldRequest; 0: one
/// call, to the driver's own tolerance or limit). Near a singular balance (layers folding onto
/// each other) the driver's own tolerance (a step of 1e-9) is reached only linearly, or not at
/// all: a traditional crane's last stage crept on to the 2,000-iteration limit (4 s on 60
/// vertices), moving 1e-5 and then 1e-6 of the sheet per hundred iterations and no crease by
/// 1e-4 rad. A run that stops short of its limit without a balance (no step lowers the energy)
/// ends it.
SolveReport driveToBalance(CreaseDriver& driver, Paper& work, const std::vector<double>& goal,
                           const std::vector<char>& fixed, double settled_move)
{
  if (!(settled_move > 0))
    return driver.drive(work, goal, fixed);
  const SolveLimits limits = driver.limits();
  SolveReport total;
  while (true)
  {
    SolveLimits run = limits;
    run.max_iterations =
        std::min(total.iterations == 0 ? kFirstRun : kLaterRun, limits.max_iterations - total.iterations);
    if (limits.max_seconds > 0)
      run.max_seconds = limits.max_seconds - total.seconds;
    if (run.max_iterations <= 0 || (limits.max_seconds > 0 && run.max_seconds <= 0))
      break;
    driver.setLimits(run);
    const Positions before = foldedPositions(work);
    const SolveReport report = driver.drive(work, goal, fixed);
    addStage(total, report);
    if (report.converged || report.diverged || report.iterations < run.max_iterations)
      break;
    double moved = 0.0;
    for (size_t v = 0; v < work.vertices.size(); ++v)
      moved = std::max(moved, (work.vertices[v].folded - before.col(static_cast<Eigen::Index>(v))).norm());
    if (moved <= settled_move * work.scale())
    {
      total.converged = true;
      total.message = "settled: " + std::to_string(report.iterations) + " iterations moved no vertex further than " +
                      std::to_string(settled_move) + " of the sheet";
      break;
    }
  }
  driver.setLimits(limits);
  return total;
}

/// The rigid solver closing a balance's faces, stopped where its energy stops falling far from
/// any rigid state (SolveLimits::stall_window: less than 1 % over 30 iterations). On Origami
/// Simulator's library the closures of strained balances (FTpoly7, the huffman boxes and weave,
/// Mooser's train) ended on an energy constant to the last digit and spent the solver's 200
/// iterations there, 1–4 s a call. The only closures seen to stall so and still converge (the
/// 6-point hypar's, after 67 and 99 iterations) drifted 0.7 % of the sheet, 80 times what
/// closeRigidly takes, and were not taken; a tenfold bound would also have stopped a hex/tri
/// tessellation's closure that converged after 161 iterations and was taken.
SolveReport solveClosure(ShapeSolver& rigid, Paper& paper, const std::vector<char>& fixed)
{
  const SolveLimits given = rigid.limits();
  SolveLimits limits = given;
  limits.stall_window = 30;
  rigid.setLimits(limits);
  const SolveReport report = rigid.solve(paper, fixed);
  rigid.setLimits(given);
  return report;
}

/// A balance stiffened twice a hundredfold: whether it converges to a rigid state (the second
/// move a tenth of the first or less), and then that stiffest balance closed by `rigid`, where
/// closing moves no vertex further than the last stiffening did.
bool closeByStiffening(Paper& closed, const Paper& work, const std::vector<double>& goal,
                       const std::vector<char>& fixed, const CreaseDriver& driver, ShapeSolver& rigid)
{
  // A balance near a rigid state stiffens in a few steps (3–4 for a 6 × 6 Miura-ori); one far
  // from any may crawl, and is not worth a long wait to refuse.
  const std::unique_ptr<CreaseDriver> stiff = driver.clone();
  SolveLimits limits = driver.limits();
  limits.max_iterations = std::min(limits.max_iterations, 100);
  stiff->setLimits(limits);
  Paper stiffer = work;
  double moves[2] = { 0.0, 0.0 };
  for (int k = 0; k < 2; ++k)
  {
    stiff->setFaceStiffness(driver.faceStiffness() * (k == 0 ? 1e2 : 1e4));
    const Paper before = stiffer;
    const SolveReport s = stiff->drive(stiffer, goal, fixed);
    if (!s.converged || s.diverged)
      return false;
    moves[k] = largestMove(stiffer, before);
  }
  if (moves[1] > 0.1 * moves[0])
    return false;
  closed = stiffer;
  const SolveReport again = solveClosure(rigid, closed, fixed);
  return again.converged && !again.diverged && largestMove(closed, stiffer) <= moves[1] + 1e-12;
}

/// Closes `work`'s faces exactly where a rigid shape lies within the strain's reach: one that no
/// vertex leaves by more than ten times the strain, or one that folds as close to the targets
/// (its angles' RMS error within ten times the strain of the balance's). The second admits the
/// rigid solver's free drift along a mechanism: closing a 10,000-vertex Miura-ori at strain 8e-5
/// moves vertices 9e-4 of the sheet, turns no crease by more than 0.45°, and leaves the RMS error
/// at 0.3204 rad against the balance's 0.3203.
///
/// Near a singular state (a Miura-ori 99 % folded, its layers almost on each other) a strain lets
/// vertices lie much further than itself from any rigid state (a 6 × 6 one: closing its balance
/// moves them 26 times its strain, and the creases 4e-3 rad off the closed form). There a rigid
/// state within reach is the one the balance converges to as the faces stiffen: a balance
/// converging to a rigid state moves a hundredth as far the second time (its strain falls as
/// 1/K), that Miura-ori a sixteenth; one that folds only through strained faces (a square twist
/// at 50 %) a fifth to a quarter, creeping towards a distant rigid state.
///
/// `stiffen` false: the rigid solver's closure alone (a shortcut's test, where a failure costs
/// the two stiffened balances of up to 100 iterations each for nothing).
bool closeRigidly(Paper& work, double scale, const std::vector<double>& goal, const std::vector<char>& fixed,
                  const CreaseDriver& driver, ShapeSolver& rigid, bool stiffen = true)
{
  const double strain = largest(faceStrains(work));
  Paper closed = work;
  const SolveReport report = solveClosure(rigid, closed, fixed);
  bool taken = false;
  if (report.converged && !report.diverged)
  {
    measureAngles(closed);
    const bool near = largestMove(closed, work) <= 10.0 * strain * scale + 1e-12;
    const bool as_close = angleError(closed, goal) <= angleError(work, goal) + 10.0 * strain;
    taken = near || as_close;
  }
  if (!taken && stiffen && strain > 0.0 && closeByStiffening(closed, work, goal, fixed, driver, rigid))
  {
    measureAngles(closed);
    taken = true;
  }
  if (taken)
    work = std::move(closed);
  return taken;
}

/// In a paper of several pieces, every vertex of the first face of each piece, held where it is:
/// each piece then has its place (the driver removes one rigid motion, the whole paper's, and a
/// piece no crease joins to the others would drift with nothing to hold it). None for one piece.
std::vector<int> pieceAnchors(const Paper& paper)
{
  std::vector<int> parent(paper.vertices.size());
  for (size_t v = 0; v < parent.size(); ++v)
    parent[v] = static_cast<int>(v);
  const std::function<int(int)> root = [&](int v) { return parent[v] == v ? v : parent[v] = root(parent[v]); };
  for (const Face& f : paper.faces)
    for (int v : f.vertices)
      parent[root(v)] = root(f.vertices[0]);
  std::vector<char> anchored(paper.vertices.size(), 0);
  std::vector<int> anchors;
  int pieces = 0;
  for (const Face& f : paper.faces)
  {
    const int piece = root(f.vertices[0]);
    if (anchored[piece])
      continue;
    anchored[piece] = 1;
    ++pieces;
    anchors.insert(anchors.end(), f.vertices.begin(), f.vertices.end());
  }
  return pieces > 1 ? anchors : std::vector<int>{};
}

/// Faces the commit left lying flat on each other get the order their creases allow, like every
/// flat fold's; where none exists the result says why (the layers would pass through each other).
void recordLayerOrder(Paper& work, AssignmentFoldResult& result)
{
  // A balance closed to a strain of 1e-10 places layers meeting at a flat-folded vertex only to
  // about its square root (the closure is singular flat): a simple vertex's two stacked creases
  // lay 1e-6 of the sheet apart, which at 1e-7 read as one crossing the other's face.
  LayerOrderOptions options;
  options.tolerance = 1e-5 * work.scale();
  // Faces joined by an unfolded crease are one sheet no layer passes through, as flatFold holds
  // them: on Origami Simulator's library no flat result changes (the same pairs ordered, the same
  // patterns refused), and a result passing a layer through such a sheet is refused.
  options.unfolded_sheets = true;
  // Stacks bounded by their overlapping pairs rather than their faces: the flat tessellations and
  // pop-ups of Origami Simulator's library stack 260–800 faces, sparsely (at most 16,049 pairs,
  // 0.36 s), and were answered without their layer order at 250 faces.
  options.max_faces = 1000;
  options.max_pairs = 20000;
  const Expected<LayerOrder> order = solveLayerOrder(work, options);
  if (!order)
  {
    result.layer_problem = order.message();
    work.face_orders.clear();
    return;
  }
  if (order->complete)
    work.face_orders = order->orders;
  else
    result.layers_unordered = order->incomplete;
  result.ordered_pairs = order->complete ? order->stacked_pairs : 0;
}
}  // namespace

namespace
{
Expected<AssignmentFoldResult> foldOnce(Paper& paper, const AssignmentFoldRequest& request, CreaseDriver& driver,
                                        ShapeSolver* rigid, const std::vector<int>& held)
{
  using Failure = Expected<AssignmentFoldResult>;
  if (!std::isfinite(request.fraction) || request.fraction < -1.0 || request.fraction > 1.0)
    return Failure::failure("the fold fraction must be a number from -1 to 1 (-100 % to 100 %)");
  if (!(request.max_stage_angle > 0.0))
    return Failure::failure("the stage angle must be positive");
  {
    const std::vector<double> targets = creaseTargets(paper);
    if (std::none_of(targets.begin(), targets.end(), [](double t) { return std::isfinite(t); }))
      return Failure::failure("no crease has a mountain, valley or flat assignment to fold by");
  }
  std::vector<char> fixed(paper.vertices.size(), 0);
  for (int v : held)
  {
    if (v < 0 || static_cast<size_t>(v) >= fixed.size())
      return Failure::failure("held vertex " + std::to_string(v) + " is not on the paper");
    fixed[v] = 1;
  }
  // A preview frame works on the paper itself (a copy of a 10,000-vertex paper is a tenth of a
  // frame's budget) and puts its positions back where the driver fails; a commit on a copy.
  Paper copy;
  if (request.converge || request.result)
    copy = paper;
  Paper& work = request.converge || request.result ? copy : paper;
  AssignmentFoldResult result;
  result.fraction = request.fraction;
  // Faces that rigid faces would lock bend instead (cut into triangles once, then kept so).
  if (makeLockedFacesCompliant(work).bodies > 0 ||
      std::any_of(work.edges.begin(), work.edges.end(), [](const Edge& e) { return isFacet(e); }))
    result.compliant_faces = compliantFaceCount(work);
  const std::vector<double> targets = creaseTargets(work);
  for (int v : pieceAnchors(paper))
    fixed[v] = 1;
  std::vector<double> goal(targets.size(), kNaN);
  for (size_t e = 0; e < targets.size(); ++e)
    if (std::isfinite(targets[e]))
      goal[e] = request.fraction * targets[e];

  bool direct = false;  // a commit from a preview frame driven and closed in one stage
  if (request.result)
  {
    const Positions& given = *request.result;
    if (given.cols() != static_cast<Eigen::Index>(paper.vertices.size()))
      return Failure::failure("a recorded fold gives " + std::to_string(given.cols()) + " positions for a paper of " +
                              std::to_string(paper.vertices.size()) + " vertices: it was made on another paper");
    if (!given.allFinite())
      return Failure::failure("a recorded fold gives a position that is not a number");
    for (size_t v = 0; v < fixed.size(); ++v)
      if (fixed[v] &&
          (given.col(static_cast<Eigen::Index>(v)) - paper.vertices[v].folded).norm() > 1e-9 * paper.scale())
        return Failure::failure("a recorded fold moves vertex " + std::to_string(v) + ", which is held here");
    setFoldedPositions(work, given);
    result.solve.converged = true;
  }
  else if (!request.converge)
  {
    const Positions before = foldedPositions(paper);
    result.solve = driver.drive(work, goal, fixed);
    if (result.solve.diverged)
      setFoldedPositions(paper, before);
  }
  else
  {
    // Stages in the fraction, from the one the creases fit now (foldFraction), so that one call
    // follows the branch that a slow slide would (and a replay lands where the slide did). Not
    // from each crease's own angle: a pattern that cannot meet its targets (a Miura-ori's
    // straight and zigzag creases differ) misses some by far at any fraction.
    const double from = foldFraction(work);
    double largest_target = 0.0;
    for (double t : targets)
      if (std::isfinite(t))
        largest_target = std::max(largest_target, std::abs(t));
    const double furthest = std::abs(request.fraction - from) * largest_target;
    const int stages = std::max(1, static_cast<int>(std::ceil(furthest / request.max_stage_angle - 1e-9)));
    // A commit runs on fresh clones of the driver, or in it with its frames set aside
    // (in_driver): what it makes depends on the paper and the fraction alone, not on what
    // previews left in the driver (a kept factorisation, the last frames). One stage (a slide's
    // step) stays near a balanced state: no detour through softer faces needed there.
    std::optional<FramesAside> aside;
    if (request.in_driver)
      aside.emplace(driver);
    const std::unique_ptr<CreaseDriver> clone = request.in_driver ? nullptr : driver.clone();
    CreaseDriver& fresh = clone ? *clone : driver;
    // Faces that bend give the fold its way already; through soft faces as well, a curved pleat
    // crept for 20 s (2,300 iterations, 50 to 100 %) where stiff ones take 1.5 s to the same end.
    const bool soft_path = stages > 1 && request.path_stiffness > 0 &&
                           request.path_stiffness < driver.faceStiffness() && result.compliant_faces == 0;
    std::unique_ptr<CreaseDriver> soft = soft_path ? driver.clone() : nullptr;
    if (soft)
      soft->setFaceStiffness(request.path_stiffness);
    CreaseDriver& path = soft ? *soft : fresh;
    // A commit going on from a preview frame (request.committed) starts on the branch the user
    // saw: the goal is driven in one stage with the driver's own faces first, and taken where
    // the rigid solver alone closes that balance (a rigid state within reach: no path through
    // soft faces leads to a better one) with no crease against its target and most creases
    // asked to turn turned; staged from the frame otherwise (a square twist, which folds only
    // through strained faces). Staged through soft faces, the release at 100 % of a
    // 10,000-vertex Miura-ori after a slide of one-iteration frames (the last fitting 70 %) took
    // six stages and 4.4 s of the driver, where one stage takes 0.9 s (both then rigid, at the
    // targets to 2e-10 rad).
    if (request.committed && stages > 1 && rigid)
    {
      // A hundred iterations at most: one stage that crawls is no shortcut.
      const std::unique_ptr<CreaseDriver> once_clone = request.in_driver ? nullptr : driver.clone();
      CreaseDriver& once = once_clone ? *once_clone : driver;
      const SolveLimits given = once.limits();
      SolveLimits limits = given;
      limits.max_iterations = std::min(limits.max_iterations, kFirstRun);
      once.setLimits(limits);
      Paper tried = work;
      const SolveReport report = driveToBalance(once, tried, goal, fixed, request.settled_move);
      once.setLimits(given);
      if (request.in_driver)
        driver.setFramesAside();  // the stages from the frame start as a fresh clone's would
      measureAngles(tried);
      AssignmentFoldResult turned;
      countStuck(*request.committed, tried, goal, turned);
      direct = report.converged && !report.diverged && againstTarget(tried, goal) == 0 &&
               2 * turned.stuck <= turned.asked_to_turn &&
               closeRigidly(tried, paper.scale(), goal, fixed, driver, *rigid, false);
      addStage(result.solve, report);
      if (direct)
        work = std::move(tried);
      else
        result.solve.diverged = false;  // staged from the frame instead
    }
    std::vector<double> stage_goal = goal;
    for (int k = 1; k <= stages && !direct && !result.solve.diverged; ++k)
    {
      const double fraction = from + (request.fraction - from) * static_cast<double>(k) / stages;
      for (size_t e = 0; e < goal.size(); ++e)
        if (std::isfinite(goal[e]))
          stage_goal[e] = fraction * targets[e];
      addStage(result.solve, driveToBalance(path, work, stage_goal, fixed, request.settled_move));
      measureAngles(work);
    }
    if (soft_path && !direct)
    {
      if (!result.solve.diverged)
      {
        addStage(result.solve, driveToBalance(fresh, work, goal, fixed, request.settled_move));
        measureAngles(work);
      }
    }
  }
  if (result.solve.diverged)
    return Failure::failure(result.solve.message.empty() ? "the crease driver diverged" : result.solve.message);
  measureAngles(work);

  if (request.converge && !request.result && rigid &&
      (direct || closeRigidly(work, paper.scale(), goal, fixed, driver, *rigid)))
    result.rigid = true;
  result.face_strain = faceStrains(work);
  result.max_strain = largest(result.face_strain);
  if (request.result)
    result.rigid = result.max_strain <= kRigidStrain;
  result.angle_error = angleError(work, goal);
  result.against_target = againstTarget(work, goal);
  for (const Edge& e : work.edges)
    if (isFacet(e))
      result.largest_bend = std::max(result.largest_bend, std::abs(e.fold_angle - *e.target_angle));
  if (request.converge || request.result)
  {
    countStuck(request.committed ? *request.committed : paper, work, goal, result);
    result.crossings = static_cast<int>(findFaceCrossings(work).size());
    recordLayerOrder(work, result);
    paper = std::move(copy);
  }
  return result;
}

/// The faces beside the driven creases a commit left stuck (asked to turn, turned less than a
/// hundredth of the way), as countStuck counts them.
std::vector<int> facesBesideStuckCreases(const Paper& before, const Paper& after, double fraction)
{
  const std::vector<double> targets = creaseTargets(before);
  std::vector<int> faces;
  for (size_t e = 0; e < targets.size(); ++e)
  {
    if (!std::isfinite(targets[e]))
      continue;
    const double asked = std::abs(fraction * targets[e] - before.edges[e].fold_angle);
    const double turned = std::abs(after.edges[e].fold_angle - before.edges[e].fold_angle);
    if (asked > 0.05 && turned < 0.01 * asked)
      faces.insert(faces.end(), before.edges[e].faces.begin(), before.edges[e].faces.end());
  }
  return faces;
}
}  // namespace

namespace
{
/// What a fold by assignment of `paper` works on: its paper (locked faces made compliant), driven
/// targets and held vertices (`held` and one anchor per piece), as foldOnce makes them (the driven
/// set, not the fraction, is what set-ups depend on). Nothing where `held` names a vertex not on
/// the paper (the fold refuses it) or no crease is driven.
struct AssignmentWork
{
  Paper paper;
  std::vector<double> targets;
  std::vector<char> fixed;
};

std::optional<AssignmentWork> assignmentWork(const Paper& paper, const std::vector<int>& held)
{
  AssignmentWork work{ paper, {}, std::vector<char>(paper.vertices.size(), 0) };
  for (int v : held)
  {
    if (v < 0 || static_cast<size_t>(v) >= work.fixed.size())
      return std::nullopt;
    work.fixed[v] = 1;
  }
  makeLockedFacesCompliant(work.paper);
  for (int v : pieceAnchors(paper))
    work.fixed[v] = 1;
  work.targets = creaseTargets(work.paper);
  if (std::none_of(work.targets.begin(), work.targets.end(), [](double t) { return std::isfinite(t); }))
    return std::nullopt;
  return work;
}
}  // namespace

void prepareAssignmentPreviews(const Paper& paper, CreaseDriver& driver, const std::vector<int>& held)
{
  if (std::optional<AssignmentWork> work = assignmentWork(paper, held))
    driver.prepare(work->paper, work->targets, work->fixed);
}

void prepareAssignmentClosure(const Paper& paper, ShapeSolver& rigid, const std::vector<int>& held)
{
  if (std::optional<AssignmentWork> work = assignmentWork(paper, held))
    rigid.prepare(work->paper, work->fixed);
}

Expected<AssignmentFoldResult> foldByAssignment(Paper& paper, const AssignmentFoldRequest& request,
                                                CreaseDriver& driver, ShapeSolver* rigid, const std::vector<int>& held)
{
  if (!request.converge || request.result)
    return foldOnce(paper, request, driver, rigid, held);
  Paper rigid_faces = paper;
  Expected<AssignmentFoldResult> result = foldOnce(rigid_faces, request, driver, rigid, held);
  // Most creases stuck: faces that cannot stay rigid held them (a hypar's trapezoids must twist).
  // Those beside the stuck creases bend, and the commit is made again from the paper as it was;
  // taken where fewer creases stick.
  if (result && 2 * result->stuck > result->asked_to_turn)
  {
    Paper bending = paper;
    const CompliantFaces made =
        makeFacesCompliant(bending, facesBesideStuckCreases(paper, rigid_faces, request.fraction));
    if (made.bodies > 0)
    {
      Expected<AssignmentFoldResult> again = foldOnce(bending, request, driver, rigid, held);
      if (again && again->stuck < result->stuck)
      {
        paper = std::move(bending);
        return again;
      }
    }
  }
  if (result)
    paper = std::move(rigid_faces);
  return result;
}

std::string assignmentFoldProblems(const AssignmentFoldResult& result, const AssignmentFoldAcceptance& acceptance)
{
  if (acceptance.keep)
    return "";
  std::vector<std::string> problems;
  char text[200];
  if (!(result.max_strain <= acceptance.max_strain))
  {
    std::snprintf(text, sizeof text, "the faces would stretch: strain %.3g, over the bound %.3g", result.max_strain,
                  acceptance.max_strain);
    problems.emplace_back(text);
  }
  if (result.against_target > 0)
    problems.push_back(std::to_string(result.against_target) +
                       (result.against_target == 1 ? " crease would fold" : " creases would fold") +
                       " against its assignment (past flat the other way)");
  if (result.crossings > 0)
    problems.push_back(std::to_string(result.crossings) +
                       (result.crossings == 1 ? " pair of faces would cross" : " pairs of faces would cross"));
  if (!result.layer_problem.empty())
    problems.push_back("the flat layers cannot be stacked: " + result.layer_problem);
  // Most creases asked to turn did not: faces that cannot bend held them (never "folded" with the
  // sheet where it was). A few may wait for others on a rigid path (a bird base's, from flat).
  if (result.asked_to_turn > 0 && 2 * result.stuck > result.asked_to_turn)
  {
    std::snprintf(text, sizeof text,
                  "the faces could not follow: %d of %d creases could not turn (angle error %.3g rad)", result.stuck,
                  result.asked_to_turn, result.angle_error);
    problems.emplace_back(text);
  }
  // All the way, every crease is where it was driven: else the fold did not happen as asked.
  if (std::abs(result.fraction) == 1.0 && result.angle_error > kTargetReached)
  {
    std::snprintf(text, sizeof text, "the creases end %.3g rad (RMS) from their targets", result.angle_error);
    problems.emplace_back(text);
  }
  std::string message;
  for (const std::string& p : problems)
    message += (message.empty() ? "" : "; ") + p;
  return message;
}

}  // namespace virtual_origami::core

#include "virtual_origami/core/rotate.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <list>
#include <optional>
#include <utility>
#include <sstream>

#include "virtual_origami/core/axis.h"
#include "virtual_origami/core/face_orders.h"
#include "virtual_origami/core/geometry.h"
#include "virtual_origami/core/validity.h"

namespace virtual_origami::core
{
namespace
{
using Failure = Expected<RotateResult>;

struct Axis
{
  Vec3 origin, direction;  // direction runs from the edge's vertices[0] to vertices[1]
  double distance(const Vec3& p) const { return (p - origin - (p - origin).dot(direction) * direction).norm(); }
};

Axis axisOf(const Paper& paper, int edge)
{
  const Vec3& a = paper.vertices[paper.edges[edge].vertices[0]].folded;
  const Vec3& b = paper.vertices[paper.edges[edge].vertices[1]].folded;
  return { a, (b - a).normalized() };
}

/// Faces reachable from `face` without crossing a crease that lies on the axis line.
std::vector<char> sideOf(const Paper& paper, int face, const Axis& axis, double tolerance)
{
  return walkFaces(paper, face, {}, [&](int e) {
    const Edge& edge = paper.edges[e];
    return axis.distance(paper.vertices[edge.vertices[0]].folded) > tolerance ||
           axis.distance(paper.vertices[edge.vertices[1]].folded) > tolerance;
  });
}

std::vector<char> verticesOf(const Paper& paper, const std::vector<char>& faces)
{
  std::vector<char> used(paper.vertices.size(), 0);
  for (size_t f = 0; f < faces.size(); ++f)
    if (faces[f])
      for (int v : paper.faces[f].vertices)
        used[v] = 1;
  return used;
}

Expected<std::pair<int, int>> resolveFaceAndAxis(const Paper& paper, const RotateRequest& request)
{
  using R = Expected<std::pair<int, int>>;
  const int faces = static_cast<int>(paper.faces.size());
  const int edges = static_cast<int>(paper.edges.size());
  if (!std::isfinite(request.angle))
    return R::failure("the rotation angle is not finite");
  // More than a whole turn places no face anywhere a smaller turn does not, and the solver
  // would follow it in stages without end (an angle of 1e300 did, found by fuzzing).
  if (std::abs(request.angle) > 2 * M_PI + 1e-9)
  {
    std::ostringstream msg;
    msg << "the rotation angle " << request.angle << " rad is more than a whole turn";
    return R::failure(msg.str());
  }
  if ((request.face < 0 || request.axis_edge < 0) && !request.click.allFinite())
    return R::failure("the click point has a non-finite coordinate");
  if (request.face < -1 || request.face >= faces)
    return R::failure("face " + std::to_string(request.face) + " does not exist (the model has " +
                      std::to_string(faces) + ")");
  if (request.axis_edge < -1 || request.axis_edge >= edges)
    return R::failure("edge " + std::to_string(request.axis_edge) + " does not exist (the model has " +
                      std::to_string(edges) + ")");
  int face = request.face;
  if (face < 0)
  {
    face = faceAt(paper, request.click, 0.05 * paper.scale());
    if (face < 0)
      return R::failure("no face under the click point");
  }
  int axis = request.axis_edge;
  if (axis < 0)
  {
    const Expected<int> chosen = automaticAxis(paper, face, request.click);
    if (!chosen)
      return R::failure(chosen.message());
    axis = *chosen;
  }
  if (!paper.edges[axis].isCrease())
    return R::failure("edge " + std::to_string(axis) + " is a boundary edge, not a crease to turn about");
  return std::make_pair(face, axis);
}
}  // namespace

namespace
{
/// True when the faces in `moving` share no vertex off the axis with the rest: they can
/// turn rigidly about it while the rest stays.
bool separable(const Paper& paper, const std::vector<char>& moving, const Axis& axis, double tolerance)
{
  std::vector<char> staying(paper.faces.size(), 0);
  for (size_t f = 0; f < moving.size(); ++f)
    staying[f] = !moving[f];
  const std::vector<char> moving_vertices = verticesOf(paper, moving);
  const std::vector<char> staying_vertices = verticesOf(paper, staying);
  for (size_t v = 0; v < paper.vertices.size(); ++v)
    if (moving_vertices[v] && staying_vertices[v] && axis.distance(paper.vertices[v].folded) > tolerance)
      return false;
  return true;
}

/// The flat stack the pressed face lies in, and the side of the axis it lies on.
struct Stack
{
  Vec3 normal;  // the pressed face's front normal
  Vec3 origin;  // a point of the axis
  Vec3 across;  // in the stack's plane, perpendicular to the axis, towards the pressed face
  double tolerance;

  /// In the stack's plane, on the pressed face's side of the axis.
  bool holds(const Paper& paper, int face) const
  {
    if (std::abs(std::abs(paper.faceNormal(face).dot(normal)) - 1.0) > 1e-9)
      return false;
    for (int v : paper.faces[face].vertices)
      if (std::abs(normal.dot(paper.vertices[v].folded - origin)) > tolerance)
        return false;
    return across.dot(paper.faceCentroid(face) - origin) > tolerance;
  }

  /// Where `other` lies from `face` along `normal` by the recorded layer order: +1, −1, or 0.
  int side(const Paper& paper, int face, int other) const
  {
    const int order = faceOrder(paper, face, other);
    return paper.faceNormal(face).dot(normal) > 0 ? order : -order;
  }
};

Stack stackOf(const Paper& paper, int face, const Axis& axis, double tolerance)
{
  Stack stack;
  stack.normal = paper.faceNormal(face);
  stack.origin = axis.origin;
  stack.across = stack.normal.cross(axis.direction).normalized();
  if (stack.across.dot(paper.faceCentroid(face) - axis.origin) < 0)
    stack.across = -stack.across;
  stack.tolerance = tolerance;
  return stack;
}

/// Adds to `moving` every layer of the stack, on the moving side of the axis, that lies
/// between a moving layer and where the turn takes it (or whose order is unknown), so no
/// layer passes through another; with `components`, each with the faces joined to it on its
/// side of the axis. Faces in `blocked` are never taken. Repeats until nothing is added.
void carryStack(const Paper& paper, const Stack& stack, int swing, const Axis& axis, const std::vector<char>& blocked,
                bool components, std::vector<char>& moving)
{
  const size_t n = paper.faces.size();
  std::vector<char> in_stack(n, 0);
  for (size_t f = 0; f < n; ++f)
    in_stack[f] = stack.holds(paper, static_cast<int>(f));
  for (bool grew = true; grew;)
  {
    grew = false;
    for (size_t h = 0; h < n; ++h)
    {
      if (!moving[h] || !in_stack[h])
        continue;
      for (size_t g = 0; g < n; ++g)
      {
        if (moving[g] || blocked[g] || !in_stack[g] ||
            !facesStacked(paper, static_cast<int>(h), static_cast<int>(g), stack.tolerance))
          continue;
        const int side = stack.side(paper, static_cast<int>(h), static_cast<int>(g));
        if (side != 0 && side != swing)
          continue;  // out of the way of the turn
        if (components)
        {
          const std::vector<char> joined = sideOf(paper, static_cast<int>(g), axis, stack.tolerance);
          for (size_t f = 0; f < n; ++f)
            moving[f] = moving[f] || joined[f];
        }
        moving[g] = 1;
        grew = true;
      }
    }
  }
}

std::vector<int> facesIn(const std::vector<char>& flags)
{
  std::vector<int> faces;
  for (size_t f = 0; f < flags.size(); ++f)
    if (flags[f])
      faces.push_back(static_cast<int>(f));
  return faces;
}

/// Layer order after a rigid turn: faces that now lie flat on a face that stayed are on the
/// side they arrived from (half-way through the turn); orders among faces that moved together
/// or stayed together hold as they were; pairs no longer stacked are dropped.
void updateFaceOrders(Paper& next, const Paper& before, const std::vector<char>& moving, const Axis& axis, double turn,
                      double tolerance)
{
  clearFaceOrdersAcross(next, moving);
  for (size_t m = 0; m < moving.size(); ++m)
  {
    if (!moving[m])
      continue;
    const Vec3 half_way = rotateAbout(before.faceCentroid(static_cast<int>(m)), axis.origin, axis.direction, turn / 2);
    for (size_t s = 0; s < moving.size(); ++s)
    {
      if (moving[s] || !facesStacked(next, static_cast<int>(s), static_cast<int>(m), tolerance))
        continue;
      const double from = next.faceNormal(static_cast<int>(s)).dot(half_way - next.faceCentroid(static_cast<int>(s)));
      if (std::abs(from) > tolerance)
        setFaceOrder(next, static_cast<int>(s), static_cast<int>(m), from > 0 ? 1 : -1);
      else if (const int kept = faceOrder(before, static_cast<int>(s), static_cast<int>(m)))
        // No turn (or one too small to tell a side): the layers stay in the order they had (a
        // preview of a turn by 0 drew a 4-layer quarter fold at 2 heights).
        setFaceOrder(next, static_cast<int>(s), static_cast<int>(m), kept);
    }
  }
  pruneFaceOrders(next, tolerance);
}
}  // namespace

/// A vertex this close to the axis stays put while the faces about it turn: the most a turn
/// can then bend a face by is twice this, within checkValidity's length tolerance. The looser
/// 1e-7 still finds the hinge creases and the stacks; a vertex between the two turns with its
/// faces, and one shared by both sides there makes them inseparable. (Fuzzing found a vertex
/// 1.1e-7 off the axis that stayed, bending a face by 2.2e-7.)
namespace
{
double onAxisTolerance(const Paper& paper)
{
  return 0.5 * ValidityTolerance{}.length * paper.scale();
}
}  // namespace

namespace
{
/// The largest turn one solve is asked to follow. The solver starts from the model with the
/// face already turned and the rest where it was, and settles on the nearest shape: after a
/// large turn that can be another branch of the mechanism (a Miura-ori turned 175° at once
/// ended with creases at ±180° off its closed form by 2π; in 30° steps it stayed exact).
constexpr double kMaxStage = 10 * M_PI / 180;
/// A stage that changes any crease by more than this is retried at half the turn, down to
/// kMinStage: a crease swinging much faster than the turn is where the path nears another
/// branch (a degree-4 vertex near flat moves one crease five times as fast as the others).
constexpr double kMaxCreaseChange = 20 * M_PI / 180;
constexpr double kMinStage = kMaxStage / 64;

double largestCreaseChange(const Paper& before, const Paper& after)
{
  double largest = 0.0;
  for (size_t e = 0; e < before.edges.size(); ++e)
    largest = std::max(largest, std::abs(after.edges[e].fold_angle - before.edges[e].fold_angle));
  return largest;
}

/// Places the vertices the solver moves where the polynomial through solved states of the turn
/// (`earlier`, oldest first, then `current` at `done`) reaches `to`. A rigid mechanism's vertices
/// move near the flat sheet by the square of the turn across it: a line through two states
/// misses by the square of the step (strain ~1e-3 for 2°, ten of Newton's steps at 1,681
/// vertices), a parabola through three by its cube.
void extrapolate(const std::vector<std::pair<const Paper*, double>>& earlier, const Paper& current, double done,
                 double to, const std::vector<char>& fixed, Paper& attempt)
{
  std::vector<const Paper*> states;
  std::vector<double> at;
  for (const auto& [state, turn] : earlier)
  {
    states.push_back(state);
    at.push_back(turn);
  }
  states.push_back(&current);
  at.push_back(done);
  std::vector<double> weight(at.size(), 1.0);  // Lagrange's basis at `to`
  for (size_t i = 0; i < at.size(); ++i)
    for (size_t j = 0; j < at.size(); ++j)
      if (j != i)
        weight[i] *= (to - at[j]) / (at[i] - at[j]);
  for (size_t v = 0; v < attempt.vertices.size(); ++v)
    if (!fixed[v])
    {
      Vec3 p = Vec3::Zero();
      for (size_t i = 0; i < states.size(); ++i)
        p += weight[i] * states[i]->vertices[v].folded;
      attempt.vertices[v].folded = p;
    }
}

/// The unit normal of a model lying flat (every vertex within `tolerance` of one face's plane),
/// or none.
std::optional<Vec3> flatNormal(const Paper& paper, double tolerance)
{
  if (paper.faces.empty() || paper.faces[0].vertices.empty())
    return std::nullopt;
  const Vec3 normal = paper.faceNormal(0);
  if (!normal.allFinite() || normal.norm() < 0.5)
    return std::nullopt;
  const Vec3 origin = paper.vertices[paper.faces[0].vertices[0]].folded;
  for (const Vertex& v : paper.vertices)
    if (std::abs((v.folded - origin).dot(normal)) > tolerance)
      return std::nullopt;
  return normal;
}

/// Places the vertices the solver moves for a turn `to` of a model that lies flat, from one
/// solved state `current` of the same turn at `done`. Turned the other way, a flat model moves
/// as its mirror image across its plane, so across the plane its vertices move by odd powers of
/// the turn and along it by even ones: by the turn and its square near the flat sheet, where the
/// guide's start costs a drag's second preview ten of the driver's steps and a line through the
/// two states misses by the square of the step.
void extrapolateFromFlat(const Paper& model, const Vec3& normal, const Paper& current, double done, double to,
                         const std::vector<char>& fixed, Paper& attempt)
{
  const double ratio = to / done;
  for (size_t v = 0; v < attempt.vertices.size(); ++v)
    if (!fixed[v])
    {
      const Vec3 moved = current.vertices[v].folded - model.vertices[v].folded;
      const Vec3 across = moved.dot(normal) * normal;
      attempt.vertices[v].folded = model.vertices[v].folded + ratio * across + ratio * ratio * (moved - across);
    }
}

/// The solved states before the current one a stage extrapolates from: two (a parabola).
constexpr size_t kEarlierStates = 2;

/// Follows the turn with the solver in stages of at most kMaxStage, each solve started from
/// the shape the one before found, so one call ends where the same turn in small calls does.
/// The stages start from `start`, the model turned `from` of the way (the model itself at 0).
/// `turnedBy(paper, angle)` places the turning faces `angle` of the way. Fails, returning no
/// paper, when a stage does not converge; `report` sums the stages' iterations and time. `earlier`:
/// solved states of the turn before `start` (oldest first, with their part of the turn);
/// `looser` > 0: the stages converge at that strain (ShapeSolver::solveLoosely).
Expected<Paper> solveInStages(const Paper& start, double from, double turn,
                              const std::function<Paper(const Paper&, double)>& turnedBy, ShapeSolver& solver,
                              const std::vector<char>& fixed, SolveReport& report,
                              const std::function<void(const Paper&, double, Paper&)>& guide = {},
                              std::vector<std::pair<const Paper*, double>> earlier = {}, double looser = 0.0)
{
  const double remaining = turn - from;
  // A flat model at no turn among the earlier states: a stage may start on its mirror symmetry.
  const std::optional<Vec3> flat = earlier.size() == 1 && earlier[0].second == 0 ?
                                       flatNormal(*earlier[0].first, 1e-9 * start.scale()) :
                                       std::nullopt;
  const int stages = std::max(1, static_cast<int>(std::ceil(std::abs(remaining) / kMaxStage - 1e-9)));
  Paper current = start;
  std::list<Paper> solved;  // the stages' states before `current`
  double done = from;  // the part of `turn` the stages have followed
  double step = remaining / stages;
  int iterations = 0;
  double seconds = 0.0;
  do  // at least once: a turn by 0 still settles the model
  {
    const bool last = std::abs(turn - done) <= std::abs(step) * (1 + 1e-12);
    const double to = last ? turn : done + step;
    Paper attempt = turnedBy(current, to);
    // A stage that turns nothing starts where the model is; one with two solved states before it
    // starts where their parabola leads (a line misses by the square of the step, worse than the
    // guide: a 30° turn from the flat sheet in 10° stages); else the guide, if any, gives the start.
    bool extrapolated = true;
    if (to != done && earlier.size() >= kEarlierStates)
      extrapolate(earlier, current, done, to, fixed, attempt);
    else if (to != done && done != 0 && earlier.size() == 1 && earlier[0].second == 0 && flat)
      extrapolateFromFlat(*earlier[0].first, *flat, current, done, to, fixed, attempt);
    else
    {
      extrapolated = false;
      if (to != done && guide)
        guide(current, to, attempt);
    }
    // Only a stage started from solved states of the turn balances loosely. The drag's later
    // frames extrapolate from one started otherwise (by the guide): left at the looser strain it
    // lies off the turn along the near-flat sheet's soft modes, the extrapolation multiplies
    // that, and each later preview creeps back in linearly convergent steps (a 10,000-vertex
    // Miura-ori's 1° and 1.5° previews took 3 and 5 of Newton's steps, one each after a first
    // preview balanced to 1e-10; docs/SOLVERS.md "The drag's first preview balanced tight").
    // Still as a frame (solveLoosely at 0): at the solver's own damping floor its steps creep.
    const auto solveStage = [&](bool from_solved_states) {
      const SolveReport r = looser > 0 ? solver.solveLoosely(attempt, fixed, from_solved_states ? looser : 0.0) :
                                         solver.solve(attempt, fixed);
      iterations += r.iterations;
      seconds += r.seconds;
      return r;
    };
    SolveReport stage = solveStage(extrapolated);
    // An extrapolated start the solver does not close within its budget is tried once more from
    // the guide's. How far from a rigid state an extrapolation lands near the flat sheet, and so
    // how many of shape matching's linearly converging steps it takes, turns on the rounding: a
    // 6 × 5 Miura-ori's 30° turn from the flat sheet (its second stage, started on the mirror
    // symmetry) took 807–1,439 of them under different BLAS kernels (docs/RELIABILITY.md).
    if ((stage.diverged || !stage.converged) && extrapolated && to != done && guide)
    {
      attempt = turnedBy(current, to);
      guide(current, to, attempt);
      stage = solveStage(false);
    }
    if (stage.diverged || !stage.converged)
    {
      report = stage;
      report.iterations = iterations;
      report.seconds = seconds;
      return Expected<Paper>::failure(solver.name() + " could not restore the face shapes: " + stage.message +
                                      "; the model is unchanged");
    }
    updateFoldAngles(attempt);
    if (std::abs(to - done) > kMinStage && largestCreaseChange(current, attempt) > kMaxCreaseChange)
    {
      step = (to - done) / 2;
      continue;
    }
    solved.push_back(std::move(current));  // a list: the states `earlier` points to stay put
    earlier.emplace_back(&solved.back(), done);
    if (earlier.size() > kEarlierStates)
      earlier.erase(earlier.begin());
    if (solved.size() > kEarlierStates)
      solved.pop_front();
    current = std::move(attempt);
    report = stage;
    done = to;
    step = std::abs(2 * step) < std::abs(remaining) / stages ? 2 * step : remaining / stages;  // back up after a retry
  } while (done != turn);
  report.iterations = iterations;
  report.seconds = seconds;
  return current;
}
/// The faces a turn of `face` about `axis_edge` by the request angle `angle` turns rigidly, and
/// whether they part from the rest exactly (`rigid`; else the face turns with the layers in its
/// way and a solver moves the rest).
std::vector<char> turning(const Paper& paper, int face, int axis_edge, double angle, bool carry_stack, bool& rigid)
{
  const Edge& hinge = paper.edges[axis_edge];
  const Axis axis = axisOf(paper, axis_edge);
  const double tolerance = 1e-7 * paper.scale();
  const int across = hinge.otherFace(face);
  const size_t face_count = paper.faces.size();
  // Left face turning by +θ about vertices[0]→vertices[1] raises the fold angle by θ.
  const double turn = hinge.faces[0] == face ? angle : -angle;
  const Stack stack = stackOf(paper, face, axis, tolerance);
  // The pressed face's points start moving along turn·(direction × across): the way its
  // layers swing, measured along the stack's normal.
  const int swing = turn * stack.normal.dot(axis.direction.cross(stack.across)) > 0 ? 1 : -1;

  // Rigid when the axis parts the face's side from the rest, carrying the layers in the way.
  std::vector<char> moving = sideOf(paper, face, axis, tolerance);
  rigid = !moving[across];
  if (rigid && carry_stack)
    carryStack(paper, stack, swing, axis, sideOf(paper, across, axis, tolerance), true, moving);
  rigid = rigid && !moving[across] && separable(paper, moving, axis, onAxisTolerance(paper));
  if (!rigid)
  {
    // The face turns alone, with the layers it would pass through; the solver moves the rest.
    moving.assign(face_count, 0);
    moving[face] = 1;
    if (carry_stack)
    {
      std::vector<char> blocked(face_count, 0);
      blocked[across] = 1;
      carryStack(paper, stack, swing, axis, blocked, false, moving);
    }
  }
  return moving;
}
}  // namespace

std::vector<int> turnedFaces(const Paper& paper, int face, int axis_edge, double angle, bool carry_stack)
{
  bool rigid = false;
  return facesIn(turning(paper, face, axis_edge, angle, carry_stack, rigid));
}

std::vector<int> flapOf(const Paper& paper, int face, int axis_edge)
{
  const double tolerance = 1e-7 * paper.scale();
  const Axis axis = axisOf(paper, axis_edge);
  const std::vector<char> moving = sideOf(paper, face, axis, tolerance);
  const Edge& hinge = paper.edges[axis_edge];
  if (moving[hinge.faces[0]] && moving[hinge.faces[1]])
    return {};
  if (!separable(paper, moving, axis, onAxisTolerance(paper)))
    return {};  // the two sides share a vertex off the axis: they cannot part rigidly
  return facesIn(moving);
}

Expected<RotateResult> rotate(Paper& paper, const RotateRequest& request, ShapeSolver* solver,
                              const std::vector<int>& held, const TurnGuide& turn_guide, const TurnStart& start,
                              double looser_tolerance)
{
  const auto resolved = resolveFaceAndAxis(paper, request);
  if (!resolved)
    return Failure::failure(resolved.message());
  RotateResult result;
  result.face = resolved->first;
  result.axis_edge = resolved->second;
  const Edge& hinge = paper.edges[result.axis_edge];
  const Axis axis = axisOf(paper, result.axis_edge);
  const double tolerance = 1e-7 * paper.scale();
  const int across = hinge.otherFace(result.face);
  // Left face turning by +θ about vertices[0]→vertices[1] raises the fold angle by θ.
  const double turn = hinge.faces[0] == result.face ? request.angle : -request.angle;
  bool rigid = false;
  const std::vector<char> moving = turning(paper, result.face, result.axis_edge, request.angle, request.carry_stack, rigid);
  result.moved_faces = facesIn(moving);

  // Hinge creases change by the turn exactly; telling updateFoldAngles so keeps ±180° on
  // the side it was folded to.
  std::vector<std::pair<int, double>> hinges;  // edge, change of its fold angle per radian of `turn`
  for (size_t e = 0; e < paper.edges.size(); ++e)
  {
    const Edge& edge = paper.edges[e];
    if (!edge.isCrease() || moving[edge.faces[0]] == moving[edge.faces[1]])
      continue;
    const Vec3 dir = paper.vertices[edge.vertices[1]].folded - paper.vertices[edge.vertices[0]].folded;
    if (axis.distance(paper.vertices[edge.vertices[0]].folded) > tolerance ||
        axis.distance(paper.vertices[edge.vertices[1]].folded) > tolerance)
      continue;
    const double rate = (moving[edge.faces[0]] ? 1.0 : -1.0) * (dir.dot(axis.direction) > 0 ? 1.0 : -1.0);
    const double expected = edge.fold_angle + rate * turn;
    if (std::abs(expected) > M_PI + 1e-9)
    {
      std::ostringstream msg;
      msg << "turning by " << request.angle << " rad would fold edge " << e << " past 180 degrees (to "
          << expected * 180 / M_PI << "); the layers would pass through each other";
      return Failure::failure(msg.str());
    }
    hinges.emplace_back(static_cast<int>(e), rate);
  }
  const std::vector<char> moving_vertices = verticesOf(paper, moving);
  // The model turned by `angle` of the way: every vertex of the turning faces turns, also
  // where a face the solver moves shares it; those on the axis stay exactly where they are.
  const auto turnedBy = [&](Paper turned, double angle) {
    for (size_t v = 0; v < paper.vertices.size(); ++v)
      if (moving_vertices[v] && axis.distance(paper.vertices[v].folded) > onAxisTolerance(paper))
        turned.vertices[v].folded = rotateAbout(paper.vertices[v].folded, axis.origin, axis.direction, angle);
    for (const auto& [e, rate] : hinges)
    {
      turned.edges[e].fold_angle = paper.edges[e].fold_angle + rate * angle;
      turned.edges[e].split = false;  // turned about, an edge splitting a concave face is a crease
    }
    return turned;
  };

  Paper next;
  if (rigid)
  {
    next = turnedBy(paper, turn);
  }
  else
  {
    if (!solver)
      return Failure::failure("turning face " + std::to_string(result.face) + " about edge " +
                              std::to_string(result.axis_edge) +
                              " drags faces held by other creases; a solver is needed and none is selected");
    std::vector<char> fixed = moving_vertices;
    for (int v : paper.faces[across].vertices)
      fixed[v] = 1;
    for (int v : held)
      if (v >= 0 && v < static_cast<int>(fixed.size()))
        fixed[v] = 1;
    result.used_solver = true;
    std::function<void(const Paper&, double, Paper&)> guide;
    if (turn_guide.driver && paper.vertices.size() >= turn_guide.min_vertices)
      guide = [&](const Paper& current, double to, Paper& attempt) {
        std::vector<double> target(paper.edges.size(), std::numeric_limits<double>::quiet_NaN());
        for (const auto& [e, rate] : hinges)
          target[e] = paper.edges[e].fold_angle + rate * to;
        std::vector<char> anchor(paper.vertices.size(), 0);
        for (int v : paper.faces[across].vertices)
          anchor[v] = 1;
        for (int v : held)
          if (v >= 0 && v < static_cast<int>(anchor.size()))
            anchor[v] = 1;
        CreaseDriver& driver = *turn_guide.driver;
        const double stiffness = driver.faceStiffness();
        // A driver kept for turns has the guide's stiffness already (and may be shared).
        if (stiffness != turn_guide.face_stiffness)
          driver.setFaceStiffness(turn_guide.face_stiffness);
        const SolveLimits limits = driver.limits();
        driver.setLimits(SolveLimits{ turn_guide.tolerance, turn_guide.max_iterations, limits.max_seconds });
        Paper guess = current;
        const SolveReport report = driver.drive(guess, target, anchor);
        driver.setLimits(limits);
        if (stiffness != turn_guide.face_stiffness)
          driver.setFaceStiffness(stiffness);
        if (report.diverged)
          return;
        // A start only where it agrees with the turn: the turning faces where it puts them.
        const double agrees = std::max(1e-6, 10 * turn_guide.tolerance) * paper.scale();
        for (size_t v = 0; v < paper.vertices.size(); ++v)
          if (moving_vertices[v] && (guess.vertices[v].folded - attempt.vertices[v].folded).norm() > agrees)
            return;
        for (size_t v = 0; v < paper.vertices.size(); ++v)
          if (!fixed[v])
            attempt.vertices[v].folded = guess.vertices[v].folded;
      };
    // A solved state of this turn on the way (a drag's last preview): the stages go on from it,
    // the first one starting on the parabola through it and the states before it (extrapolate)
    // when there are two, the model itself (no turn) among them.
    const Paper* from_paper = &paper;
    double from = 0.0;
    std::vector<std::pair<const Paper*, double>> earlier;
    const auto sameShape = [&](const Paper* other) {
      return other && other->vertices.size() == paper.vertices.size() && other->edges.size() == paper.edges.size() &&
             other->faces.size() == paper.faces.size();
    };
    if (sameShape(start.paper) && start.face == result.face && start.axis_edge == result.axis_edge)
    {
      const double start_turn = hinge.faces[0] == result.face ? start.angle : -start.angle;
      if (start_turn * turn > 0 && std::abs(turn - start_turn) < std::abs(turn))
      {
        from_paper = start.paper;
        from = start_turn;
        // The model itself is the state at no turn; the previews before, nearer it, lie between.
        earlier.emplace_back(&paper, 0.0);
        for (const auto& [state, angle] : start.before)
        {
          const double before_turn = hinge.faces[0] == result.face ? angle : -angle;
          if (sameShape(state) && before_turn * start_turn > 0 && std::abs(before_turn) < std::abs(start_turn) &&
              std::abs(before_turn) > std::abs(earlier.back().second))
            earlier.emplace_back(state, before_turn);
        }
        while (earlier.size() > kEarlierStates)
          earlier.erase(earlier.begin());
      }
    }
    Expected<Paper> solved =
        solveInStages(*from_paper, from, turn, turnedBy, *solver, fixed, result.solve, guide, std::move(earlier),
                      looser_tolerance);
    if (!solved)
      return Failure::failure(solved.message());
    next = std::move(*solved);
  }
  updateFoldAngles(next);
  updateFaceOrders(next, paper, moving, axis, turn, tolerance);
  paper = std::move(next);
  return result;
}

}  // namespace virtual_origami::core

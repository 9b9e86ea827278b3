#include "virtual_origami/core/rotate.h"

#include <cmath>
#include <deque>
#include <sstream>

#include "virtual_origami/core/axis.h"
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
  std::vector<char> reached(paper.faces.size(), 0);
  std::deque<int> queue{ face };
  reached[face] = 1;
  while (!queue.empty())
  {
    const int f = queue.front();
    queue.pop_front();
    for (int e : paper.faces[f].edges)
    {
      const Edge& edge = paper.edges[e];
      if (!edge.isCrease())
        continue;
      const bool hinge = axis.distance(paper.vertices[edge.vertices[0]].folded) <= tolerance &&
                         axis.distance(paper.vertices[edge.vertices[1]].folded) <= tolerance;
      const int g = edge.otherFace(f);
      if (hinge || reached[g])
        continue;
      reached[g] = 1;
      queue.push_back(g);
    }
  }
  return reached;
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

std::vector<int> flapOf(const Paper& paper, int face, int axis_edge)
{
  const double tolerance = 1e-7 * paper.scale();
  const Axis axis = axisOf(paper, axis_edge);
  const std::vector<char> moving = sideOf(paper, face, axis, tolerance);
  const Edge& hinge = paper.edges[axis_edge];
  if (moving[hinge.faces[0]] && moving[hinge.faces[1]])
    return {};
  std::vector<char> staying(paper.faces.size(), 0);
  for (size_t f = 0; f < moving.size(); ++f)
    staying[f] = !moving[f];
  const std::vector<char> moving_vertices = verticesOf(paper, moving);
  const std::vector<char> staying_vertices = verticesOf(paper, staying);
  for (size_t v = 0; v < paper.vertices.size(); ++v)
    if (moving_vertices[v] && staying_vertices[v] && axis.distance(paper.vertices[v].folded) > tolerance)
      return {};  // the two sides share a vertex off the axis: they cannot part rigidly
  std::vector<int> flap;
  for (size_t f = 0; f < moving.size(); ++f)
    if (moving[f])
      flap.push_back(static_cast<int>(f));
  return flap;
}

Expected<RotateResult> rotate(Paper& paper, const RotateRequest& request, ShapeSolver* solver,
                              const std::vector<int>& held)
{
  const auto resolved = resolveFaceAndAxis(paper, request);
  if (!resolved)
    return Failure::failure(resolved.message());
  RotateResult result;
  result.face = resolved->first;
  result.axis_edge = resolved->second;
  const Edge& hinge = paper.edges[result.axis_edge];
  const Axis axis = axisOf(paper, result.axis_edge);

  result.moved_faces = flapOf(paper, result.face, result.axis_edge);
  std::vector<char> moving(paper.faces.size(), 0);
  for (int f : result.moved_faces)
    moving[f] = 1;
  if (result.moved_faces.empty())
    moving[result.face] = 1;  // the face turns alone; the solver moves the rest
  int side = -1;              // which of the hinge's faces turns
  if (moving[hinge.faces[0]] != moving[hinge.faces[1]])
    side = moving[hinge.faces[0]] ? 0 : 1;
  if (side < 0)
    return Failure::failure("face " + std::to_string(result.face) + " lies on neither side of edge " +
                            std::to_string(result.axis_edge) + "; choose an axis on its side");
  // Left face turning by +θ about vertices[0]→vertices[1] raises the fold angle by θ.
  const double turn = side == 0 ? request.angle : -request.angle;

  Paper next = paper;
  // Hinge creases change by the turn exactly; telling updateFoldAngles so keeps ±180° on
  // the side it was folded to.
  for (size_t e = 0; e < paper.edges.size(); ++e)
  {
    const Edge& edge = paper.edges[e];
    if (!edge.isCrease() || moving[edge.faces[0]] == moving[edge.faces[1]])
      continue;
    const Vec3 dir = paper.vertices[edge.vertices[1]].folded - paper.vertices[edge.vertices[0]].folded;
    if (axis.distance(paper.vertices[edge.vertices[0]].folded) > 1e-7 * paper.scale() ||
        axis.distance(paper.vertices[edge.vertices[1]].folded) > 1e-7 * paper.scale())
      continue;
    const double delta = (moving[edge.faces[0]] ? turn : -turn) * (dir.dot(axis.direction) > 0 ? 1.0 : -1.0);
    const double expected = edge.fold_angle + delta;
    if (std::abs(expected) > M_PI + 1e-9)
    {
      std::ostringstream msg;
      msg << "turning by " << request.angle << " rad would fold edge " << e << " past 180 degrees (to "
          << expected * 180 / M_PI << "); the layers would pass through each other";
      return Failure::failure(msg.str());
    }
    next.edges[e].fold_angle = expected;
  }
  const std::vector<char> moving_vertices = verticesOf(paper, moving);
  // Every vertex of the turning faces turns, also where a face the solver moves shares it;
  // those on the axis stay exactly where they are.
  for (size_t v = 0; v < paper.vertices.size(); ++v)
    if (moving_vertices[v] && axis.distance(paper.vertices[v].folded) > 1e-7 * paper.scale())
      next.vertices[v].folded = rotateAbout(paper.vertices[v].folded, axis.origin, axis.direction, turn);

  if (result.moved_faces.empty())
  {
    if (!solver)
      return Failure::failure("turning face " + std::to_string(result.face) + " about edge " +
                              std::to_string(result.axis_edge) +
                              " drags faces held by other creases; a solver is needed and none is selected");
    std::vector<char> fixed = moving_vertices;
    for (int v : paper.faces[hinge.otherFace(result.face)].vertices)
      fixed[v] = 1;
    for (int v : held)
      if (v >= 0 && v < static_cast<int>(fixed.size()))
        fixed[v] = 1;
    result.used_solver = true;
    result.solve = solver->solve(next, fixed);
    if (result.solve.diverged || !result.solve.converged)
      return Failure::failure(solver->name() + " could not restore the face shapes: " + result.solve.message +
                              "; the model is unchanged");
  }
  updateFoldAngles(next);
  paper = std::move(next);
  return result;
}

}  // namespace virtual_origami::core

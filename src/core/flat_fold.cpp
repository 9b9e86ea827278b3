#include "virtual_origami/core/flat_fold.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "virtual_origami/core/face_orders.h"
#include "virtual_origami/core/kinematics.h"

namespace virtual_origami::core
{
namespace
{
double distanceToSegment(const Vec2& p, const Vec2& a, const Vec2& b)
{
  const Vec2 ab = b - a;
  const double t = std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
  return (p - (a + t * ab)).norm();
}

bool insideFace(const Paper& paper, int face, const Vec2& p)
{
  const std::vector<int>& vs = paper.faces[face].vertices;
  for (size_t i = 0; i < vs.size(); ++i)
  {
    const Vec2& a = paper.vertices[vs[i]].crease_pattern;
    const Vec2& b = paper.vertices[vs[(i + 1) % vs.size()]].crease_pattern;
    const Vec2 ab = b - a, ap = p - a;
    if (ab.x() * ap.y() - ab.y() * ap.x() < -1e-12)
      return false;
  }
  return true;
}
}  // namespace

Expected<FlatFoldResult> flatFold(Paper& paper, const FlatFoldRequest& request)
{
  using Failure = Expected<FlatFoldResult>;
  const double tolerance = 1e-9 * paper.scale();
  std::vector<double> angles(paper.edges.size(), 0.0);
  for (size_t e = 0; e < paper.edges.size(); ++e)
    angles[e] = paper.edges[e].fold_angle;
  FlatFoldResult result;
  for (size_t k = 0; k < request.creases.size(); ++k)
  {
    const CreaseLineAngle& line = request.creases[k];
    const std::string which = "crease line " + std::to_string(k + 1);
    if (!line.start.allFinite() || !line.end.allFinite() || !std::isfinite(line.angle))
      return Failure::failure(which + " has a non-finite value");
    if (std::abs(line.angle) > M_PI + 1e-12)
      return Failure::failure(which + ": a fold angle beyond ±180 degrees would pass the layers through each other");
    if ((line.end - line.start).norm() < tolerance)
      return Failure::failure(which + " has zero length");
    int found = 0;
    for (size_t e = 0; e < paper.edges.size(); ++e)
    {
      const Edge& edge = paper.edges[e];
      if (!edge.isCrease() ||
          distanceToSegment(paper.vertices[edge.vertices[0]].crease_pattern, line.start, line.end) > tolerance ||
          distanceToSegment(paper.vertices[edge.vertices[1]].crease_pattern, line.start, line.end) > tolerance)
        continue;
      ++found;
      if (angles[e] != line.angle)
        result.changed_edges.push_back(static_cast<int>(e));
      angles[e] = line.angle;
    }
    if (found == 0)
      return Failure::failure(which + " runs along no crease (crease it first)");
  }
  int root = -1;
  for (size_t f = 0; f < paper.faces.size() && root < 0; ++f)
    if (insideFace(paper, static_cast<int>(f), request.fixed_point))
      root = static_cast<int>(f);
  if (root < 0)
    return Failure::failure("the fixed point lies off the sheet");
  const Expected<std::vector<Vec3>> placed =
      foldedPositionsFromAngles(paper, angles, root, facePose(paper, root), tolerance);
  if (!placed)
    return Failure::failure("the fold does not close: " + placed.message());

  Paper next = paper;
  for (size_t v = 0; v < next.vertices.size(); ++v)
    next.vertices[v].folded = (*placed)[v];
  std::vector<char> moved(paper.faces.size(), 0);
  for (size_t f = 0; f < paper.faces.size(); ++f)
    for (int v : paper.faces[f].vertices)
      if ((next.vertices[v].folded - paper.vertices[v].folded).norm() > tolerance)
        moved[f] = 1;
  for (size_t f = 0; f < moved.size(); ++f)
    if (moved[f])
      result.moved_faces.push_back(static_cast<int>(f));
  for (size_t e = 0; e < next.edges.size(); ++e)
    next.edges[e].fold_angle = angles[e];  // the branch to measure against
  updateFoldAngles(next);
  clearFaceOrdersAcross(next, moved);
  pruneFaceOrders(next, 1e-7 * paper.scale());
  paper = std::move(next);
  return result;
}

}  // namespace virtual_origami::core

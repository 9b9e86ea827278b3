#include "virtual_origami/core/axis.h"

#include <cmath>
#include <limits>

#include "virtual_origami/core/geometry.h"

namespace virtual_origami::core
{
namespace
{
Status checkFace(const Paper& paper, int face, const Vec3& click)
{
  if (face < 0 || face >= static_cast<int>(paper.faces.size()))
    return failure("face " + std::to_string(face) + " does not exist");
  if (!click.allFinite())
    return failure("the click point has a non-finite coordinate");
  return success();
}

Expected<int> noCrease(int face)
{
  return Expected<int>::failure("face " + std::to_string(face) +
                                " has no crease to turn about: crease it first, or name a crease as the axis");
}

double angleBetween(const Vec3& a, const Vec3& b)
{
  return std::atan2(a.cross(b).norm(), a.dot(b));
}
}  // namespace

Expected<int> automaticAxis(const Paper& paper, int face, const Vec3& click)
{
  const Status ok = checkFace(paper, face, click);
  if (!ok)
    return Expected<int>::failure(ok.message());
  const Vec3 n = paper.faceNormal(face);
  const Vec3 centre = paper.faceCentroid(face);
  const Vec3 p = click - n.dot(click - centre) * n;  // the click on the face's plane
  if ((centre - p).norm() < 1e-9 * paper.scale())
    return farthestCreaseAxis(paper, face, click);  // G is undefined at the centre itself
  const Vec3 away = (centre - p).normalized();      // from the click through the centre
  const Vec3 g = away.cross(n).normalized();
  int best = -1;
  double best_distance = -1;
  // Where G crosses none: the crease nearest in angle, seen from the centre, to `away`.
  int nearest = -1;
  double nearest_angle = std::numeric_limits<double>::infinity();
  for (int e : paper.faces[face].edges)
  {
    const Edge& edge = paper.edges[e];
    if (!edge.isCrease())
      continue;
    const Vec3& a = paper.vertices[edge.vertices[0]].folded;
    const Vec3& b = paper.vertices[edge.vertices[1]].folded;
    const double angle = std::min(angleBetween(away, a - centre), angleBetween(away, b - centre));
    if (angle < nearest_angle - 1e-12)
    {
      nearest_angle = angle;
      nearest = e;
    }
    const double da = g.dot(a - p), db = g.dot(b - p);
    if (da * db > 0)
      continue;  // G does not cross this crease
    const Vec3 x = std::abs(da - db) > 0 ? Vec3(a + (da / (da - db)) * (b - a)) : Vec3(0.5 * (a + b));
    const double d = (x - p).norm();
    if (d > best_distance)
    {
      best_distance = d;
      best = e;
    }
  }
  if (best >= 0)
    return best;
  if (nearest >= 0)
    return nearest;
  return noCrease(face);
}

Expected<int> farthestCreaseAxis(const Paper& paper, int face, const Vec3& click)
{
  const Status ok = checkFace(paper, face, click);
  if (!ok)
    return Expected<int>::failure(ok.message());
  int best = -1;
  double best_distance = -1;
  for (int e : paper.faces[face].edges)
  {
    const Edge& edge = paper.edges[e];
    if (!edge.isCrease())
      continue;
    const double d =
        pointSegmentDistance(click, paper.vertices[edge.vertices[0]].folded, paper.vertices[edge.vertices[1]].folded);
    if (d > best_distance)
    {
      best_distance = d;
      best = e;
    }
  }
  if (best < 0)
    return noCrease(face);
  return best;
}

int creaseNear(const Paper& paper, const Vec3& point, double radius)
{
  if (!point.allFinite())
    return -1;
  int best = -1;
  double best_distance = radius;
  for (size_t e = 0; e < paper.edges.size(); ++e)
  {
    const Edge& edge = paper.edges[e];
    if (!edge.isCrease())
      continue;
    const double d =
        pointSegmentDistance(point, paper.vertices[edge.vertices[0]].folded, paper.vertices[edge.vertices[1]].folded);
    if (d <= best_distance)
    {
      best_distance = d;
      best = static_cast<int>(e);
    }
  }
  return best;
}

}  // namespace virtual_origami::core

#include "virtual_origami/core/axis.h"

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
  const Vec3 g = (centre - p).cross(n).normalized();
  int best = -1;
  double best_distance = -1;
  for (int e : paper.faces[face].edges)
  {
    const Edge& edge = paper.edges[e];
    if (!edge.isCrease())
      continue;
    const Vec3& a = paper.vertices[edge.vertices[0]].folded;
    const Vec3& b = paper.vertices[edge.vertices[1]].folded;
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
  if (best < 0)
    return Expected<int>::failure("face " + std::to_string(face) +
                                  " has no crease on the line through the click and its centre; name the axis");
  return best;
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
    const double d = pointSegmentDistance(click, paper.vertices[edge.vertices[0]].folded,
                                          paper.vertices[edge.vertices[1]].folded);
    if (d > best_distance)
    {
      best_distance = d;
      best = e;
    }
  }
  if (best < 0)
    return Expected<int>::failure("face " + std::to_string(face) + " has no crease to turn about");
  return best;
}

}  // namespace virtual_origami::core

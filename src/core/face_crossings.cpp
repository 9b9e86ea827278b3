#include "virtual_origami/core/face_crossings.h"

#include <CGAL/Bbox_3.h>
#include <CGAL/box_intersection_d.h>

#include <algorithm>
#include <cmath>
#include <optional>

namespace virtual_origami::core
{
namespace
{
using Box = CGAL::Box_intersection_d::Box_with_handle_d<double, 3, const int*,
                                                        CGAL::Box_intersection_d::ID_FROM_HANDLE>;

struct FacePlane
{
  Vec3 normal = Vec3::Zero();  // unit
  double offset = 0.0;         // normal · x on the plane
};

FacePlane planeOf(const Paper& paper, int face)
{
  FacePlane plane;
  plane.normal = paper.faceNormal(face);
  plane.offset = plane.normal.dot(paper.faceCentroid(face));
  return plane;
}

/// The interval (along `direction`, from `origin`) that the plane cuts from a convex face,
/// when the face has vertices strictly on both sides of it; none otherwise (the face only
/// touches the plane, or lies off it).
std::optional<std::pair<double, double>> chord(const Paper& paper, int face, const FacePlane& plane,
                                               const Vec3& origin, const Vec3& direction, double tolerance)
{
  const std::vector<int>& vs = paper.faces[face].vertices;
  bool above = false, below = false;
  for (int v : vs)
  {
    const double d = plane.normal.dot(paper.vertices[v].folded) - plane.offset;
    above = above || d > tolerance;
    below = below || d < -tolerance;
  }
  if (!above || !below)
    return std::nullopt;
  double lo = INFINITY, hi = -INFINITY;
  for (size_t i = 0; i < vs.size(); ++i)
  {
    const Vec3& p = paper.vertices[vs[i]].folded;
    const Vec3& q = paper.vertices[vs[(i + 1) % vs.size()]].folded;
    const double dp = plane.normal.dot(p) - plane.offset;
    const double dq = plane.normal.dot(q) - plane.offset;
    auto take = [&](const Vec3& x) {
      const double t = direction.dot(x - origin);
      lo = std::min(lo, t);
      hi = std::max(hi, t);
    };
    if (std::abs(dp) <= tolerance)
      take(p);
    if ((dp > tolerance && dq < -tolerance) || (dp < -tolerance && dq > tolerance))
      take(p + (q - p) * (dp / (dp - dq)));
  }
  if (!(lo <= hi))
    return std::nullopt;
  return std::make_pair(lo, hi);
}

bool shareEdge(const Paper& paper, int a, int b)
{
  for (int e : paper.faces[a].edges)
    if (paper.edges[e].otherFace(a) == b)
      return true;
  return false;
}

/// Whether faces a and b (their planes pa and pb) cross transversally.
bool cross(const Paper& paper, int a, int b, const FacePlane& pa, const FacePlane& pb, double tolerance)
{
  const Vec3 direction = pa.normal.cross(pb.normal);
  const double sine = direction.norm();
  // Parallel planes (layers on each other, or apart) never cross transversally.
  if (sine < 1e-9)
    return false;
  const Vec3 unit = direction / sine;
  // A point on both planes: the line's closest point to the origin.
  const Vec3 origin = (pa.offset * pb.normal.cross(direction) + pb.offset * direction.cross(pa.normal)) /
                      direction.squaredNorm();
  const auto ca = chord(paper, a, pb, origin, unit, tolerance);
  if (!ca)
    return false;
  const auto cb = chord(paper, b, pa, origin, unit, tolerance);
  if (!cb)
    return false;
  return std::min(ca->second, cb->second) - std::max(ca->first, cb->first) > tolerance;
}
}  // namespace

std::vector<std::pair<int, int>> findFaceCrossings(const Paper& paper, double tolerance)
{
  if (!(tolerance > 0.0))
    tolerance = 1e-6 * paper.scale();
  const int n = static_cast<int>(paper.faces.size());
  std::vector<int> ids(n);
  std::vector<Box> boxes;
  boxes.reserve(n);
  // Each face's plane once: a flat-folded sheet's stacks make millions of candidate pairs, and
  // a 10,000-vertex Miura-ori folded flat took 0.27 s with the planes made for each pair, 0.06 s so.
  std::vector<FacePlane> planes(n);
  for (int f = 0; f < n; ++f)
  {
    ids[f] = f;
    planes[f] = planeOf(paper, f);
    CGAL::Bbox_3 bounds;
    for (int v : paper.faces[f].vertices)
    {
      const Vec3& p = paper.vertices[v].folded;
      bounds += CGAL::Bbox_3(p.x(), p.y(), p.z(), p.x(), p.y(), p.z());
    }
    boxes.emplace_back(bounds, &ids[f]);
  }
  std::vector<std::pair<int, int>> crossings;
  // Boxes that touch are candidates too (closed boxes): a face standing on another.
  CGAL::box_self_intersection_d(
      boxes.begin(), boxes.end(),
      [&](const Box& x, const Box& y) {
        int a = *x.handle(), b = *y.handle();
        if (a > b)
          std::swap(a, b);
        if (!shareEdge(paper, a, b) && cross(paper, a, b, planes[a], planes[b], tolerance))
          crossings.emplace_back(a, b);
      },
      std::ptrdiff_t(10), CGAL::Box_intersection_d::CLOSED);
  std::sort(crossings.begin(), crossings.end());
  return crossings;
}

}  // namespace virtual_origami::core

// Small predicates and measures in the plane (the crease pattern's frame): each has its one home
// here. Inline, as they sit in the inner loops of the meshers and readers.
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include "virtual_origami/core/paper.h"

namespace virtual_origami::core
{
/// The z component of the cross product: twice the signed area of the triangle (0, a, b),
/// positive when b lies counter-clockwise of a.
inline double cross2(const Vec2& a, const Vec2& b)
{
  return a.x() * b.y() - a.y() * b.x();
}

/// Signed area of a polygon, positive when counter-clockwise (shoelace formula).
inline double signedArea(const std::vector<Vec2>& polygon)
{
  double twice = 0;
  for (size_t i = 0; i < polygon.size(); ++i)
    twice += cross2(polygon[i], polygon[(i + 1) % polygon.size()]);
  return 0.5 * twice;
}

/// Signed area of the polygon whose corners are `points[cycle[k]]`.
inline double signedArea(const std::vector<Vec2>& points, const std::vector<int>& cycle)
{
  double twice = 0;
  for (size_t k = 0; k < cycle.size(); ++k)
    twice += cross2(points[cycle[k]], points[cycle[(k + 1) % cycle.size()]]);
  return 0.5 * twice;
}

/// The unsigned angle between two vectors, in [0, π]: atan2 keeps it accurate near 0 and π.
inline double angleBetween(const Vec2& u, const Vec2& v)
{
  return std::atan2(std::abs(cross2(u, v)), u.dot(v));
}

/// Distance from a point to the segment [a, b] (to a itself when the segment has no length).
inline double pointSegmentDistance(const Vec2& point, const Vec2& a, const Vec2& b)
{
  const Vec2 ab = b - a;
  const double length2 = ab.squaredNorm();
  const double t = length2 > 0 ? std::clamp((point - a).dot(ab) / length2, 0.0, 1.0) : 0.0;
  return (a + t * ab - point).norm();
}

/// The least distance between the segments [a, b] and [c, d]: 0 when they cross.
double segmentDistance(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d);

/// Length of the diagonal of the points' bounding box; the points must not be empty.
double boundingDiagonal(const std::vector<Vec2>& points);

/// The points a cycle of indices names, in its order (a face or piece as a polygon).
inline std::vector<Vec2> cornersOf(const std::vector<Vec2>& points, const std::vector<int>& cycle)
{
  std::vector<Vec2> corners;
  corners.reserve(cycle.size());
  for (int v : cycle)
    corners.push_back(points[v]);
  return corners;
}

}  // namespace virtual_origami::core

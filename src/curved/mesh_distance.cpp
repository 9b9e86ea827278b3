#include "virtual_origami/curved/mesh_distance.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace virtual_origami::core
{
Vec3 nearestOnTriangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c)
{
  // By the region of the triangle's plane p projects into (Ericson, Real-Time Collision
  // Detection, 5.1.5).
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0)
    return Vec3(1, 0, 0);
  const Vec3 bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3)
    return Vec3(0, 1, 0);
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0)
  {
    const double v = d1 / (d1 - d3);
    return Vec3(1 - v, v, 0);
  }
  const Vec3 cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6)
    return Vec3(0, 0, 1);
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0)
  {
    const double w = d2 / (d2 - d6);
    return Vec3(1 - w, 0, w);
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0)
  {
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return Vec3(0, 1 - w, w);
  }
  const double scale = 1.0 / (va + vb + vc);
  const double v = vb * scale, w = vc * scale;
  return Vec3(1 - v - w, v, w);
}

Vec2 nearestOnSegments(const Vec3& p, const Vec3& q, const Vec3& r, const Vec3& s)
{
  // Ericson 5.1.9: the closest points' parameters, clamped to the segments.
  const Vec3 d1 = q - p, d2 = s - r, w = p - r;
  const double a = d1.squaredNorm(), e = d2.squaredNorm(), f = d2.dot(w);
  if (!(a > 0) && !(e > 0))
    return Vec2(0, 0);
  if (!(a > 0))
    return Vec2(0, std::clamp(f / e, 0.0, 1.0));
  const double c = d1.dot(w);
  if (!(e > 0))
    return Vec2(std::clamp(-c / a, 0.0, 1.0), 0);
  const double b = d1.dot(d2), denominator = a * e - b * b;
  double u = denominator > 1e-14 * a * e ? std::clamp((b * f - c * e) / denominator, 0.0, 1.0) : 0.0;
  double v = (b * u + f) / e;
  if (v < 0)
  {
    v = 0;
    u = std::clamp(-c / a, 0.0, 1.0);
  }
  else if (v > 1)
  {
    v = 1;
    u = std::clamp((b - c) / a, 0.0, 1.0);
  }
  return Vec2(u, v);
}

double pointTriangleDistance(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c)
{
  const Vec3 w = nearestOnTriangle(p, a, b, c);
  return (p - (w.x() * a + w.y() * b + w.z() * c)).norm();
}

double segmentDistance(const Vec3& p, const Vec3& q, const Vec3& r, const Vec3& s)
{
  const Vec2 t = nearestOnSegments(p, q, r, s);
  return ((p + t.x() * (q - p)) - (r + t.y() * (s - r))).norm();
}

ClosestApproach closestApproach(const CurvedMesh& mesh, const Positions& x, double reach)
{
  ClosestApproach best;
  best.distance = std::numeric_limits<double>::infinity();
  const auto apart = [reach](const Vec3& lo_a, const Vec3& hi_a, const Vec3& lo_b, const Vec3& hi_b) {
    return ((lo_b - hi_a).array() > reach).any() || ((lo_a - hi_b).array() > reach).any();
  };
  for (size_t t = 0; t < mesh.triangles.size(); ++t)
  {
    const auto& tri = mesh.triangles[t].nodes;
    const Vec3 lo = x.col(tri[0]).cwiseMin(x.col(tri[1])).cwiseMin(x.col(tri[2]));
    const Vec3 hi = x.col(tri[0]).cwiseMax(x.col(tri[1])).cwiseMax(x.col(tri[2]));
    for (int i = 0; i < static_cast<int>(mesh.nodes.size()); ++i)
    {
      if (i == tri[0] || i == tri[1] || i == tri[2] || apart(lo, hi, x.col(i), x.col(i)))
        continue;
      const double d = pointTriangleDistance(x.col(i), x.col(tri[0]), x.col(tri[1]), x.col(tri[2]));
      if (d < best.distance)
        best = { d, 0, { i, static_cast<int>(t) } };
    }
  }
  std::vector<Vec3> lo(mesh.edges.size()), hi(mesh.edges.size());
  for (size_t e = 0; e < mesh.edges.size(); ++e)
  {
    lo[e] = x.col(mesh.edges[e].nodes[0]).cwiseMin(x.col(mesh.edges[e].nodes[1]));
    hi[e] = x.col(mesh.edges[e].nodes[0]).cwiseMax(x.col(mesh.edges[e].nodes[1]));
  }
  for (size_t a = 0; a < mesh.edges.size(); ++a)
    for (size_t b = a + 1; b < mesh.edges.size(); ++b)
    {
      const auto& ea = mesh.edges[a].nodes;
      const auto& eb = mesh.edges[b].nodes;
      if (ea[0] == eb[0] || ea[0] == eb[1] || ea[1] == eb[0] || ea[1] == eb[1] || apart(lo[a], hi[a], lo[b], hi[b]))
        continue;
      const double d = segmentDistance(x.col(ea[0]), x.col(ea[1]), x.col(eb[0]), x.col(eb[1]));
      if (d < best.distance)
        best = { d, 1, { static_cast<int>(a), static_cast<int>(b) } };
    }
  return best;
}

}  // namespace virtual_origami::core

#include "virtual_origami/core/snap.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Geometry>

namespace virtual_origami::core
{
namespace
{
bool snapToVertex(const Paper& paper, const Vec3& cursor, double radius, Snap& snap)
{
  double best = radius;
  for (size_t v = 0; v < paper.vertices.size(); ++v)
  {
    const double d = (paper.vertices[v].folded - cursor).norm();
    if (d <= best)
    {
      best = d;
      snap.kind = SnapKind::Vertex;
      snap.vertex = static_cast<int>(v);
      snap.point = paper.vertices[v].folded;
    }
  }
  return snap.kind == SnapKind::Vertex;
}

bool snapToEdgeDivision(const Paper& paper, const Vec3& cursor, const SnapSettings& settings, Snap& snap)
{
  double best = settings.radius;
  for (size_t e = 0; e < paper.edges.size(); ++e)
  {
    const Vec3& a = paper.vertices[paper.edges[e].vertices[0]].folded;
    const Vec3& b = paper.vertices[paper.edges[e].vertices[1]].folded;
    for (int n : settings.edge_divisions)
      for (int k = 1; k < n; ++k)
      {
        const Vec3 p = a + (b - a) * (static_cast<double>(k) / n);
        const double d = (p - cursor).norm();
        // Prefer the coarser division when two coincide (1/2 before 2/4).
        if (d < best - 1e-12 || (snap.edge == static_cast<int>(e) && d <= best && n < snap.divisions))
        {
          best = d;
          snap.kind = SnapKind::EdgeDivision;
          snap.edge = static_cast<int>(e);
          snap.divisions = n;
          snap.index = k;
          snap.point = p;
        }
      }
  }
  if (snap.kind != SnapKind::EdgeDivision)
    return false;
  const Vec3& a = paper.vertices[paper.edges[snap.edge].vertices[0]].folded;
  const Vec3& b = paper.vertices[paper.edges[snap.edge].vertices[1]].folded;
  for (int k = 1; k < snap.divisions; ++k)
    snap.guide_points.push_back(a + (b - a) * (static_cast<double>(k) / snap.divisions));
  return true;
}

/// Unit directions dividing the face's angle at `vertex` into n equal parts (k = 1 … n−1).
std::vector<Vec3> angleDivisions(const Paper& paper, int face, int vertex, int n)
{
  const std::vector<int>& vs = paper.faces[face].vertices;
  const size_t count = vs.size();
  size_t i = 0;
  while (vs[i] != vertex)
    ++i;
  const Vec3& p = paper.vertices[vertex].folded;
  const Vec3 to_next = (paper.vertices[vs[(i + 1) % count]].folded - p).normalized();
  const Vec3 to_prev = (paper.vertices[vs[(i + count - 1) % count]].folded - p).normalized();
  const double angle = std::acos(std::clamp(to_next.dot(to_prev), -1.0, 1.0));
  const Vec3 axis = to_next.cross(to_prev).normalized();
  std::vector<Vec3> dirs;
  for (int k = 1; k < n; ++k)
    dirs.push_back(Eigen::AngleAxisd(angle * k / n, axis) * to_next);
  return dirs;
}

/// How far the ray from `p` (a vertex of the convex face) along `dir` runs inside the face:
/// where it leaves it. 0 when it does not enter it.
double exitAlong(const Paper& paper, int face, const Vec3& p, const Vec3& dir)
{
  const std::vector<int>& vs = paper.faces[face].vertices;
  const Vec3 n = paper.faceNormal(face);
  const double tolerance = 1e-12 * paper.scale();
  double exit = 0.0;
  for (size_t i = 0; i < vs.size(); ++i)
  {
    const Vec3& a = paper.vertices[vs[i]].folded;
    const Vec3& b = paper.vertices[vs[(i + 1) % vs.size()]].folded;
    const double across = dir.cross(b - a).dot(n);
    if (std::abs(across) < 1e-12)
      continue;  // parallel to this side
    const double t = (a - p).cross(b - a).dot(n) / across;
    const double s = (p + t * dir - a).dot(b - a) / (b - a).squaredNorm();
    if (t > tolerance && s >= -1e-9 && s <= 1 + 1e-9)
      exit = std::max(exit, t);
  }
  return exit;
}

bool snapToAngleDivision(const Paper& paper, const Vec3& cursor, const SnapSettings& settings, int start, Snap& snap)
{
  const Vec3& p = paper.vertices[start].folded;
  const double reach = (cursor - p).norm();
  if (reach <= settings.radius)
    return false;
  double best = settings.radius;
  // Where layers' corners coincide (a folded model's open point) the angles of every layer's
  // faces there are offered, not only those of the vertex the press snapped to.
  std::vector<std::pair<int, int>> corners;  // (vertex, face)
  const double same = 1e-9 * paper.scale();
  for (size_t v = 0; v < paper.vertices.size(); ++v)
    if ((paper.vertices[v].folded - p).norm() <= same)
      for (int f : paper.facesOfVertex(static_cast<int>(v)))
        corners.emplace_back(static_cast<int>(v), f);
  for (const auto& [vertex, f] : corners)
    for (int n : settings.angle_divisions)
    {
      const std::vector<Vec3> dirs = angleDivisions(paper, f, vertex, n);
      for (size_t k = 0; k < dirs.size(); ++k)
      {
        const double t = (cursor - p).dot(dirs[k]);
        if (t <= 0)
          continue;
        const double d = (p + t * dirs[k] - cursor).norm();
        if (d < best - 1e-12 || (snap.face == f && d <= best && n < snap.divisions))
        {
          best = d;
          snap.kind = SnapKind::AngleDivision;
          snap.vertex = vertex;
          snap.face = f;
          snap.divisions = n;
          snap.index = static_cast<int>(k) + 1;
          // Extended to where it leaves the face: a crease from the vertex that ends short of
          // the far side would not cut the face, and would be refused.
          snap.point = p + std::max(t, exitAlong(paper, f, p, dirs[k])) * dirs[k];
        }
      }
    }
  if (snap.kind != SnapKind::AngleDivision)
    return false;
  for (const Vec3& dir : angleDivisions(paper, snap.face, snap.vertex, snap.divisions))
    snap.guide_lines.push_back({ p, p + std::max(reach, exitAlong(paper, snap.face, p, dir)) * dir });
  return true;
}
}  // namespace

Snap snapPoint(const Paper& paper, const Vec3& cursor, const SnapSettings& settings, int start_vertex)
{
  Snap snap;
  snap.point = cursor;
  if (snapToVertex(paper, cursor, settings.radius, snap))
    return snap;
  if (snapToEdgeDivision(paper, cursor, settings, snap))
    return snap;
  if (start_vertex >= 0 && start_vertex < static_cast<int>(paper.vertices.size()))
    snapToAngleDivision(paper, cursor, settings, start_vertex, snap);
  return snap;
}

}  // namespace virtual_origami::core

#include "virtual_origami/curved/strip_scenes.h"

#include <cmath>
#include <limits>

#include "virtual_origami/core/planar_geometry.h"
#include "virtual_origami/curved/bubble_mesh.h"
#include "virtual_origami/curved/cgal_mesh.h"

namespace virtual_origami::core
{
namespace
{
bool positiveFinite(double v) { return std::isfinite(v) && v > 0; }

/// Nodes this near x = 0 or x = L (relative to L) count as on the clamp lines; the meshers put
/// the crease nodes there up to rounding.
constexpr double kOnLine = 1e-9;
}  // namespace

Expected<StripScene> stripScene(double length, double width, bool held_end, double clamp)
{
  if (clamp == 0.0)
    clamp = width / 2;
  if (!positiveFinite(length) || !positiveFinite(width) || !positiveFinite(clamp))
    return Expected<StripScene>::failure("a strip needs a positive, finite length, width and clamp zone");
  StripScene scene;
  scene.length = length;
  scene.width = width;
  scene.clamp = clamp;
  scene.held_end = held_end;
  Paper& p = scene.paper;
  const double end = held_end ? length + clamp : length;
  // Counter-clockwise from the clamp zone's lower corner; the flat creases at x = 0 (and L).
  std::vector<Vec2> corners = { { -clamp, 0 }, { 0, 0 }, { length, 0 } };
  if (held_end)
    corners.push_back({ end, 0 });
  if (held_end)
    corners.push_back({ end, width });
  corners.push_back({ length, width });
  corners.push_back({ 0, width });
  corners.push_back({ -clamp, width });
  for (const Vec2& c : corners)
    p.vertices.push_back({ c, Vec3(c.x(), c.y(), 0.0) });
  const int n = static_cast<int>(corners.size());
  for (int i = 0; i < n; ++i)
    p.edges.push_back({ { i, (i + 1) % n }, Assignment::Boundary, 0.0, { -1, -1 }, false, {} });
  // Vertex indices: the bottom row from 0 (x = −c, 0, L[, L + c]), the top row back: the vertex
  // above bottom vertex i is n − 1 − i.
  const auto top = [&](int bottom_index) { return n - 1 - bottom_index; };
  p.edges.push_back({ { 1, top(1) }, Assignment::Flat, 0.0, { -1, -1 }, false, {} });
  p.faces.push_back({ { 0, 1, top(1), top(0) }, {} });
  p.faces.push_back({ { 1, 2, top(2), top(1) }, {} });
  if (held_end)
  {
    p.edges.push_back({ { 2, top(2) }, Assignment::Flat, 0.0, { -1, -1 }, false, {} });
    p.faces.push_back({ { 2, 3, top(3), top(2) }, {} });
  }
  p.sheet_area = (end + clamp) * width;
  if (const Status linked = linkTopology(p); !linked)
    return Expected<StripScene>::failure("strip: " + linked.message());
  return scene;
}

Expected<CurvedMesh> meshStrip(const StripScene& scene, StripMesher mesher, double spacing)
{
  if (mesher == StripMesher::Cgal)
  {
    CgalMeshOptions options;
    options.spacing = spacing;
    return cgalMesh(scene.paper, options);
  }
  BubbleMeshOptions options;
  options.spacing = spacing;
  return bubbleMesh(scene.paper, options);
}

void holdStripZones(const StripScene& scene, CurvedMesh& mesh)
{
  // Faces 0 (the clamp zone) and 2 (the end zone) are the ones stripPins holds.
  mesh.held_faces.assign(scene.paper.faces.size(), 0);
  mesh.held_faces[0] = 1;
  if (scene.held_end)
    mesh.held_faces[2] = 1;
}

std::vector<CurvedPin> stripPins(const StripScene& scene, const CurvedMesh& mesh, const Eigen::Vector2d& end,
                                 double end_angle)
{
  std::vector<CurvedPin> pins;
  const double tol = kOnLine * scene.length;
  const Eigen::Vector2d along(std::cos(end_angle), std::sin(end_angle));
  for (size_t v = 0; v < mesh.nodes.size(); ++v)
  {
    const Vec2& p = mesh.nodes[v].crease_pattern;
    if (p.x() <= tol)
      pins.push_back({ static_cast<int>(v), Vec3(p.x(), p.y(), 0.0) });
    else if (scene.held_end && p.x() >= scene.length - tol)
    {
      const Eigen::Vector2d xz = end + std::max(0.0, p.x() - scene.length) * along;
      pins.push_back({ static_cast<int>(v), Vec3(xz.x(), p.y(), xz.y()) });
    }
  }
  return pins;
}

Positions stripAlong(const StripScene& scene, const CurvedMesh& mesh, const ElasticaCurve& curve)
{
  Positions x(3, mesh.nodes.size());
  const Eigen::Vector2d end = curve.at(curve.length);
  const double end_angle = curve.theta.back();
  const Eigen::Vector2d along(std::cos(end_angle), std::sin(end_angle));
  for (size_t v = 0; v < mesh.nodes.size(); ++v)
  {
    const Vec2& p = mesh.nodes[v].crease_pattern;
    Eigen::Vector2d xz;
    if (p.x() <= 0)
      xz = Eigen::Vector2d(p.x(), 0.0);
    else if (p.x() >= scene.length)
      xz = end + (p.x() - scene.length) * along;
    else
      xz = curve.at(p.x() * curve.length / scene.length);
    x.col(v) = Vec3(xz.x(), p.y(), xz.y());
  }
  return x;
}

Expected<Vec3> pointOnSheet(const CurvedMesh& mesh, const Positions& x, const Vec2& q)
{
  // The triangle whose smallest barycentric coordinate at q is largest: the one holding q (a
  // point on a shared edge is in both, and either gives the same point).
  int best = -1;
  double best_min = -std::numeric_limits<double>::infinity();
  Eigen::Vector3d best_weights = Eigen::Vector3d::Zero();
  for (size_t t = 0; t < mesh.triangles.size(); ++t)
  {
    const auto& n = mesh.triangles[t].nodes;
    const Vec2 &a = mesh.nodes[n[0]].crease_pattern, &b = mesh.nodes[n[1]].crease_pattern,
               &c = mesh.nodes[n[2]].crease_pattern;
    const double area = cross2(b - a, c - a);
    if (!(area > 0))
      continue;
    const Eigen::Vector3d w(cross2(b - q, c - q) / area, cross2(c - q, a - q) / area, cross2(a - q, b - q) / area);
    if (w.minCoeff() > best_min)
    {
      best_min = w.minCoeff();
      best = static_cast<int>(t);
      best_weights = w;
    }
  }
  // Off by more than rounding of the triangle's size: not on the sheet.
  if (best < 0 || best_min < -1e-9 || !q.allFinite())
    return Expected<Vec3>::failure("the point (" + std::to_string(q.x()) + ", " + std::to_string(q.y()) +
                                   ") is off the sheet");
  const auto& n = mesh.triangles[best].nodes;
  return Vec3(best_weights[0] * x.col(n[0]) + best_weights[1] * x.col(n[1]) + best_weights[2] * x.col(n[2]));
}

Expected<double> midlineDeviation(const StripScene& scene, const CurvedMesh& mesh, const Positions& x,
                                  const ElasticaCurve& curve, int samples)
{
  double largest = 0.0;
  for (int k = 0; k <= samples; ++k)
  {
    const double s = scene.length * k / samples;
    const Expected<Vec3> p = pointOnSheet(mesh, x, Vec2(s, scene.width / 2));
    if (!p)
      return Expected<double>::failure(p.message());
    const Eigen::Vector2d xz = curve.at(s * curve.length / scene.length);
    largest = std::max(largest, (*p - Vec3(xz.x(), scene.width / 2, xz.y())).norm());
  }
  return largest / scene.length;
}

CurvedMaterial stripMaterial(CurvedMaterial material)
{
  material.crease = 1.0;
  return material;
}

}  // namespace virtual_origami::core

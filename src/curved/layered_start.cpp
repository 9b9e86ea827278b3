#include "virtual_origami/curved/layered_start.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Dense>

#include "virtual_origami/core/layers.h"

namespace virtual_origami::core
{
namespace
{
/// Groups faces lying in one plane (parallel normals, same offset): the stacks of a flat fold.
std::vector<int> groupPlanes(const Paper& paper, double tolerance, std::vector<Vec3>& normals)
{
  std::vector<int> plane_of(paper.faces.size(), -1);
  std::vector<double> offsets;
  for (size_t f = 0; f < paper.faces.size(); ++f)
  {
    const Vec3 n = paper.faceNormal(static_cast<int>(f));
    const Vec3 c = paper.faceCentroid(static_cast<int>(f));
    for (size_t p = 0; p < normals.size() && plane_of[f] < 0; ++p)
    {
      const double facing = n.dot(normals[p]);
      if (std::abs(std::abs(facing) - 1) < tolerance && std::abs(normals[p].dot(c) - offsets[p]) < tolerance)
        plane_of[f] = static_cast<int>(p);
    }
    if (plane_of[f] < 0)
    {
      plane_of[f] = static_cast<int>(normals.size());
      normals.push_back(n);
      offsets.push_back(n.dot(c));
    }
  }
  return plane_of;
}

/// Per face, its level along its plane's normal: one more than the highest face the orders
/// put below it in the same plane (longest path; a cycle's faces keep what they reached).
std::vector<int> stackLevelsByPlane(const Paper& paper, const std::vector<int>& plane_of,
                                    const std::vector<Vec3>& normals)
{
  const size_t n = paper.faces.size();
  // The recorded orders, and each flat fold's two faces (a valley turns their fronts to face
  // each other: each lies on the other's front), which files seldom list.
  std::vector<FaceOrder> orders = paper.face_orders;
  for (const Edge& e : paper.edges)
    if (e.isCrease() && std::abs(e.fold_angle) > M_PI - 1e-3)
      orders.push_back({ e.faces[0], e.faces[1], e.fold_angle > 0 ? 1 : -1 });
  std::vector<std::array<int, 2>> below_above;
  for (const FaceOrder& o : orders)
  {
    if (o.above == 0 || o.face < 0 || o.other < 0 || static_cast<size_t>(o.face) >= n ||
        static_cast<size_t>(o.other) >= n || o.face == o.other || plane_of[o.face] != plane_of[o.other])
      continue;
    // `other` lies on side `above` of `face`'s front; turn it into the plane's normal.
    const bool face_along = paper.faceNormal(o.face).dot(normals[plane_of[o.face]]) > 0;
    const bool other_higher = (o.above > 0) == face_along;
    below_above.push_back(other_higher ? std::array<int, 2>{ o.face, o.other } : std::array<int, 2>{ o.other, o.face });
  }
  return levelsFromOrders(n, below_above);
}
/// The unit direction in `face`'s folded plane perpendicular to paper edge `e`, into the face.
Vec3 inwardFrom(const Paper& paper, int e, int face)
{
  const Edge& edge = paper.edges[e];
  const Vec3 p0 = paper.vertices[edge.vertices[0]].folded, p1 = paper.vertices[edge.vertices[1]].folded;
  const Vec3 along = (p1 - p0).normalized();
  Vec3 w = paper.faceCentroid(face) - p0;
  w -= w.dot(along) * along;
  return w.normalized();
}
}  // namespace

LayeredStart layeredStart(const CurvedMesh& mesh, const Paper& paper, const LayeredStartOptions& options)
{
  LayeredStart start;
  const double scale = paper.scale();
  const double gap = options.gapFor(paper);
  const double inset = options.stripFor(paper);
  std::vector<Vec3> normals;
  start.plane_of = groupPlanes(paper, options.plane_tolerance * scale, normals);
  start.planes = static_cast<int>(normals.size());
  start.levels = stackLevelsByPlane(paper, start.plane_of, normals);
  start.positions = placeNodes(mesh, paper);

  // Each face moves by a translation t_f whose part along its plane's normal is its level ×
  // gap; the parts in its plane are chosen so faces joined by a crease move alike (least
  // squares): a wing at a right angle to the body moves with the body's layer it hangs from,
  // and its hinge keeps its length.
  const int faces = static_cast<int>(paper.faces.size());
  std::vector<Eigen::Matrix<double, 3, 2>> basis(faces);
  std::vector<Vec3> along_normal(faces);
  for (int f = 0; f < faces; ++f)
  {
    const Vec3& n = normals[start.plane_of[f]];
    const Vec3 u = (std::abs(n.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY()).cross(n).normalized();
    basis[f].col(0) = u;
    basis[f].col(1) = n.cross(u);
    along_normal[f] = start.levels[f] * gap * n;
  }
  Eigen::MatrixXd a = 1e-9 * Eigen::MatrixXd::Identity(2 * faces, 2 * faces);
  Eigen::VectorXd b = Eigen::VectorXd::Zero(2 * faces);
  for (const Edge& e : paper.edges)
  {
    if (!e.isCrease())
      continue;
    // |t_f − t_g|² = |B_f y_f − B_g y_g + (c_f − c_g)|².
    const int f = e.faces[0], g = e.faces[1];
    Eigen::Matrix<double, 3, 4> j;
    j << basis[f], -basis[g];
    const Vec3 c = along_normal[f] - along_normal[g];
    const Eigen::Matrix4d jj = j.transpose() * j;
    const Eigen::Vector4d jc = j.transpose() * c;
    const int index[2] = { 2 * f, 2 * g };
    for (int r = 0; r < 2; ++r)
    {
      b.segment<2>(index[r]) -= jc.segment<2>(2 * r);
      for (int q = 0; q < 2; ++q)
        a.block<2, 2>(index[r], index[q]) += jj.block<2, 2>(2 * r, 2 * q);
    }
  }
  const Eigen::VectorXd y = a.ldlt().solve(b);
  std::vector<Vec3> moved(faces);
  for (int f = 0; f < faces; ++f)
    moved[f] = along_normal[f] + basis[f] * y.segment<2>(2 * f);

  const std::vector<std::vector<int>> node_faces = mesh.facesOfNodes(paper);
  for (size_t i = 0; i < mesh.nodes.size(); ++i)
  {
    const std::vector<int>& of = node_faces[i];
    Vec3 lift = Vec3::Zero();
    for (int f : of)
      lift += moved[f];
    lift /= static_cast<double>(of.size());
    // Set out past the crease: a node between faces of one stack at different levels, both
    // on one side of it (a fold), moves away from them in their plane.
    const MeshNode& node = mesh.nodes[i];
    if (node.paper_edge >= 0 && of.size() == 2 && start.plane_of[of[0]] == start.plane_of[of[1]])
    {
      const Vec3 w0 = inwardFrom(paper, node.paper_edge, of[0]), w1 = inwardFrom(paper, node.paper_edge, of[1]);
      const int levels_apart = std::abs(start.levels[of[0]] - start.levels[of[1]]);
      if (w0.dot(w1) > 0.5 && levels_apart > 0)
        lift -= options.setback * levels_apart * gap * (w0 + w1).normalized();
    }
    // The sheet's own edges draw back into their face: raw edges that meet in one plane (two
    // flaps laid edge to edge) or end inside a fold then lie apart. Paper vertices stay, so
    // layers still touch next to them, where the hinges of several folds meet (layered_start.h).
    if (node.paper_edge >= 0 && of.size() == 1)
      lift += inset * inwardFrom(paper, node.paper_edge, of[0]);
    start.positions.col(i) += lift;
  }
  return start;
}

double stackThickness(const CurvedMesh& mesh, const Paper& paper, const LayeredStart& start, int plane,
                      const Positions& x)
{
  const auto first = std::find(start.plane_of.begin(), start.plane_of.end(), plane);
  if (first == start.plane_of.end())
    return 0.0;
  const Vec3 normal = paper.faceNormal(static_cast<int>(first - start.plane_of.begin()));
  double low = std::numeric_limits<double>::infinity(), high = -low;
  const std::vector<std::vector<int>> node_faces = mesh.facesOfNodes(paper);
  for (int i = 0; i < x.cols(); ++i)
  {
    const std::vector<int>& faces = node_faces[i];
    if (std::none_of(faces.begin(), faces.end(), [&](int f) { return start.plane_of[f] == plane; }))
      continue;
    const double height = normal.dot(x.col(i));
    low = std::min(low, height);
    high = std::max(high, height);
  }
  return high >= low ? high - low : 0.0;
}

}  // namespace virtual_origami::core

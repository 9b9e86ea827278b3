#include "virtual_origami/curved/plate_bending.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>

#include <Eigen/SVD>

namespace virtual_origami::core
{
namespace
{
/// A hinge as hingeAngle takes it, seen from the triangle `from` (left of a→b): the dihedral it
/// takes when the sheet lies on a surface of uniform curvature h = (H₁₁, H₂₂, H₁₂) is row·h.
struct Hinge
{
  std::array<int, 4> nodes{ -1, -1, -1, -1 };
  double rest = 0.0;
  Eigen::RowVector3d row = Eigen::RowVector3d::Zero();
  int edge = -1;
  int across = -1;  // the triangle on its far side; -1 beside a held face (see sideHinge)
  double scale = 1.0;
};

const Eigen::Matrix2d kBasis[3] = { (Eigen::Matrix2d() << 1, 0, 0, 0).finished(),
                                    (Eigen::Matrix2d() << 0, 0, 0, 1).finished(),
                                    (Eigen::Matrix2d() << 0, 1, 1, 0).finished() };

std::array<Vec2, 3> cornersOf(const CurvedMesh& mesh, int t)
{
  std::array<Vec2, 3> c;
  for (int k = 0; k < 3; ++k)
    c[k] = mesh.nodes[mesh.triangles[t].nodes[k]].crease_pattern;
  return c;
}

/// Gradient of the plane through a triangle's corners at heights ½·pᵀHp.
Vec2 planeSlope(const std::array<Vec2, 3>& corner, const Eigen::Matrix2d& h)
{
  const Vec2 origin = corner[0];
  const auto value = [&](const Vec2& p) { return 0.5 * (p - origin).dot(h * (p - origin)); };
  Eigen::Matrix2d sides;
  sides.row(0) = (corner[1] - corner[0]).transpose();
  sides.row(1) = (corner[2] - corner[0]).transpose();
  // Relative to the origin's own slope, which is the same in every triangle and cancels in the
  // jumps: h·origin added back.
  return sides.lu().solve(Eigen::Vector2d(value(corner[1]) - value(corner[0]), value(corner[2]) - value(corner[0]))) +
         h * origin;
}

struct Lookup
{
  const CurvedMesh& mesh;
  const Paper& paper;
  const CurvedMaterial& material;
  std::map<std::pair<int, int>, int> edge_of;

  bool held(int triangle) const
  {
    const int face = mesh.triangles[triangle].face;
    return face >= 0 && face < static_cast<int>(mesh.held_faces.size()) && mesh.held_faces[face];
  }
};

/// The corner c mirrored across the line through a and b.
Vec2 mirrored(const Vec2& c, const Vec2& a, const Vec2& b)
{
  const Vec2 along = (b - a).normalized();
  const Vec2 foot = a + along * along.dot(c - a);
  return 2 * foot - c;
}

/// The hinge on side i (opposite corner i) of triangle t, when that side bends: not on the
/// sheet's edge, not a crease that turns freely, not inside a held face. Beside a held face
/// (a clamp) the paper continues as its own mirror image across the side (the even extension
/// that a clamped edge's zero slope means): the hinge is then the dihedral with the mirror
/// triangle, twice the one with the held triangle (`scale` 2), so the curvature recovered at
/// the clamp is the paper's and not half of it.
std::optional<Hinge> sideHinge(const Lookup& look, int t, int i)
{
  const CurvedMesh& mesh = look.mesh;
  const MeshTriangle& tri = mesh.triangles[t];
  if (look.held(t))
    return std::nullopt;
  const int a = tri.nodes[(i + 1) % 3], b = tri.nodes[(i + 2) % 3];
  const auto found = look.edge_of.find({ std::min(a, b), std::max(a, b) });
  if (found == look.edge_of.end())
    return std::nullopt;
  const MeshEdge& edge = mesh.edges[found->second];
  if (!edge.isHinge())
    return std::nullopt;
  Hinge h;
  h.edge = found->second;
  h.across = edge.triangles[0] == t ? edge.triangles[1] : edge.triangles[0];
  const bool crease = mesh.triangles[h.across].face != tri.face;
  if (crease && !(look.material.crease > 0))
    return std::nullopt;
  int far = -1;
  for (int node : mesh.triangles[h.across].nodes)
    if (node != a && node != b)
      far = node;
  h.nodes = { a, b, tri.nodes[i], far };
  h.rest = crease && edge.paper_edge >= 0 ? look.paper.edges[edge.paper_edge].fold_angle : 0.0;
  const Vec2 pa = mesh.nodes[a].crease_pattern, pb = mesh.nodes[b].crease_pattern;
  const std::array<Vec2, 3> near = cornersOf(mesh, t);
  std::array<Vec2, 3> across = cornersOf(mesh, h.across);
  if (look.held(h.across))
  {
    across = { pa, pb, mirrored(near[i], pa, pb) };
    h.across = -1;
    h.scale = 2.0;
  }
  Vec2 out(pb.y() - pa.y(), pa.x() - pb.x());
  out.normalize();
  if (out.dot(pa - near[i]) < 0)
    out = -out;
  // The jump of the planes' slopes across the side, outward: the dihedral, valley positive.
  for (int k = 0; k < 3; ++k)
    h.row[k] = out.dot(planeSlope(across, kBasis[k]) - planeSlope(near, kBasis[k]));
  return h;
}

/// Smallest singular value of the rows, each scaled to unit length: how well they fix h.
double independence(const std::vector<Eigen::RowVector3d>& rows)
{
  Eigen::MatrixXd m(rows.size(), 3);
  for (size_t k = 0; k < rows.size(); ++k)
    m.row(k) = rows[k] / rows[k].norm();
  const Eigen::VectorXd s = Eigen::JacobiSVD<Eigen::MatrixXd>(m).singularValues();
  return s.size() < 3 ? 0.0 : s[2];
}

std::vector<Eigen::RowVector3d> rowsOf(const std::vector<Hinge>& hinges)
{
  std::vector<Eigen::RowVector3d> rows;
  for (const Hinge& h : hinges)
    rows.push_back(h.row);
  return rows;
}

constexpr double kIndependent = 0.05;  // rows this far from dependent fix h well enough

/// Triangle t's own hinges (`used`, fewer than three) completed by the one or two hinges of the
/// triangles within two bending sides that fix its curvature best; as they were where none fix
/// it well enough.
std::vector<Hinge> completedHinges(const Lookup& look, int t, const std::vector<Hinge>& used)
{
  // Candidates: the hinges of the triangles within two bending sides.
  std::vector<int> near = { t };
  for (int depth = 0; depth < 2; ++depth)
  {
    const size_t count = near.size();
    for (size_t k = 0; k < count; ++k)
      for (int i = 0; i < 3; ++i)
        if (std::optional<Hinge> h = sideHinge(look, near[k], i))
          if (h->across >= 0 && std::find(near.begin(), near.end(), h->across) == near.end())
            near.push_back(h->across);
  }
  std::vector<Hinge> candidates;
  for (size_t k = 1; k < near.size(); ++k)
    for (int i = 0; i < 3; ++i)
      if (std::optional<Hinge> h = sideHinge(look, near[k], i))
      {
        const auto same = [&](const Hinge& o) { return o.edge == h->edge; };
        if (std::none_of(used.begin(), used.end(), same) && std::none_of(candidates.begin(), candidates.end(), same))
          candidates.push_back(*h);
      }
  // The one or two that fix the curvature best.
  const size_t need = 3 - used.size();
  double best = 0.0;
  std::vector<Hinge> chosen;
  for (size_t p = 0; p < candidates.size(); ++p)
    for (size_t q = need == 1 ? p : p + 1; q < (need == 1 ? p + 1 : candidates.size()); ++q)
    {
      std::vector<Hinge> trial = used;
      trial.push_back(candidates[p]);
      if (need == 2)
        trial.push_back(candidates[q]);
      const double quality = independence(rowsOf(trial));
      if (quality > best)
      {
        best = quality;
        chosen = trial;
      }
    }
  return best > kIndependent ? chosen : used;
}

/// The jump of the curvature across each bending side inside a face: ½·s·A·(h − h')ᵀ·Q·(h − h'),
/// over the hinges of both triangles, A the mean of their areas.
void addSmoothingTerms(const CurvedMesh& mesh, const CurvedMaterial& material, const Eigen::Matrix3d& density,
                       const std::vector<std::vector<Hinge>>& hinges_of,
                       const std::vector<Eigen::MatrixXd>& curvature_of, std::vector<PlateTerm>& terms)
{
  for (const MeshEdge& edge : mesh.edges)
  {
    if (!edge.isHinge())
      continue;
    const int t = edge.triangles[0], u = edge.triangles[1];
    if (hinges_of[t].empty() || hinges_of[u].empty())
      continue;
    if (mesh.triangles[t].face != mesh.triangles[u].face)
      continue;  // a crease: the curvature may jump there
    PlateTerm term;
    std::vector<int> edges;
    const auto slotOf = [&](const Hinge& h) {
      const auto at = std::find(edges.begin(), edges.end(), h.edge);
      if (at != edges.end())
        return static_cast<int>(at - edges.begin());
      edges.push_back(h.edge);
      term.hinges.push_back(h.nodes);
      term.rest.push_back(h.rest);
      return static_cast<int>(edges.size()) - 1;
    };
    std::vector<int> slots_t, slots_u;
    for (const Hinge& h : hinges_of[t])
      slots_t.push_back(slotOf(h));
    for (const Hinge& h : hinges_of[u])
      slots_u.push_back(slotOf(h));
    // A hinge seen from the other side has the same dihedral: slotOf matches it by its edge.
    Eigen::MatrixXd jump = Eigen::MatrixXd::Zero(3, edges.size());
    for (size_t k = 0; k < slots_t.size(); ++k)
      jump.col(slots_t[k]) += curvature_of[t].col(k);
    for (size_t k = 0; k < slots_u.size(); ++k)
      jump.col(slots_u[k]) -= curvature_of[u].col(k);
    double stiffness = material.bend;
    if (mesh.triangles[t].face < static_cast<int>(mesh.curved_faces.size()) &&
        !mesh.curved_faces[mesh.triangles[t].face])
      stiffness *= material.flat_face;
    const double area = 0.5 * (mesh.restArea(t) + mesh.restArea(u));
    term.weight = material.plate_smoothing * stiffness * area * jump.transpose() * density * jump;
    terms.push_back(std::move(term));
  }
}
}  // namespace

std::vector<PlateTerm> plateTerms(const CurvedMesh& mesh, const Paper& paper, const CurvedMaterial& material)
{
  Lookup look{ mesh, paper, material, {} };
  for (size_t e = 0; e < mesh.edges.size(); ++e)
  {
    const auto& n = mesh.edges[e].nodes;
    look.edge_of[{ std::min(n[0], n[1]), std::max(n[0], n[1]) }] = static_cast<int>(e);
  }
  const double nu = material.poisson_ratio;
  Eigen::Matrix3d density;  // ½·hᵀ·density·h = ½·(ν (tr H)² + (1 − ν) H : H)
  density << 1, nu, 0, nu, 1, 0, 0, 0, 2 * (1 - nu);

  std::vector<PlateTerm> terms;
  terms.reserve(mesh.triangles.size());
  // Per triangle: its hinges (by mesh edge) and the map from their dihedrals to its curvature.
  std::vector<std::vector<Hinge>> hinges_of(mesh.triangles.size());
  std::vector<Eigen::MatrixXd> curvature_of(mesh.triangles.size());
  for (size_t t = 0; t < mesh.triangles.size(); ++t)
  {
    const MeshTriangle& tri = mesh.triangles[t];
    if (look.held(static_cast<int>(t)))
      continue;  // held rigidly: its energy cannot change
    double stiffness = material.bend;
    if (tri.face < static_cast<int>(mesh.curved_faces.size()) && !mesh.curved_faces[tri.face])
      stiffness *= material.flat_face;
    const Eigen::Matrix3d plate = stiffness * mesh.restArea(static_cast<int>(t)) * density;

    // Its own sides' hinges; where a side bends freely (the sheet's edge, a free crease), a hinge
    // of a neighbour instead, so that the three dihedrals still fix the curvature: a free edge
    // is a plate's edge, not a softer strip along it.
    std::vector<Hinge> used;
    for (int i = 0; i < 3; ++i)
      if (std::optional<Hinge> h = sideHinge(look, static_cast<int>(t), i))
        used.push_back(*h);
    if (used.empty())
      continue;
    if (used.size() < 3)
      used = completedHinges(look, static_cast<int>(t), used);
    Eigen::MatrixXd r(used.size(), 3);
    for (size_t k = 0; k < used.size(); ++k)
      r.row(k) = used[k].row;
    // h = C·θ: R⁻¹ when three hinges fix it; else the least-energy curvature that gives them.
    Eigen::MatrixXd curvature;
    if (used.size() == 3 && independence(rowsOf(used)) > kIndependent)
      curvature = Eigen::Matrix3d(r).inverse();
    else
    {
      const Eigen::Matrix3d compliance = plate.inverse();
      curvature = compliance * r.transpose() * (r * compliance * r.transpose()).inverse();
    }
    for (size_t k = 0; k < used.size(); ++k)
      curvature.col(k) *= used[k].scale;
    PlateTerm term;
    for (const Hinge& h : used)
    {
      term.hinges.push_back(h.nodes);
      term.rest.push_back(h.rest);
    }
    term.weight = curvature.transpose() * plate * curvature;
    terms.push_back(std::move(term));
    hinges_of[t] = used;
    curvature_of[t] = curvature;
  }
  if (material.plate_smoothing > 0)
    addSmoothingTerms(mesh, material, density, hinges_of, curvature_of, terms);
  for (PlateTerm& term : terms)
    for (const auto& h : term.hinges)
      for (int node : h)
        if (std::find(term.nodes.begin(), term.nodes.end(), node) == term.nodes.end())
          term.nodes.push_back(node);
  return terms;
}

double evaluatePlate(const std::vector<PlateTerm>& terms, const Positions& x, const Assembly& out)
{
  double energy = 0.0;
  for (const PlateTerm& term : terms)
  {
    const int n = static_cast<int>(term.nodes.size()), m = static_cast<int>(term.hinges.size());
    std::vector<std::array<int, 4>> slot(m);  // where each hinge's nodes sit in term.nodes
    Eigen::VectorXd theta(m);
    std::vector<Eigen::Matrix<double, 3, 4>> grad(m);
    std::vector<Eigen::Matrix<double, 12, 12>> curvature(m);
    for (int i = 0; i < m; ++i)
    {
      const auto& h = term.hinges[i];
      for (int k = 0; k < 4; ++k)
        slot[i][k] = static_cast<int>(std::find(term.nodes.begin(), term.nodes.end(), h[k]) - term.nodes.begin());
      double angle = hingeAngle(x.col(h[0]), x.col(h[1]), x.col(h[2]), x.col(h[3]), out.free_index ? &grad[i] : nullptr,
                                out.wantsHessian() ? &curvature[i] : nullptr);
      // A crease folded to ±π measures on the branch nearest its rest angle.
      if (angle - term.rest[i] > M_PI)
        angle -= 2 * M_PI;
      else if (term.rest[i] - angle > M_PI)
        angle += 2 * M_PI;
      theta[i] = angle - term.rest[i];
    }
    const Eigen::VectorXd moment = term.weight * theta;
    energy += 0.5 * theta.dot(moment);
    if (!out.free_index)
      continue;
    Eigen::MatrixXd spread = Eigen::MatrixXd::Zero(3 * n, m);  // each hinge's gradient over the nodes
    for (int i = 0; i < m; ++i)
      for (int k = 0; k < 4; ++k)
        spread.block<3, 1>(3 * slot[i][k], i) += grad[i].col(k);
    const std::vector<int>& free_index = *out.free_index;
    if (out.gradient)
    {
      const Eigen::VectorXd g = spread * moment;
      for (int k = 0; k < n; ++k)
        if (const int f = free_index[term.nodes[k]]; f >= 0)
          out.gradient->segment<3>(3 * f) += g.segment<3>(3 * k);
    }
    if (!out.wantsHessian())
      continue;
    Eigen::MatrixXd hessian = spread * term.weight * spread.transpose();
    for (int i = 0; i < m; ++i)
      for (int k = 0; k < 4; ++k)
        for (int l = 0; l < 4; ++l)
          hessian.block<3, 3>(3 * slot[i][k], 3 * slot[i][l]) += moment[i] * curvature[i].block<3, 3>(3 * k, 3 * l);
    for (int k = 0; k < n; ++k)
      if (const int fk = free_index[term.nodes[k]]; fk >= 0)
        for (int l = 0; l < n; ++l)
          if (const int fl = free_index[term.nodes[l]]; fl >= 0 && (fk >= fl || !out.blocks))
            out.addBlock(fk, fl, hessian.block<3, 3>(3 * k, 3 * l));
  }
  return energy;
}

}  // namespace virtual_origami::core

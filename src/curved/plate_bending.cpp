#include "virtual_origami/curved/plate_bending.h"

#include <cmath>
#include <map>

namespace virtual_origami::core
{
namespace
{
double cross2(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

/// Gradient of the plane through a triangle's corners over the heights ½·pᵀHp (p about `origin`).
Vec2 planeSlope(const std::array<Vec2, 3>& corner, const Eigen::Matrix2d& h, const Vec2& origin)
{
  const auto value = [&](const Vec2& p) { return 0.5 * (p - origin).dot(h * (p - origin)); };
  Eigen::Matrix2d sides;
  sides.row(0) = (corner[1] - corner[0]).transpose();
  sides.row(1) = (corner[2] - corner[0]).transpose();
  return sides.lu().solve(
      Eigen::Vector2d(value(corner[1]) - value(corner[0]), value(corner[2]) - value(corner[0])));
}
}  // namespace

std::vector<PlateTerm> plateTerms(const CurvedMesh& mesh, const Paper& paper, const CurvedMaterial& material)
{
  std::map<std::pair<int, int>, int> edge_of;
  for (size_t e = 0; e < mesh.edges.size(); ++e)
  {
    const auto& n = mesh.edges[e].nodes;
    edge_of[{ std::min(n[0], n[1]), std::max(n[0], n[1]) }] = static_cast<int>(e);
  }
  const double nu = material.poisson_ratio;
  Eigen::Matrix3d density;  // ½·hᵀ·density·h = ½·(ν (tr H)² + (1 − ν) H : H)
  density << 1, nu, 0, nu, 1, 0, 0, 0, 2 * (1 - nu);

  std::vector<PlateTerm> terms;
  terms.reserve(mesh.triangles.size());
  for (size_t t = 0; t < mesh.triangles.size(); ++t)
  {
    const MeshTriangle& tri = mesh.triangles[t];
    std::array<Vec2, 3> corner;
    for (int k = 0; k < 3; ++k)
      corner[k] = mesh.nodes[tri.nodes[k]].crease_pattern;
    const double area = mesh.restArea(static_cast<int>(t));
    double stiffness = material.bend;
    if (tri.face < static_cast<int>(mesh.curved_faces.size()) && !mesh.curved_faces[tri.face])
      stiffness *= material.flat_face;
    PlateTerm term;
    for (int k = 0; k < 3; ++k)
      term.nodes[k] = tri.nodes[k];
    // The dihedral each side takes when the patch (this triangle and those across its sides)
    // lies on a surface of uniform curvature h = (H₁₁, H₂₂, H₁₂): the jump of the planes'
    // slopes across it. Exact for any such surface on any mesh, so the curvature recovered
    // from the dihedrals is too.
    const Vec2 origin = (corner[0] + corner[1] + corner[2]) / 3;
    const Eigen::Matrix2d basis[3] = { (Eigen::Matrix2d() << 1, 0, 0, 0).finished(),
                                       (Eigen::Matrix2d() << 0, 0, 0, 1).finished(),
                                       (Eigen::Matrix2d() << 0, 1, 1, 0).finished() };
    std::vector<int> kept;
    std::vector<Eigen::RowVector3d> rows;
    for (int i = 0; i < 3; ++i)
    {
      const int a = tri.nodes[(i + 1) % 3], b = tri.nodes[(i + 2) % 3];
      const auto found = edge_of.find({ std::min(a, b), std::max(a, b) });
      if (found == edge_of.end())
        continue;
      const MeshEdge& edge = mesh.edges[found->second];
      if (!edge.isHinge())
        continue;
      const int other = edge.triangles[0] == static_cast<int>(t) ? edge.triangles[1] : edge.triangles[0];
      const bool crease = mesh.triangles[other].face != tri.face;
      if (crease && !(material.crease > 0))
        continue;  // a free crease: a free edge of both triangles
      std::array<Vec2, 3> across;
      for (int k = 0; k < 3; ++k)
      {
        const int node = mesh.triangles[other].nodes[k];
        across[k] = mesh.nodes[node].crease_pattern;
        if (node != a && node != b)
          term.nodes[3 + i] = node;
      }
      const Vec2 pa = mesh.nodes[a].crease_pattern, pb = mesh.nodes[b].crease_pattern;
      Vec2 out(pb.y() - pa.y(), pa.x() - pb.x());
      out.normalize();
      if (out.dot(pa - corner[i]) < 0)
        out = -out;
      Eigen::RowVector3d row;
      for (int k = 0; k < 3; ++k)
        row[k] = out.dot(planeSlope(across, basis[k], origin) - planeSlope(corner, basis[k], origin));
      rows.push_back(row);
      kept.push_back(i);
      term.rest[i] = crease && edge.paper_edge >= 0 ? paper.edges[edge.paper_edge].fold_angle : 0.0;
    }
    if (kept.empty())
      continue;
    // ½·A·hᵀ·Q·h, the least over the curvatures that give the kept sides' dihedrals θ (free
    // sides bend as costs least): ½·θᵀ·(R (A Q)⁻¹ Rᵀ)⁻¹·θ, R the kept rows.
    Eigen::MatrixXd r(kept.size(), 3);
    for (size_t k = 0; k < kept.size(); ++k)
      r.row(k) = rows[k];
    const Eigen::Matrix3d compliance = (stiffness * area * density).inverse();
    const Eigen::MatrixXd reduced = (r * compliance * r.transpose()).inverse();
    for (size_t p = 0; p < kept.size(); ++p)
      for (size_t q = 0; q < kept.size(); ++q)
        term.weight(kept[p], kept[q]) = reduced(p, q);
    terms.push_back(term);
  }
  return terms;
}

double evaluatePlate(const std::vector<PlateTerm>& terms, const Positions& x, const Assembly& out)
{
  double energy = 0.0;
  for (const PlateTerm& term : terms)
  {
    // Slots of the hinge of side i: a, b (the side), left (corner i), right (across).
    std::array<std::array<int, 4>, 3> slot;
    Eigen::Vector3d theta = Eigen::Vector3d::Zero();
    std::array<Eigen::Matrix<double, 3, 4>, 3> grad;
    std::array<Eigen::Matrix<double, 12, 12>, 3> curvature;
    for (int i = 0; i < 3; ++i)
    {
      if (term.nodes[3 + i] < 0)
        continue;
      slot[i] = { (i + 1) % 3, (i + 2) % 3, i, 3 + i };
      const auto at = [&](int k) { return x.col(term.nodes[slot[i][k]]); };
      double angle = hingeAngle(at(0), at(1), at(2), at(3), out.free_index ? &grad[i] : nullptr,
                                out.wantsHessian() ? &curvature[i] : nullptr);
      // A crease folded to ±π measures on the branch nearest its rest angle.
      if (angle - term.rest[i] > M_PI)
        angle -= 2 * M_PI;
      else if (term.rest[i] - angle > M_PI)
        angle += 2 * M_PI;
      theta[i] = angle - term.rest[i];
    }
    const Eigen::Vector3d moment = term.weight * theta;
    energy += 0.5 * theta.dot(moment);
    if (!out.free_index)
      continue;
    // Absent sides' slots point at corner 0 and carry nothing.
    std::array<int, 6> nodes = term.nodes;
    for (int& n : nodes)
      if (n < 0)
        n = term.nodes[0];
    std::array<Eigen::Matrix<double, 18, 1>, 3> spread;  // each hinge's gradient over the slots
    Eigen::Matrix<double, 3, 6> gradient = Eigen::Matrix<double, 3, 6>::Zero();
    for (int i = 0; i < 3; ++i)
    {
      spread[i].setZero();
      if (term.nodes[3 + i] < 0)
        continue;
      for (int k = 0; k < 4; ++k)
        spread[i].segment<3>(3 * slot[i][k]) = grad[i].col(k);
      gradient += moment[i] * Eigen::Map<const Eigen::Matrix<double, 3, 6>>(spread[i].data());
    }
    addGradient<6>(nodes, gradient, out);
    if (!out.wantsHessian())
      continue;
    Eigen::Matrix<double, 18, 18> hessian = Eigen::Matrix<double, 18, 18>::Zero();
    for (int i = 0; i < 3; ++i)
    {
      if (term.nodes[3 + i] < 0)
        continue;
      for (int j = 0; j < 3; ++j)
        if (term.nodes[3 + j] >= 0 && term.weight(i, j) != 0.0)
          hessian += term.weight(i, j) * spread[i] * spread[j].transpose();
      for (int k = 0; k < 4; ++k)
        for (int l = 0; l < 4; ++l)
          hessian.block<3, 3>(3 * slot[i][k], 3 * slot[i][l]) += moment[i] * curvature[i].block<3, 3>(3 * k, 3 * l);
    }
    addHessian<6>(nodes, hessian, out);
  }
  return energy;
}

}  // namespace virtual_origami::core

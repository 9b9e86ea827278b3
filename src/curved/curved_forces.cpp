#include "virtual_origami/curved/curved_forces.h"

#include "virtual_origami/core/compliant_faces.h"

#include "virtual_origami/curved/plate_bending.h"

#include <cmath>
#include <optional>

namespace virtual_origami::core
{
namespace
{
/// Where each node of `term` sits in `nodes` (a node listed twice: its first place), or nothing
/// when the term has a node outside them.
std::optional<std::array<int, 3>> slotsIn(const std::array<int, 3>& nodes, const ShearTerm& term)
{
  std::array<int, 3> slots{};
  const std::array<int, 3> term_nodes = { term.o, term.i, term.j };
  for (int k = 0; k < 3; ++k)
  {
    const auto at = std::find(nodes.begin(), nodes.end(), term_nodes[k]);
    if (at == nodes.end())
      return std::nullopt;
    slots[k] = static_cast<int>(at - nodes.begin());
  }
  return slots;
}

/// One wing's share of a hinge's curvature, the wing's gradient n/h·(−(1 − t), −t, 1) over
/// (a, b, wing) differentiated, with n its front normal, `across` the unit direction from the
/// hinge to it, h its distance and t where its foot divides a→b (Tamstorf & Grinspun 2013,
/// "Discrete bending forces and their Jacobians"). One wing alone would also turn the sheet
/// about the hinge, (across nᵀ − n acrossᵀ)/|e|² in its a, b blocks; the two wings' turns
/// cancel, so each wing keeps only its symmetric part.
struct WingCurvature
{
  Eigen::Matrix3d wing_wing, wing_a, wing_b, a_a, b_b, a_b;
};

WingCurvature wingCurvature(const Vec3& along, double le, const Vec3& n, const Vec3& across, double h, double t)
{
  const Eigen::Matrix3d m = (across * n.transpose() + n * across.transpose()) / (h * h);
  const Eigen::Matrix3d k = along * n.transpose() / (le * h);
  const Eigen::Matrix3d k_sym = k + k.transpose();
  const double s = h * h / (2 * le * le);
  WingCurvature c;
  c.wing_wing = -m;
  c.wing_a = (1 - t) * m + k;
  c.wing_b = t * m - k;
  c.a_a = -((1 - t) * (1 - t) + s) * m - (1 - t) * k_sym;
  c.b_b = -(t * t + s) * m + t * k_sym;
  c.a_b = (s - t * (1 - t)) * m + (1 - t) * k - t * k.transpose();
  return c;
}
}  // namespace

double cornerAngle(const Vec3& o, const Vec3& i, const Vec3& j, Eigen::Matrix<double, 3, 3>* grad,
                   Eigen::Matrix<double, 9, 9>* curvature)
{
  const Vec3 u = i - o, v = j - o;
  const Vec3 area = u.cross(v);
  const double angle = std::atan2(area.norm(), u.dot(v));
  if (!grad && !curvature)
    return angle;
  const double lu = u.norm(), lv = v.norm();
  // Moving i towards j's side (in the triangle's plane, across u) closes the angle.
  const Vec3 across_u = v - v.dot(u) / (lu * lu) * u;
  const Vec3 across_v = u - u.dot(v) / (lv * lv) * v;
  const double across_u_norm = across_u.norm(), across_v_norm = across_v.norm();
  // A degenerate corner has no direction to open in: no gradient, no curvature.
  const bool spread = across_u_norm > 1e-14 * lv && across_v_norm > 1e-14 * lu;
  if (grad)
  {
    grad->setZero();
    if (spread)
    {
      grad->col(1) = -across_u / (across_u_norm * lu);
      grad->col(2) = -across_v / (across_v_norm * lv);
      grad->col(0) = -grad->col(1) - grad->col(2);
    }
  }
  if (curvature && !spread)
    curvature->setZero();
  else if (curvature)
  {
    // θ(u, v): in the plane each side turns like a polar angle, (ûpᵀ + pûᵀ)/|u|² with p its
    // unit direction across; out of the plane (along n) the angle opens by cot θ/|u|² for
    // either side alone and closes by 1/|u × v| for both together.
    const double area_norm = area.norm();
    const Vec3 n = area / area_norm;
    const Eigen::Matrix3d nn = n * n.transpose();
    const double cot = u.dot(v) / area_norm;
    const Vec3 du = u / lu, dv = v / lv;
    const Vec3 pu = across_u / across_u_norm, pv = across_v / across_v_norm;
    const Eigen::Matrix3d uu = (du * pu.transpose() + pu * du.transpose() + cot * nn) / (lu * lu);
    const Eigen::Matrix3d vv = (dv * pv.transpose() + pv * dv.transpose() + cot * nn) / (lv * lv);
    const Eigen::Matrix3d uv = -nn / area_norm;  // symmetric, as are uu and vv
    auto block = [&](int r, int c) { return curvature->block<3, 3>(3 * r, 3 * c); };
    block(1, 1) = uu;
    block(2, 2) = vv;
    block(1, 2) = uv;
    block(2, 1) = uv;
    block(0, 1) = block(1, 0) = -(uu + uv);
    block(0, 2) = block(2, 0) = -(uv + vv);
    block(0, 0) = uu + 2 * uv + vv;
  }
  return angle;
}

double hingeAngle(const Vec3& a, const Vec3& b, const Vec3& left, const Vec3& right, Eigen::Matrix<double, 3, 4>* grad,
                  Eigen::Matrix<double, 12, 12>* curvature)
{
  const Vec3 e = b - a;
  const double le = e.norm();
  // Left triangle (a, b, left) and right triangle (b, a, right) are counter-clockwise in the
  // crease pattern: their normals are the front normals, as in measureFoldAngle.
  const Vec3 area_left = e.cross(left - a), area_right = (a - b).cross(right - b);
  const double al = area_left.norm(), ar = area_right.norm();
  const Vec3 n_left = area_left / al, n_right = area_right / ar;
  const double angle = std::atan2(e.dot(n_right.cross(n_left)) / le, n_left.dot(n_right));
  if (!grad && !curvature)
    return angle;
  const double t_left = (left - a).dot(e) / (le * le), t_right = (right - a).dot(e) / (le * le);
  if (grad)
  {
    // Lifting a wing towards its front folds valley-wise: ∂φ/∂x = n / (distance to the hinge).
    const Vec3 g_left = n_left * (le / al), g_right = n_right * (le / ar);
    grad->col(0) = -(1 - t_left) * g_left - (1 - t_right) * g_right;
    grad->col(1) = -t_left * g_left - t_right * g_right;
    grad->col(2) = g_left;
    grad->col(3) = g_right;
  }
  if (curvature)
  {
    const Vec3 along = e / le;
    const WingCurvature l = wingCurvature(along, le, n_left, n_left.cross(along), al / le, t_left);
    const WingCurvature r = wingCurvature(along, le, n_right, along.cross(n_right), ar / le, t_right);
    auto block = [&](int row, int column) { return curvature->block<3, 3>(3 * row, 3 * column); };
    block(0, 0) = l.a_a + r.a_a;
    block(1, 1) = l.b_b + r.b_b;
    block(0, 1) = l.a_b + r.a_b;
    block(1, 0) = block(0, 1).transpose();
    block(2, 2) = l.wing_wing;
    block(3, 3) = r.wing_wing;
    block(2, 3).setZero();
    block(3, 2).setZero();
    block(2, 0) = l.wing_a;
    block(0, 2) = l.wing_a.transpose();
    block(2, 1) = l.wing_b;
    block(1, 2) = l.wing_b.transpose();
    block(3, 0) = r.wing_a;
    block(0, 3) = r.wing_a.transpose();
    block(3, 1) = r.wing_b;
    block(1, 3) = r.wing_b.transpose();
  }
  return angle;
}

CurvedTerms curvedTerms(const CurvedMesh& mesh, const Paper& paper, const CurvedMaterial& material)
{
  CurvedTerms terms;
  const size_t n = mesh.nodes.size();
  terms.mass.assign(n, 0.0);
  for (size_t t = 0; t < mesh.triangles.size(); ++t)
  {
    const auto& tri = mesh.triangles[t].nodes;
    const double area = mesh.restArea(static_cast<int>(t));
    for (int k = 0; k < 3; ++k)
    {
      terms.mass[tri[k]] += material.density * area / 3;
      ShearTerm s;
      s.o = tri[k];
      s.i = tri[(k + 1) % 3];
      s.j = tri[(k + 2) % 3];
      s.rest = cornerAngle(mesh.restPosition(s.o), mesh.restPosition(s.i), mesh.restPosition(s.j));
      s.weight = material.shear * area;
      if (s.weight > 0)
        terms.shear.push_back(s);
    }
  }
  for (const MeshEdge& e : mesh.edges)
  {
    StretchTerm s;
    s.i = e.nodes[0];
    s.j = e.nodes[1];
    s.rest = (mesh.nodes[s.i].crease_pattern - mesh.nodes[s.j].crease_pattern).norm();
    double area = 0;
    for (int t : e.triangles)
      area += t >= 0 ? mesh.restArea(t) : 0.0;
    s.weight = material.stretch * (2 / std::sqrt(3.0)) * area / (s.rest * s.rest);
    terms.stretch.push_back(s);
    if (!e.isHinge())
      continue;
    BendTerm b;
    b.a = e.nodes[0];
    b.b = e.nodes[1];
    for (int side = 0; side < 2; ++side)
    {
      const auto& tri = mesh.triangles[e.triangles[side]].nodes;
      for (int node : tri)
        if (node != b.a && node != b.b)
          (side == 0 ? b.left : b.right) = node;
    }
    const int face_left = mesh.triangles[e.triangles[0]].face, face_right = mesh.triangles[e.triangles[1]].face;
    b.crease = face_left != face_right;
    // A facet of a kept bend is paper, not a crease: it bends as stiffly as the paper does, back
    // towards the bend it was kept with (a hinge free there would let the kept shape fall away).
    const bool facet = b.crease && e.paper_edge >= 0 && isFacet(paper.edges[e.paper_edge]);
    if (material.plate_bending && !facet && (!b.crease || material.crease > 0))
      continue;  // bent by the plate terms of its triangles
    double modulus = material.bend;
    if (facet)
    {
      b.crease = false;
      b.rest = paper.edges[e.paper_edge].fold_angle;
    }
    else if (b.crease)
    {
      modulus *= material.crease;
      b.rest = e.paper_edge >= 0 ? paper.edges[e.paper_edge].fold_angle : 0.0;
    }
    else if (face_left < static_cast<int>(mesh.curved_faces.size()) && !mesh.curved_faces[face_left])
      modulus *= material.flat_face;
    b.weight = modulus * (std::sqrt(3.0) / 2) * s.rest * s.rest / area;
    if (b.weight > 0)
      terms.bend.push_back(b);
  }
  if (material.plate_bending)
    terms.plate = plateTerms(mesh, paper, material);
  return terms;
}

std::vector<std::array<int, 4>> termGroups(const CurvedTerms& terms)
{
  std::vector<std::array<int, 4>> groups;
  groups.reserve(terms.stretch.size() + terms.shear.size() / 3 + terms.bend.size());
  for (const StretchTerm& s : terms.stretch)
    groups.push_back({ s.i, s.j, -1, -1 });
  for (const ShearTerm& s : terms.shear)
    groups.push_back({ s.o, s.i, s.j, -1 });
  for (const BendTerm& b : terms.bend)
    groups.push_back({ b.a, b.b, b.left, b.right });
  // A plate term couples every two of its nodes.
  for (const PlateTerm& p : terms.plate)
    for (size_t i = 0; i < p.nodes.size(); ++i)
      for (size_t j = i + 1; j < p.nodes.size(); ++j)
        groups.push_back({ p.nodes[i], p.nodes[j], -1, -1 });
  return groups;
}

Eigen::SparseMatrix<double> blockPattern(int free_count, const std::vector<int>& free_index,
                                         const std::vector<std::array<int, 4>>& groups)
{
  std::vector<std::vector<int>> rows(free_count);  // per block column, its block rows
  for (int f = 0; f < free_count; ++f)
    rows[f].push_back(f);
  for (const auto& group : groups)
    for (int a : group)
      for (int b : group)
        if (a >= 0 && b >= 0 && free_index[a] > free_index[b] && free_index[b] >= 0)
          rows[free_index[b]].push_back(free_index[a]);
  size_t blocks = 0;
  for (auto& r : rows)
  {
    std::sort(r.begin(), r.end());
    r.erase(std::unique(r.begin(), r.end()), r.end());
    blocks += r.size();
  }
  Eigen::SparseMatrix<double> m(3 * free_count, 3 * free_count);
  m.reserve(static_cast<Eigen::Index>(9 * blocks));
  for (int f = 0; f < free_count; ++f)
    for (int c = 0; c < 3; ++c)
    {
      m.startVec(3 * f + c);
      for (int fr : rows[f])
        for (int r = 0; r < 3; ++r)
          m.insertBack(3 * fr + r, 3 * f + c) = 0.0;
    }
  m.finalize();
  return m;
}

CurvedEnergy evaluateCurved(const CurvedTerms& terms, const Positions& x, const Assembly& out)
{
  CurvedEnergy energy;
  for (const StretchTerm& s : terms.stretch)
  {
    const Vec3 d = x.col(s.j) - x.col(s.i);
    const double length = d.norm();
    Eigen::Matrix<double, 3, 2> grad;
    grad.col(1) = length > 0 ? Vec3(d / length) : Vec3::Zero();
    grad.col(0) = -grad.col(1);
    // ∇²l = (I − êêᵀ)/l: the transverse stiffness w(1 − l0/l)(I − êêᵀ) that Gauss–Newton would
    // leave out, positive when stretched, negative when compressed.
    Eigen::Matrix<double, 6, 6> curvature;
    if (out.wantsHessian())
    {
      Eigen::Matrix3d transverse = Eigen::Matrix3d::Zero();
      if (length > 0)
        transverse = (Eigen::Matrix3d::Identity() - grad.col(1) * grad.col(1).transpose()) / length;
      curvature << transverse, -transverse, -transverse, transverse;
    }
    energy.stretch +=
        addTerm<2>({ s.i, s.j }, s.weight, length - s.rest, grad, out, out.wantsHessian() ? &curvature : nullptr);
  }
  // The corners of one triangle follow each other (curvedTerms): their derivatives are summed
  // and assembled once per triangle, a third of the sparse additions.
  for (size_t t = 0; t < terms.shear.size();)
  {
    const std::array<int, 3> nodes = { terms.shear[t].o, terms.shear[t].i, terms.shear[t].j };
    Eigen::Matrix<double, 3, 3> gradient = Eigen::Matrix<double, 3, 3>::Zero();
    Eigen::Matrix<double, 9, 9> hessian;
    if (out.wantsHessian())
      hessian.setZero();
    for (; t < terms.shear.size(); ++t)
    {
      const ShearTerm& s = terms.shear[t];
      const std::optional<std::array<int, 3>> slots = slotsIn(nodes, s);
      if (!slots)
        break;  // the next triangle (never the group's first term, which is over `nodes`)
      Eigen::Matrix<double, 3, 3> grad;
      Eigen::Matrix<double, 9, 9> curvature;
      const double residual = cornerAngle(x.col(s.o), x.col(s.i), x.col(s.j), out.free_index ? &grad : nullptr,
                                          out.wantsHessian() ? &curvature : nullptr) -
                              s.rest;
      energy.shear += 0.5 * s.weight * residual * residual;
      if (!out.free_index)
        continue;
      for (int k = 0; k < 3; ++k)
        gradient.col((*slots)[k]) += s.weight * residual * grad.col(k);
      if (!out.wantsHessian())
        continue;
      for (int k = 0; k < 3; ++k)
        for (int l = 0; l < 3; ++l)
          hessian.block<3, 3>(3 * (*slots)[k], 3 * (*slots)[l]) +=
              s.weight * (grad.col(k) * grad.col(l).transpose() + residual * curvature.block<3, 3>(3 * k, 3 * l));
    }
    addGradient<3>(nodes, gradient, out);
    if (out.wantsHessian())
      addHessian<3>(nodes, hessian, out);
  }
  for (const BendTerm& b : terms.bend)
  {
    Eigen::Matrix<double, 3, 4> grad;
    Eigen::Matrix<double, 12, 12> curvature;
    double angle = hingeAngle(x.col(b.a), x.col(b.b), x.col(b.left), x.col(b.right), out.free_index ? &grad : nullptr,
                              out.wantsHessian() ? &curvature : nullptr);
    // A crease folded to ±π measures on the branch nearest its rest angle.
    if (angle - b.rest > M_PI)
      angle -= 2 * M_PI;
    else if (b.rest - angle > M_PI)
      angle += 2 * M_PI;
    energy.bend += addTerm<4>({ b.a, b.b, b.left, b.right }, b.weight, angle - b.rest, grad, out,
                              out.wantsHessian() ? &curvature : nullptr);
  }
  energy.bend += evaluatePlate(terms.plate, x, out);
  return energy;
}

void restTermsAt(CurvedTerms& terms, const Positions& x)
{
  for (StretchTerm& s : terms.stretch)
    s.rest = (x.col(s.i) - x.col(s.j)).norm();
  for (ShearTerm& s : terms.shear)
    s.rest = cornerAngle(x.col(s.o), x.col(s.i), x.col(s.j));
  for (BendTerm& b : terms.bend)
  {
    double angle = hingeAngle(x.col(b.a), x.col(b.b), x.col(b.left), x.col(b.right), nullptr, nullptr);
    if (angle - b.rest > M_PI)
      angle -= 2 * M_PI;
    else if (b.rest - angle > M_PI)
      angle += 2 * M_PI;
    b.rest = angle;
  }
}

}  // namespace virtual_origami::core

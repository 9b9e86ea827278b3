#include "virtual_origami/curved/curved_forces.h"

#include <cmath>

#include <unsupported/Eigen/AutoDiff>

namespace virtual_origami::core
{
namespace
{
/// Adds the transverse part of an edge's Hessian, w(1 − l0/l)(I − êêᵀ), which Gauss–Newton
/// leaves out: positive when stretched, negative when compressed.
void addTension(const StretchTerm& s, const Vec3& d, double length, const Assembly& out)
{
  if (!out.wantsHessian() || !(length > 0))
    return;
  const Vec3 u = d / length;
  const Eigen::Matrix3d block = s.weight * (1.0 - s.rest / length) * (Eigen::Matrix3d::Identity() - u * u.transpose());
  const int fi = (*out.free_index)[s.i], fj = (*out.free_index)[s.j];
  if (fi >= 0)
    out.addBlock(fi, fi, block);
  if (fj >= 0)
    out.addBlock(fj, fj, block);
  if (fi >= 0 && fj >= 0)
  {
    const Eigen::Matrix3d opposite = -block;
    out.addBlock(fi, fj, opposite);
    out.addBlock(fj, fi, opposite);
  }
}
}  // namespace

namespace
{
double valueOf(double v) { return v; }
template <class D>
double valueOf(const Eigen::AutoDiffScalar<D>& v)
{
  return v.value();
}

template <class S>
using V3 = Eigen::Matrix<S, 3, 1>;

template <class S>
S cornerAngleT(const V3<S>& o, const V3<S>& i, const V3<S>& j, Eigen::Matrix<S, 3, 3>* grad)
{
  using std::atan2;
  const V3<S> u = i - o, v = j - o;
  const S angle = atan2(u.cross(v).norm(), u.dot(v));
  if (grad)
  {
    grad->setZero();
    const S lu = u.norm(), lv = v.norm();
    // Moving i towards j's side (in the triangle's plane, across u) closes the angle.
    const V3<S> across_u = v - v.dot(u) / (lu * lu) * u;
    const V3<S> across_v = u - u.dot(v) / (lv * lv) * v;
    if (valueOf(across_u.norm()) > 1e-14 * valueOf(lv) && valueOf(across_v.norm()) > 1e-14 * valueOf(lu))
    {
      grad->col(1) = -across_u / (across_u.norm() * lu);
      grad->col(2) = -across_v / (across_v.norm() * lv);
      grad->col(0) = -grad->col(1) - grad->col(2);
    }
  }
  return angle;
}

template <class S>
S hingeAngleT(const V3<S>& a, const V3<S>& b, const V3<S>& left, const V3<S>& right, Eigen::Matrix<S, 3, 4>* grad)
{
  using std::atan2;
  const V3<S> e = b - a;
  const S le = e.norm();
  // Left triangle (a, b, left) and right triangle (b, a, right) are counter-clockwise in the
  // crease pattern: their normals are the front normals, as in measureFoldAngle.
  const V3<S> area_left = e.cross(left - a), area_right = (a - b).cross(right - b);
  const S al = area_left.norm(), ar = area_right.norm();
  const V3<S> n_left = area_left / al, n_right = area_right / ar;
  const S angle = atan2(e.dot(n_right.cross(n_left)) / le, n_left.dot(n_right));
  if (grad)
  {
    // Lifting a wing towards its front folds valley-wise: ∂φ/∂x = n / (distance to the hinge).
    const V3<S> g_left = n_left * (le / al), g_right = n_right * (le / ar);
    const S t_left = (left - a).dot(e) / (le * le), t_right = (right - a).dot(e) / (le * le);
    grad->col(0) = -(1 - t_left) * g_left - (1 - t_right) * g_right;
    grad->col(1) = -t_left * g_left - t_right * g_right;
    grad->col(2) = g_left;
    grad->col(3) = g_right;
  }
  return angle;
}

/// Second derivatives of a measure: forward-mode automatic differentiation of its analytic
/// gradient, K nodes of 3 coordinates.
template <int K, class Measure>
Eigen::Matrix<double, 3 * K, 3 * K> curvatureOf(const std::array<Vec3, K>& points, Measure measure)
{
  using Ad = Eigen::AutoDiffScalar<Eigen::Matrix<double, 3 * K, 1>>;
  std::array<V3<Ad>, K> p;
  for (int k = 0; k < K; ++k)
    for (int r = 0; r < 3; ++r)
      p[k][r] = Ad(points[k][r], 3 * K, 3 * k + r);
  Eigen::Matrix<Ad, 3, K> grad;
  measure(p, &grad);
  Eigen::Matrix<double, 3 * K, 3 * K> h;
  for (int k = 0; k < K; ++k)
    for (int r = 0; r < 3; ++r)
      h.row(3 * k + r) = grad(r, k).derivatives().transpose();
  return 0.5 * (h + h.transpose());
}
}  // namespace

double cornerAngle(const Vec3& o, const Vec3& i, const Vec3& j, Eigen::Matrix<double, 3, 3>* grad,
                   Eigen::Matrix<double, 9, 9>* curvature)
{
  if (curvature)
    *curvature = curvatureOf<3>({ o, i, j }, [](const auto& p, auto* g) { return cornerAngleT(p[0], p[1], p[2], g); });
  return cornerAngleT<double>(o, i, j, grad);
}

double hingeAngle(const Vec3& a, const Vec3& b, const Vec3& left, const Vec3& right, Eigen::Matrix<double, 3, 4>* grad,
                  Eigen::Matrix<double, 12, 12>* curvature)
{
  if (curvature)
    *curvature = curvatureOf<4>({ a, b, left, right },
                                [](const auto& p, auto* g) { return hingeAngleT(p[0], p[1], p[2], p[3], g); });
  return hingeAngleT<double>(a, b, left, right, grad);
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
    double modulus = material.bend;
    if (b.crease)
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
        if (a >= 0 && b >= 0 && a != b && free_index[a] >= 0 && free_index[b] >= 0)
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
    energy.stretch += addTerm<2>({ s.i, s.j }, s.weight, length - s.rest, grad, out);
    addTension(s, d, length, out);
  }
  for (const ShearTerm& s : terms.shear)
  {
    Eigen::Matrix<double, 3, 3> grad;
    Eigen::Matrix<double, 9, 9> curvature;
    const double angle = cornerAngle(x.col(s.o), x.col(s.i), x.col(s.j), out.free_index ? &grad : nullptr,
                                     out.wantsHessian() ? &curvature : nullptr);
    energy.shear +=
        addTerm<3>({ s.o, s.i, s.j }, s.weight, angle - s.rest, grad, out, out.wantsHessian() ? &curvature : nullptr);
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
  return energy;
}

}  // namespace virtual_origami::core

#include "virtual_origami/solvers/driven_faces.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Geometry>
#include <Eigen/SVD>

#include "virtual_origami/core/compliant_faces.h"

namespace virtual_origami::core
{
namespace
{
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// The vertex of `face` farthest from the line through a and b in the crease pattern.
int wingVertex(const Paper& paper, int face, int a, int b)
{
  const Vec2 pa = paper.vertices[a].crease_pattern;
  const Vec2 axis = (paper.vertices[b].crease_pattern - pa).normalized();
  int best = -1;
  double best_distance = -1.0;
  for (int v : paper.faces[face].vertices)
  {
    const Vec2 d = paper.vertices[v].crease_pattern - pa;
    const double distance = std::abs(axis.x() * d.y() - axis.y() * d.x());
    if (v != a && v != b && distance > best_distance)
    {
      best_distance = distance;
      best = v;
    }
  }
  return best;
}

Eigen::Matrix3d skew(const Eigen::Vector3d& q)
{
  Eigen::Matrix3d s;
  s << 0, -q.z(), q.y(), q.z(), 0, -q.x(), -q.y(), q.x(), 0;
  return s;
}

double unwrapNear(double angle, double reference)
{
  if (!std::isfinite(reference))
    return angle;
  while (angle - reference > M_PI)
    angle -= 2 * M_PI;
  while (reference - angle > M_PI)
    angle += 2 * M_PI;
  return angle;
}
}  // namespace

double hingeAngle(const Hinge& h, const Positions& x)
{
  const Eigen::Vector3d e = x.col(h.b) - x.col(h.a);
  const Eigen::Vector3d n_left = e.cross(x.col(h.left) - x.col(h.a));
  const Eigen::Vector3d n_right = (x.col(h.right) - x.col(h.a)).cross(e);
  // As measureFoldAngle: positive when the faces turn towards each other on the front (valley).
  return std::atan2(e.normalized().dot(n_right.cross(n_left)), n_left.dot(n_right));
}

Eigen::Matrix<double, 3, 4> hingeAngleGradient(const Hinge& h, const Positions& x)
{
  const Eigen::Vector3d e = x.col(h.b) - x.col(h.a);
  const Eigen::Vector3d c = x.col(h.left) - x.col(h.a);
  const Eigen::Vector3d d = x.col(h.right) - x.col(h.a);
  const Eigen::Vector3d n_left = e.cross(c);
  const Eigen::Vector3d n_right = d.cross(e);
  const double e2 = e.squaredNorm(), e_norm = std::sqrt(e2);
  // A wing moving along its face's front normal turns the face about the axis by its
  // displacement over its height |n|/|e|: d θ / d wing = |e| n / |n|².
  const Eigen::Vector3d g_left = e_norm * n_left / n_left.squaredNorm();
  const Eigen::Vector3d g_right = e_norm * n_right / n_right.squaredNorm();
  const double t_left = c.dot(e) / e2, t_right = d.dot(e) / e2;
  Eigen::Matrix<double, 3, 4> g;
  g.col(0) = -(1 - t_left) * g_left - (1 - t_right) * g_right;
  g.col(1) = -t_left * g_left - t_right * g_right;
  g.col(2) = g_left;
  g.col(3) = g_right;
  return g;
}

Eigen::Matrix<double, 3, 4> hingeAngleGradientChange(const Hinge& h, const Positions& x, const Positions& v)
{
  const Eigen::Vector3d e = x.col(h.b) - x.col(h.a);
  const Eigen::Vector3d c = x.col(h.left) - x.col(h.a);
  const Eigen::Vector3d d = x.col(h.right) - x.col(h.a);
  const Eigen::Vector3d de = v.col(h.b) - v.col(h.a);
  const Eigen::Vector3d dc = v.col(h.left) - v.col(h.a);
  const Eigen::Vector3d dd = v.col(h.right) - v.col(h.a);
  const Eigen::Vector3d n_left = e.cross(c), n_right = d.cross(e);
  const Eigen::Vector3d dn_left = de.cross(c) + e.cross(dc), dn_right = dd.cross(e) + d.cross(de);
  const double e2 = e.squaredNorm(), e_norm = std::sqrt(e2), de_norm = e.dot(de) / e_norm;
  // g = |e| n / |n|² and its change, per wing.
  const auto wing = [&](const Eigen::Vector3d& n, const Eigen::Vector3d& dn, Eigen::Vector3d& g, Eigen::Vector3d& dg) {
    const double n2 = n.squaredNorm();
    g = e_norm * n / n2;
    dg = de_norm * n / n2 + e_norm * (dn / n2 - 2.0 * n.dot(dn) / (n2 * n2) * n);
  };
  Eigen::Vector3d g_left, g_right, dg_left, dg_right;
  wing(n_left, dn_left, g_left, dg_left);
  wing(n_right, dn_right, g_right, dg_right);
  const double t_left = c.dot(e) / e2, t_right = d.dot(e) / e2;
  const double dt_left = (dc.dot(e) + c.dot(de)) / e2 - 2.0 * c.dot(e) * e.dot(de) / (e2 * e2);
  const double dt_right = (dd.dot(e) + d.dot(de)) / e2 - 2.0 * d.dot(e) * e.dot(de) / (e2 * e2);
  Eigen::Matrix<double, 3, 4> out;
  out.col(0) = dt_left * g_left - (1 - t_left) * dg_left + dt_right * g_right - (1 - t_right) * dg_right;
  out.col(1) = -dt_left * g_left - t_left * dg_left - dt_right * g_right - t_right * dg_right;
  out.col(2) = dg_left;
  out.col(3) = dg_right;
  return out;
}

Eigen::Matrix3d fitFaceRotation(const RigidFace& face, const Positions& x, Eigen::Vector3d* mean_out)
{
  const Eigen::Index n = face.rest.cols();
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (int v : face.vertices)
    mean += x.col(v);
  mean /= static_cast<double>(n);
  if (mean_out)
    *mean_out = mean;
  Eigen::Matrix<double, 3, 2> m = Eigen::Matrix<double, 3, 2>::Zero();
  for (Eigen::Index k = 0; k < n; ++k)
    m += (x.col(face.vertices[k]) - mean) * face.rest.col(k).transpose();
  // q = m (mᵀm)^{-1/2}, the 2 × 2 square root in closed form: ten times cheaper than an SVD,
  // and as exact while mᵀm is far from singular; a sliver face takes the SVD (see fitRotation).
  const Eigen::Matrix2d s = m.transpose() * m;
  const double det = s.determinant(), trace = s.trace();
  Eigen::Matrix<double, 3, 2> q;
  if (det > 1e-8 * trace * trace)
  {
    const double root_det = std::sqrt(det);
    const Eigen::Matrix2d root = (s + root_det * Eigen::Matrix2d::Identity()) / std::sqrt(trace + 2 * root_det);
    q = m * root.inverse();
  }
  else
  {
    const Eigen::JacobiSVD<Eigen::Matrix<double, 3, 2>> svd(m, Eigen::ComputeFullU | Eigen::ComputeFullV);
    q = svd.matrixU().leftCols<2>() * svd.matrixV().transpose();
  }
  Eigen::Matrix3d r;
  r.col(0) = q.col(0);
  r.col(1) = q.col(1);
  r.col(2) = q.col(0).cross(q.col(1));
  return r;
}

DrivenFaces::DrivenFaces(const Paper& paper, double face_stiffness)
  : faces_(rigidFaces(paper, false)), scale_(paper.scale() > 0 ? paper.scale() : 1.0), stiffness_(face_stiffness)
{
  // Rest shapes in sheet-scale units, so that the energy is the same for any sheet size.
  std::vector<int> rigid_of_face(paper.faces.size(), -1);
  std::vector<double> size2;
  int offset = 0;
  for (size_t r = 0; r < faces_.size(); ++r)
  {
    face_offset_.push_back(offset);
    offset += static_cast<int>(faces_[r].vertices.size());
    faces_[r].rest /= scale_;
    const double s2 = faces_[r].rest.colwise().squaredNorm().mean();
    size2.push_back(s2);
    face_weight_.push_back(face_stiffness / s2);
  }
  // Each face's rigid body, among the bodies through its first vertex (a scan of every body
  // per face took a tenth of a second on a 10,000-vertex tessellation).
  std::vector<std::vector<int>> bodies_at(paper.vertices.size());
  for (size_t r = 0; r < faces_.size(); ++r)
    for (int v : faces_[r].vertices)
      bodies_at[v].push_back(static_cast<int>(r));
  for (size_t f = 0; f < paper.faces.size(); ++f)
    for (int r : bodies_at[paper.faces[f].vertices[0]])
      if (rigid_of_face[f] < 0 &&
          std::all_of(paper.faces[f].vertices.begin(), paper.faces[f].vertices.end(), [&](int v) {
            return std::find(faces_[r].vertices.begin(), faces_[r].vertices.end(), v) != faces_[r].vertices.end();
          }))
        rigid_of_face[f] = r;
  for (size_t e = 0; e < paper.edges.size(); ++e)
  {
    const Edge& edge = paper.edges[e];
    // A facet of a compliant face bends too, far softer than a crease (kFacetBending), held
    // at its own target (flat) whatever the creases are driven to.
    const bool facet = isFacet(edge);
    if (!edge.isCrease() || (edge.split && !facet))
      continue;
    Hinge h;
    h.edge = static_cast<int>(e);
    h.a = edge.vertices[0];
    h.b = edge.vertices[1];
    h.left = wingVertex(paper, edge.faces[0], h.a, h.b);
    h.right = wingVertex(paper, edge.faces[1], h.a, h.b);
    if (h.left < 0 || h.right < 0)
      continue;
    const double length = (paper.vertices[h.b].crease_pattern - paper.vertices[h.a].crease_pattern).norm() / scale_;
    const int fl = rigid_of_face[edge.faces[0]], fr = rigid_of_face[edge.faces[1]];
    const double size = 0.5 * (std::sqrt(size2[fl >= 0 ? fl : 0]) + std::sqrt(size2[fr >= 0 ? fr : 0]));
    h.weight = (facet ? kFacetBending : 1.0) * length / size;
    hinges_.push_back(h);
    facet_target_.push_back(facet ? *edge.target_angle : kNaN);
  }
  target_ = facet_target_;
  reference_.assign(paper.edges.size(), kNaN);
  for (size_t e = 0; e < paper.edges.size(); ++e)
    reference_[e] = paper.edges[e].fold_angle;
  crease_pattern_.resize(2, static_cast<Eigen::Index>(paper.vertices.size()));
  for (size_t v = 0; v < paper.vertices.size(); ++v)
    crease_pattern_.col(static_cast<Eigen::Index>(v)) = paper.vertices[v].crease_pattern / scale_;
}

void DrivenFaces::setTargets(const std::vector<double>& targets)
{
  for (size_t h = 0; h < hinges_.size(); ++h)
  {
    const size_t e = static_cast<size_t>(hinges_[h].edge);
    target_[h] = std::isfinite(facet_target_[h]) ? facet_target_[h] : e < targets.size() ? targets[e] : kNaN;
  }
}

double DrivenFaces::unwrappedAngle(const Hinge& h, const Positions& x) const
{
  return unwrapNear(hingeAngle(h, x), reference_[h.edge]);
}

std::vector<double> DrivenFaces::angles(const Positions& x) const
{
  std::vector<double> out(reference_.size(), kNaN);
  for (const Hinge& h : hinges_)
    out[h.edge] = unwrappedAngle(h, x);
  return out;
}

DrivenFaces::Evaluation DrivenFaces::evaluate(const Positions& x, Positions* gradient, Linearization* l) const
{
  Evaluation out;
  if (gradient)
    gradient->setZero(3, x.cols());
  if (l)
  {
    prepare(*l);
    l->at = x;
  }
  for (size_t f = 0; f < faces_.size(); ++f)
  {
    const RigidFace& face = faces_[f];
    Eigen::Vector3d mean;
    const Eigen::Matrix3d r = fitFaceRotation(face, x, &mean);
    if (l)
      linearizeFace(f, r, x, *l);
    for (Eigen::Index k = 0; k < face.rest.cols(); ++k)
    {
      // With R_f fitted, dE/dx_v is the weighted residual itself (the fit is stationary in R).
      const Eigen::Vector3d residual = x.col(face.vertices[k]) - mean - r.leftCols<2>() * face.rest.col(k);
      out.face_energy += 0.5 * face_weight_[f] * residual.squaredNorm();
      if (gradient)
        gradient->col(face.vertices[k]) += face_weight_[f] * residual;
    }
  }
  for (size_t i = 0; i < hinges_.size(); ++i)
  {
    if (!std::isfinite(target_[i]))
      continue;
    const Hinge& h = hinges_[i];
    const double angle = unwrappedAngle(h, x);
    const double miss = angle - target_[i];
    out.hinge_energy += 0.5 * h.weight * miss * miss;
    if (gradient || l)
    {
      const Eigen::Matrix<double, 3, 4> unit = hingeAngleGradient(h, x);
      if (l)
      {
        l->hinge_gradient.push_back(unit);
        l->hinge_miss.push_back(miss);
      }
      if (gradient)
      {
        const Eigen::Matrix<double, 3, 4> g = unit * (h.weight * miss);
        gradient->col(h.a) += g.col(0);
        gradient->col(h.b) += g.col(1);
        gradient->col(h.left) += g.col(2);
        gradient->col(h.right) += g.col(3);
      }
    }
  }
  out.energy = out.face_energy + out.hinge_energy;
  if (!std::isfinite(out.energy))
    out.energy = std::numeric_limits<double>::infinity();
  return out;
}

double DrivenFaces::hingeEnergy(const Positions& x) const
{
  double energy = 0.0;
  for (size_t i = 0; i < hinges_.size(); ++i)
    if (std::isfinite(target_[i]))
    {
      const Hinge& h = hinges_[i];
      const double miss = unwrappedAngle(h, x) - target_[i];
      energy += 0.5 * h.weight * miss * miss;
    }
  return energy;
}

Eigen::SparseMatrix<double> DrivenFaces::constantMatrix(const std::vector<int>& free_index, int free_count) const
{
  std::vector<Eigen::Triplet<double>> triplets;
  const auto add = [&](int v, int w, double value) {
    const int i = free_index[v], j = free_index[w];
    if (i >= 0 && j >= 0)
      triplets.emplace_back(i, j, value);
  };
  for (size_t f = 0; f < faces_.size(); ++f)
  {
    const std::vector<int>& vs = faces_[f].vertices;
    const double inv_n = 1.0 / static_cast<double>(vs.size());
    for (int v : vs)
      for (int w : vs)
        add(v, w, face_weight_[f] * ((v == w ? 1.0 : 0.0) - inv_n));
  }
  // A driven hinge near the flat rest state: θ ≈ Σ a_i z_i, stiffness w a aᵀ.
  Positions flat = Positions::Zero(3, crease_pattern_.cols());
  flat.topRows<2>() = crease_pattern_;
  for (size_t i = 0; i < hinges_.size(); ++i)
  {
    if (!std::isfinite(target_[i]))
      continue;
    const Hinge& h = hinges_[i];
    const Eigen::Matrix<double, 3, 4> g = hingeAngleGradient(h, flat);
    const int vs[4] = { h.a, h.b, h.left, h.right };
    for (int p = 0; p < 4; ++p)
      for (int q = 0; q < 4; ++q)
        add(vs[p], vs[q], h.weight * g(2, p) * g(2, q));
  }
  Eigen::SparseMatrix<double> m(free_count, free_count);
  m.setFromTriplets(triplets.begin(), triplets.end());
  return m;
}

Eigen::SparseMatrix<double> DrivenFaces::gaussNewtonMatrix(const Positions& x, const std::vector<int>& free_index,
                                                         int free_count) const
{
  std::vector<Eigen::Triplet<double>> triplets;
  gaussNewtonTriplets(x, free_index, triplets);
  Eigen::SparseMatrix<double> m(3 * free_count, 3 * free_count);
  m.setFromTriplets(triplets.begin(), triplets.end());
  return m;
}

void DrivenFaces::gaussNewtonTriplets(const Positions& x, const std::vector<int>& free_index,
                                      std::vector<Eigen::Triplet<double>>& triplets) const
{
  triplets.clear();
  const auto add = [&](int v, int w, const Eigen::Matrix3d& block) {
    const int i = free_index[v], j = free_index[w];
    if (i < 0 || j < 0 || i < j)
      return;  // lower triangle only
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b)
        if (3 * i + a >= 3 * j + b)
          triplets.emplace_back(3 * i + a, 3 * j + b, block(a, b));
  };
  std::vector<Eigen::Vector3d> q;
  for (size_t f = 0; f < faces_.size(); ++f)
  {
    const RigidFace& face = faces_[f];
    const size_t n = face.vertices.size();
    const Eigen::Matrix3d r = fitFaceRotation(face, x, nullptr);
    q.resize(n);
    Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();
    for (size_t k = 0; k < n; ++k)
    {
      q[k] = r.leftCols<2>() * face.rest.col(static_cast<Eigen::Index>(k));
      inertia += q[k].squaredNorm() * Eigen::Matrix3d::Identity() - q[k] * q[k].transpose();
    }
    // The face's own turn eliminated: C ⊗ I − B D⁻¹ Bᵀ, B_v = [q_v]×, D its inertia.
    const Eigen::Matrix3d inertia_inv = inertia.inverse();
    const double inv_n = 1.0 / static_cast<double>(n);
    for (size_t k = 0; k < n; ++k)
    {
      const Eigen::Matrix3d left = skew(q[k]) * inertia_inv;
      for (size_t l = 0; l < n; ++l)
      {
        Eigen::Matrix3d block = left * skew(q[l]);
        block.diagonal().array() += (k == l ? 1.0 : 0.0) - inv_n;
        add(face.vertices[k], face.vertices[l], face_weight_[f] * block);
      }
    }
  }
  for (size_t i = 0; i < hinges_.size(); ++i)
  {
    if (!std::isfinite(target_[i]))
      continue;
    const Hinge& h = hinges_[i];
    const Eigen::Matrix<double, 3, 4> g = hingeAngleGradient(h, x);
    const int vs[4] = { h.a, h.b, h.left, h.right };
    for (int p = 0; p < 4; ++p)
      for (int k = 0; k < 4; ++k)
        add(vs[p], vs[k], h.weight * g.col(p) * g.col(k).transpose());
  }
}

void DrivenFaces::prepare(Linearization& l) const
{
  const int corners = faces_.empty() ? 0 : face_offset_.back() + static_cast<int>(faces_.back().vertices.size());
  l.turned_rest.resize(3, corners);
  l.inertia_inverse.resize(faces_.size());
  l.hinge_gradient.clear();
  l.hinge_gradient.reserve(hinges_.size());
  l.frame.resize(faces_.size());
  l.stretch_inverse.resize(faces_.size());
  l.stretch_trace.resize(faces_.size());
  l.hinge_miss.clear();
  l.hinge_miss.reserve(hinges_.size());
}

void DrivenFaces::linearizeFace(size_t f, const Eigen::Matrix3d& r, const Positions& x, Linearization& l) const
{
  const RigidFace& face = faces_[f];
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();
  Eigen::Matrix<double, 3, 2> moment = Eigen::Matrix<double, 3, 2>::Zero();  // M = Σ x_v p̃_vᵀ (p̃ centred)
  for (Eigen::Index k = 0; k < face.rest.cols(); ++k)
  {
    const Eigen::Vector3d q = r.leftCols<2>() * face.rest.col(k);
    l.turned_rest.col(face_offset_[f] + k) = q;
    inertia += q.squaredNorm() * Eigen::Matrix3d::Identity() - q * q.transpose();
    moment += x.col(face.vertices[k]) * face.rest.col(k).transpose();
  }
  l.inertia_inverse[f] = inertia.inverse();
  l.frame[f] = r.leftCols<2>();
  Eigen::Matrix2d stretch = l.frame[f].transpose() * moment;
  stretch = 0.5 * (stretch + stretch.transpose()).eval();
  const double trace = stretch.trace();
  const bool regular = trace > 0 && stretch.determinant() > 1e-4 * trace * trace;
  l.stretch_trace[f] = regular ? trace : 0.0;
  l.stretch_inverse[f] = regular ? Eigen::Matrix2d(stretch.inverse()) : Eigen::Matrix2d::Zero();
}

DrivenFaces::Linearization DrivenFaces::linearize(const Positions& x) const
{
  Linearization l;
  prepare(l);
  for (size_t f = 0; f < faces_.size(); ++f)
    linearizeFace(f, fitFaceRotation(faces_[f], x, nullptr), x, l);
  for (size_t i = 0; i < hinges_.size(); ++i)
    if (std::isfinite(target_[i]))
    {
      const Hinge& h = hinges_[i];
      l.hinge_gradient.push_back(hingeAngleGradient(h, x));
      l.hinge_miss.push_back(unwrappedAngle(h, x) - target_[i]);
    }
  l.at = x;
  return l;
}

void DrivenFaces::addFaceGaussNewtonProduct(size_t f, const Linearization& l, const Positions& v, Positions& out) const
{
  const std::vector<int>& vs = faces_[f].vertices;
  const auto q = l.turned_rest.middleCols(face_offset_[f], static_cast<Eigen::Index>(vs.size()));
  Eigen::Vector3d turn = Eigen::Vector3d::Zero(), mean = Eigen::Vector3d::Zero();
  for (size_t k = 0; k < vs.size(); ++k)
  {
    turn += q.col(static_cast<Eigen::Index>(k)).cross(v.col(vs[k]));
    mean += v.col(vs[k]);
  }
  mean /= static_cast<double>(vs.size());
  // Σ_l block(k, l) v_l = v_k − mean + q_k × (D⁻¹ Σ_l q_l × v_l), the face's turn taken out.
  const Eigen::Vector3d spin = l.inertia_inverse[f] * turn;
  for (size_t k = 0; k < vs.size(); ++k)
    out.col(vs[k]) += face_weight_[f] * (v.col(vs[k]) - mean + q.col(static_cast<Eigen::Index>(k)).cross(spin));
}

void DrivenFaces::gaussNewtonProduct(const Linearization& l, const Positions& v, Positions& out) const
{
  out.setZero(3, v.cols());
  for (size_t f = 0; f < faces_.size(); ++f)
    addFaceGaussNewtonProduct(f, l, v, out);
  addHingeProducts(l, v, false, out);
}

void DrivenFaces::addHingeProducts(const Linearization& l, const Positions& v, bool curvature, Positions& out) const
{
  size_t driven = 0;
  for (size_t i = 0; i < hinges_.size(); ++i)
  {
    if (!std::isfinite(target_[i]))
      continue;
    const Hinge& h = hinges_[i];
    const size_t k = driven++;
    const Eigen::Matrix<double, 3, 4>& g = l.hinge_gradient[k];
    const int vs[4] = { h.a, h.b, h.left, h.right };
    double along = 0.0;
    for (int p = 0; p < 4; ++p)
      along += g.col(p).dot(v.col(vs[p]));
    if (curvature)
    {
      const Eigen::Matrix<double, 3, 4> change = hingeAngleGradientChange(h, l.at, v);
      for (int p = 0; p < 4; ++p)
        out.col(vs[p]) += h.weight * (along * g.col(p) + l.hinge_miss[k] * change.col(p));
    }
    else
      for (int p = 0; p < 4; ++p)
        out.col(vs[p]) += h.weight * along * g.col(p);
  }
}

void DrivenFaces::hessianProduct(const Linearization& l, const Positions& v, Positions& out) const
{
  out.setZero(3, v.cols());
  for (size_t f = 0; f < faces_.size(); ++f)
  {
    const double trace = l.stretch_trace[f];
    if (!(trace > 0))
    {
      // A sliver face: its polar factor has no derivative; turned as a rigid body instead.
      addFaceGaussNewtonProduct(f, l, v, out);
      continue;
    }
    const RigidFace& face = faces_[f];
    const std::vector<int>& vs = face.vertices;
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    for (int w : vs)
      mean += v.col(w);
    mean /= static_cast<double>(vs.size());
    // The face's gradient is w (x_v − x̄ − Q p̃_v) with Q the polar factor of M = Σ x_v p̃_vᵀ;
    // M = Q S gives dQ = Q Ω + (I − Q Qᵀ) dM S⁻¹, with Ω = ω J skew and
    // ω tr S = (QᵀdM)₀₁ − (QᵀdM)₁₀.
    Eigen::Matrix<double, 3, 2> moment = Eigen::Matrix<double, 3, 2>::Zero();
    for (size_t k = 0; k < vs.size(); ++k)
      moment += v.col(vs[k]) * face.rest.col(static_cast<Eigen::Index>(k)).transpose();
    const Eigen::Matrix<double, 3, 2>& q = l.frame[f];
    const Eigen::Matrix2d a = q.transpose() * moment;
    const double spin = (a(0, 1) - a(1, 0)) / trace;
    Eigen::Matrix<double, 3, 2> frame_change = (moment - q * a) * l.stretch_inverse[f];
    frame_change.col(0) -= spin * q.col(1);
    frame_change.col(1) += spin * q.col(0);
    for (size_t k = 0; k < vs.size(); ++k)
      out.col(vs[k]) +=
          face_weight_[f] * (v.col(vs[k]) - mean - frame_change * face.rest.col(static_cast<Eigen::Index>(k)));
  }
  addHingeProducts(l, v, true, out);
}

}  // namespace virtual_origami::core

#include "virtual_origami/curved/barrier_contact.h"

#include <CGAL/Bbox_3.h>
#include <CGAL/box_intersection_d.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "virtual_origami/curved/mesh_distance.h"

namespace virtual_origami::core
{
namespace
{
using Box = CGAL::Box_intersection_d::Box_with_handle_d<double, 3, const int*, CGAL::Box_intersection_d::ID_FROM_HANDLE>;

/// A pair's distance and its gradient with respect to the pair's four nodes.
struct Closest
{
  double distance = 0.0;
  Eigen::Matrix<double, 3, 4> gradient;
};

/// The distance from p to triangle abc and its gradient.
Closest pointTriangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c)
{
  const Vec3 w = nearestOnTriangle(p, a, b, c);
  const Vec3 offset = p - (w.x() * a + w.y() * b + w.z() * c);
  Closest r;
  r.distance = offset.norm();
  const Vec3 n = r.distance > 0 ? Vec3(offset / r.distance) : Vec3::Zero();
  r.gradient << n, -w.x() * n, -w.y() * n, -w.z() * n;
  return r;
}

/// The distance between segments pq and rs and its gradient.
Closest edgeEdge(const Vec3& p, const Vec3& q, const Vec3& r, const Vec3& s)
{
  const Vec2 t = nearestOnSegments(p, q, r, s);
  const double u = t.x(), v = t.y();
  const Vec3 offset = (p + u * (q - p)) - (r + v * (s - r));
  Closest result;
  result.distance = offset.norm();
  const Vec3 n = result.distance > 0 ? Vec3(offset / result.distance) : Vec3::Zero();
  result.gradient << (1 - u) * n, u * n, -(1 - v) * n, -v * n;
  return result;
}

Closest measure(char kind, const Positions& x, const std::array<int, 4>& n)
{
  return kind == 0 ? pointTriangle(x.col(n[0]), x.col(n[1]), x.col(n[2]), x.col(n[3])) :
                     edgeEdge(x.col(n[0]), x.col(n[1]), x.col(n[2]), x.col(n[3]));
}

/// The coefficients k0 + k1·t + k2·t² + k3·t³ of (u × v) · w along a linear motion of the three.
std::array<double, 4> coplanarity(const Vec3& u0, const Vec3& u1, const Vec3& v0, const Vec3& v1, const Vec3& w0,
                                  const Vec3& w1)
{
  const Vec3 n0 = u0.cross(v0), n1 = u0.cross(v1) + u1.cross(v0), n2 = u1.cross(v1);
  return { n0.dot(w0), n0.dot(w1) + n1.dot(w0), n1.dot(w1) + n2.dot(w0), n2.dot(w1) };
}

double cubic(const std::array<double, 4>& k, double t)
{
  return ((k[3] * t + k[2]) * t + k[1]) * t + k[0];
}

/// The first t in [0, 1] at which the four points are coplanar and `meets(t)` says they touch
/// there; 2 when none. The cubic is split where its slope changes sign, and each sign change
/// found by bisection; where it barely leaves zero (the motion keeps them in one plane) the
/// times are sampled instead.
template <class Meets>
double firstImpact(const std::array<double, 4>& k, double size, Meets&& meets)
{
  const double largest = std::max({ std::abs(k[0]), std::abs(k[1]), std::abs(k[2]), std::abs(k[3]) });
  if (!(largest > 1e-30 * size))
  {
    for (int i = 0; i <= 16; ++i)
      if (meets(i / 16.0))
        return i / 16.0;
    return 2.0;
  }
  std::vector<double> ends{ 0.0 };
  // f'(t) = 3 k3 t² + 2 k2 t + k1.
  const double qa = 3 * k[3], qb = 2 * k[2], qc = k[1];
  if (std::abs(qa) > 1e-300)
  {
    const double disc = qb * qb - 4 * qa * qc;
    if (disc >= 0)
    {
      const double root = std::sqrt(disc);
      const double q = -0.5 * (qb + (qb >= 0 ? root : -root));
      for (double t : { q / qa, q != 0 ? qc / q : -1.0 })
        if (t > 0 && t < 1)
          ends.push_back(t);
    }
  }
  else if (std::abs(qb) > 1e-300)
  {
    const double t = -qc / qb;
    if (t > 0 && t < 1)
      ends.push_back(t);
  }
  ends.push_back(1.0);
  std::sort(ends.begin(), ends.end());
  for (size_t i = 0; i + 1 < ends.size(); ++i)
  {
    double lo = ends[i], hi = ends[i + 1];
    double f_lo = cubic(k, lo);
    const double f_hi = cubic(k, hi);
    if (f_lo == 0.0 || std::abs(f_lo) < 1e-14 * largest)
    {
      if (meets(lo))
        return lo;
      continue;
    }
    if ((f_lo > 0) == (f_hi > 0) && f_hi != 0.0)
    {
      if (std::abs(f_hi) < 1e-14 * largest && meets(hi))
        return hi;
      continue;
    }
    for (int it = 0; it < 100 && hi - lo > 1e-16; ++it)
    {
      const double mid = 0.5 * (lo + hi);
      const double f_mid = cubic(k, mid);
      if ((f_mid > 0) == (f_lo > 0) && f_mid != 0.0)
        lo = mid, f_lo = f_mid;
      else
        hi = mid;
    }
    if (meets(hi))
      return hi;
  }
  return 2.0;
}
}  // namespace

double pointTriangleImpact(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& dp, const Vec3& da,
                           const Vec3& db, const Vec3& dc, double tolerance)
{
  const std::array<double, 4> k = coplanarity(b - a, db - da, c - a, dc - da, p - a, dp - da);
  const double size = std::pow(std::max({ (b - a).norm(), (c - a).norm(), (p - a).norm(), 1e-300 }), 3);
  return firstImpact(k, size, [&](double t) {
    return pointTriangle(p + t * dp, a + t * da, b + t * db, c + t * dc).distance <= tolerance;
  });
}

double edgeEdgeImpact(const Vec3& p, const Vec3& q, const Vec3& r, const Vec3& s, const Vec3& dp, const Vec3& dq,
                      const Vec3& dr, const Vec3& ds, double tolerance)
{
  const std::array<double, 4> k = coplanarity(q - p, dq - dp, s - r, ds - dr, r - p, dr - dp);
  const double size = std::pow(std::max({ (q - p).norm(), (s - r).norm(), (r - p).norm(), 1e-300 }), 3);
  return firstImpact(k, size, [&](double t) {
    return edgeEdge(p + t * dp, q + t * dq, r + t * dr, s + t * ds).distance <= tolerance;
  });
}

BarrierContact::BarrierContact(const CurvedMesh& mesh, const BarrierContactOptions& options)
  : mesh_(mesh)
  , activation_(options.activation > 0 ? options.activation : 1e-2 * mesh.spacing)
  , stiffness_(options.stiffness)
{
}

void BarrierContact::setPush(double force)
{
  // |b'(d̂/2)| = d̂·(ln 2 + ½).
  stiffness_ = force / ((std::log(2.0) + 0.5) * activation_);
}

template <class F>
void BarrierContact::forPairs(const Positions& x, const Positions* motion, double reach, F&& f) const
{
  auto bounds = [&](std::initializer_list<int> nodes, double grow) {
    CGAL::Bbox_3 box;
    for (int v : nodes)
    {
      const Vec3 p = x.col(v);
      box += CGAL::Bbox_3(p.x(), p.y(), p.z(), p.x(), p.y(), p.z());
      if (motion)
      {
        const Vec3 q = p + motion->col(v);
        box += CGAL::Bbox_3(q.x(), q.y(), q.z(), q.x(), q.y(), q.z());
      }
    }
    return CGAL::Bbox_3(box.xmin() - grow, box.ymin() - grow, box.zmin() - grow, box.xmax() + grow,
                        box.ymax() + grow, box.zmax() + grow);
  };
  const int node_count = static_cast<int>(mesh_.nodes.size());
  const int triangle_count = static_cast<int>(mesh_.triangles.size());
  const int edge_count = static_cast<int>(mesh_.edges.size());
  // Each box its own handle (CGAL tells boxes apart by their handles' addresses): node v at
  // ids[v], triangle t at ids[node_count + t], both holding their own index.
  std::vector<int> ids(node_count + std::max(triangle_count, edge_count));
  for (int i = 0; i < node_count; ++i)
    ids[i] = i;
  for (size_t i = node_count; i < ids.size(); ++i)
    ids[i] = static_cast<int>(i) - node_count;

  std::vector<Box> nodes, triangles, edges;
  nodes.reserve(node_count);
  for (int v = 0; v < node_count; ++v)
    nodes.emplace_back(bounds({ v }, 0.0), &ids[v]);
  triangles.reserve(triangle_count);
  for (int t = 0; t < triangle_count; ++t)
  {
    const auto& n = mesh_.triangles[t].nodes;
    triangles.emplace_back(bounds({ n[0], n[1], n[2] }, reach), &ids[node_count + t]);
  }
  CGAL::box_intersection_d(
      nodes.begin(), nodes.end(), triangles.begin(), triangles.end(),
      [&](const Box& a, const Box& b) {
        // Which is the node: its handle lies below the triangles' in `ids`.
        const bool a_is_node = a.handle() < ids.data() + node_count;
        const int v = *(a_is_node ? a : b).handle();
        const auto& n = mesh_.triangles[*(a_is_node ? b : a).handle()].nodes;
        if (v == n[0] || v == n[1] || v == n[2])
          return;
        f(char(0), std::array<int, 4>{ v, n[0], n[1], n[2] });
      },
      std::ptrdiff_t(10), CGAL::Box_intersection_d::CLOSED);

  edges.reserve(edge_count);
  for (int e = 0; e < edge_count; ++e)
  {
    const auto& n = mesh_.edges[e].nodes;
    edges.emplace_back(bounds({ n[0], n[1] }, 0.5 * reach), &ids[node_count + e]);
  }
  CGAL::box_self_intersection_d(
      edges.begin(), edges.end(),
      [&](const Box& a, const Box& b) {
        int i = *a.handle(), j = *b.handle();
        if (i > j)
          std::swap(i, j);
        const auto& p = mesh_.edges[i].nodes;
        const auto& q = mesh_.edges[j].nodes;
        if (p[0] == q[0] || p[0] == q[1] || p[1] == q[0] || p[1] == q[1])
          return;
        f(char(1), std::array<int, 4>{ p[0], p[1], q[0], q[1] });
      },
      std::ptrdiff_t(10), CGAL::Box_intersection_d::CLOSED);
}

void BarrierContact::update(const Positions& x, const Positions* motion, double reach)
{
  pairs_.clear();
  kinds_.clear();
  reach_.clear();
  forPairs(x, motion, std::max(reach, activation_), [&](char kind, const std::array<int, 4>& n) {
    double own = activation_;
    if (!near_start_.empty())
      if (const auto found = near_start_.find({ kind, n[0], n[1], n[2], n[3] }); found != near_start_.end())
      {
        if (!(found->second > 1e-6 * activation_))
          return;
        own = found->second;
      }
    pairs_.push_back(n);
    kinds_.push_back(kind);
    reach_.push_back(own);
  });
}

void BarrierContact::guardNearPairs(const Positions& x, double distance)
{
  forPairs(x, nullptr, distance, [&](char kind, const std::array<int, 4>& n) {
    if (const double d = measure(kind, x, n).distance; d < distance)
      near_start_.emplace(std::array<int, 5>{ kind, n[0], n[1], n[2], n[3] }, d);
  });
}

double BarrierContact::evaluate(const Positions& x, const Assembly& out) const
{
  double energy = 0.0;
  for (size_t k = 0; k < pairs_.size(); ++k)
  {
    const Closest c = measure(kinds_[k], x, pairs_[k]);
    const double reach = reach_[k];
    if (c.distance >= reach)
      continue;
    if (!(c.distance > 0))
      return std::numeric_limits<double>::infinity();
    // κ scaled so that a pair with a shorter reach pushes alike at the same share of it.
    const double kappa = stiffness_ * activation_ / reach;
    const double d = c.distance, gap = d - reach, log = std::log(d / reach);
    const double b = -gap * gap * log;
    const double db = -2 * gap * log - gap * gap / d;
    const double ddb = -2 * log - 4 * gap / d + gap * gap / (d * d);
    energy += kappa * b;
    addGradient<4>(pairs_[k], Eigen::Matrix<double, 3, 4>(kappa * db * c.gradient), out);
    if (out.wantsHessian())
    {
      // The barrier's curvature along the distance's gradient: positive; the distance's own
      // curvature, multiplied by a negative slope, is left out (the Hessian stays semidefinite).
      const Eigen::Map<const Eigen::Matrix<double, 12, 1>> g(c.gradient.data());
      addHessian<4>(pairs_[k], Eigen::Matrix<double, 12, 12>(kappa * ddb * g * g.transpose()), out);
    }
  }
  return energy;
}

double BarrierContact::safeStep(const Positions& x, const Positions& motion, double separation) const
{
  double first = 2.0;
  for (size_t k = 0; k < pairs_.size(); ++k)
  {
    const std::array<int, 4>& n = pairs_[k];
    const double tolerance = separation * measure(kinds_[k], x, n).distance;
    const double t = kinds_[k] == 0 ?
                         pointTriangleImpact(x.col(n[0]), x.col(n[1]), x.col(n[2]), x.col(n[3]), motion.col(n[0]),
                                             motion.col(n[1]), motion.col(n[2]), motion.col(n[3]), tolerance) :
                         edgeEdgeImpact(x.col(n[0]), x.col(n[1]), x.col(n[2]), x.col(n[3]), motion.col(n[0]),
                                        motion.col(n[1]), motion.col(n[2]), motion.col(n[3]), tolerance);
    first = std::min(first, t);
  }
  return first > 1.0 ? 1.0 : 0.9 * first;
}

int BarrierContact::activePairs(const Positions& x) const
{
  int count = 0;
  for (size_t k = 0; k < pairs_.size(); ++k)
    count += measure(kinds_[k], x, pairs_[k]).distance < reach_[k] ? 1 : 0;
  return count;
}

double BarrierContact::minimumDistance(const Positions& x) const
{
  double nearest = std::numeric_limits<double>::infinity();
  for (size_t k = 0; k < pairs_.size(); ++k)
    nearest = std::min(nearest, measure(kinds_[k], x, pairs_[k]).distance);
  return nearest;
}

}  // namespace virtual_origami::core

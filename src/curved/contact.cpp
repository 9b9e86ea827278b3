#include "virtual_origami/curved/contact.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <unordered_map>

#include "virtual_origami/core/planar_geometry.h"

namespace virtual_origami::core
{
namespace
{
/// Mesh elements (triangles or edges) binned by their bounding boxes, grown by `margin`, in
/// cubic cells: an array of the cells over the elements' extent (a lookup is an index, not a
/// hash: a search visits millions of cells), or a hash of the occupied ones where that array
/// would be much larger than the elements (a sheet spread far apart). Either visits the same
/// elements in the same order.
class ElementGrid
{
public:
  ElementGrid(const CurvedMesh& mesh, const Positions& x, double cell, double margin)
    : ElementGrid(mesh.triangles.size(), x, cell, margin, [&](size_t t) { return mesh.triangles[t].nodes; })
  {
  }

  template <class Nodes>
  ElementGrid(size_t count, const Positions& x, double cell, double margin, Nodes nodes_of) : cell_(cell)
  {
    std::vector<std::array<long, 3>> first(count), last(count);
    std::array<long, 3> low{ 0, 0, 0 }, high{ -1, -1, -1 };
    for (size_t t = 0; t < count; ++t)
    {
      const auto nodes = nodes_of(t);
      Vec3 lo = x.col(nodes[0]), hi = lo;
      for (int n : nodes)
      {
        lo = lo.cwiseMin(x.col(n));
        hi = hi.cwiseMax(x.col(n));
      }
      first[t] = key(lo - Vec3::Constant(margin));
      last[t] = key(hi + Vec3::Constant(margin));
      for (int axis = 0; axis < 3; ++axis)
      {
        low[axis] = t == 0 ? first[t][axis] : std::min(low[axis], first[t][axis]);
        high[axis] = t == 0 ? last[t][axis] : std::max(high[axis], last[t][axis]);
      }
    }
    double cells = 1.0;
    for (int axis = 0; axis < 3; ++axis)
      cells *= static_cast<double>(high[axis] - low[axis] + 1);
    dense_ = count > 0 && cells <= 16.0 * static_cast<double>(count) + 4096.0;
    if (dense_)
    {
      low_ = low;
      for (int axis = 0; axis < 3; ++axis)
        size_[axis] = high[axis] - low[axis] + 1;
      // Two passes: the count per cell, then the elements in order (a cell's list ascending).
      start_.assign(static_cast<size_t>(cells) + 1, 0);
      for (size_t t = 0; t < count; ++t)
        forCells(first[t], last[t], [&](size_t c) { ++start_[c + 1]; });
      for (size_t c = 1; c < start_.size(); ++c)
        start_[c] += start_[c - 1];
      entries_.resize(start_.back());
      std::vector<int> filled(start_.begin(), start_.end() - 1);
      for (size_t t = 0; t < count; ++t)
        forCells(first[t], last[t], [&](size_t c) { entries_[filled[c]++] = static_cast<int>(t); });
      return;
    }
    for (size_t t = 0; t < count; ++t)
      for (long i = first[t][0]; i <= last[t][0]; ++i)
        for (long j = first[t][1]; j <= last[t][1]; ++j)
          for (long k = first[t][2]; k <= last[t][2]; ++k)
            cells_[{ i, j, k }].push_back(static_cast<int>(t));
  }

  /// The triangles in the cells a box touches (each once per call, via `stamp`).
  template <class Visit>
  void near(const Vec3& lo, const Vec3& hi, std::vector<int>& stamp, int mark, Visit visit) const
  {
    const auto a = key(lo), b = key(hi);
    const auto visitAll = [&](const int* begin, const int* end) {
      for (const int* t = begin; t != end; ++t)
        if (stamp[*t] != mark)
        {
          stamp[*t] = mark;
          visit(*t);
        }
    };
    if (dense_)
    {
      // Cells beyond the array hold nothing.
      std::array<long, 3> from, to;
      for (int axis = 0; axis < 3; ++axis)
      {
        from[axis] = std::max(a[axis], low_[axis]);
        to[axis] = std::min(b[axis], low_[axis] + size_[axis] - 1);
      }
      for (long i = from[0]; i <= to[0]; ++i)
        for (long j = from[1]; j <= to[1]; ++j)
          for (long k = from[2]; k <= to[2]; ++k)
          {
            const size_t c = index(i, j, k);
            visitAll(entries_.data() + start_[c], entries_.data() + start_[c + 1]);
          }
      return;
    }
    for (long i = a[0]; i <= b[0]; ++i)
      for (long j = a[1]; j <= b[1]; ++j)
        for (long k = a[2]; k <= b[2]; ++k)
        {
          const auto it = cells_.find({ i, j, k });
          if (it != cells_.end())
            visitAll(it->second.data(), it->second.data() + it->second.size());
        }
  }

private:
  struct KeyHash
  {
    size_t operator()(const std::array<long, 3>& k) const
    {
      return static_cast<size_t>(k[0] * 73856093L ^ k[1] * 19349663L ^ k[2] * 83492791L);
    }
  };
  std::array<long, 3> key(const Vec3& p) const
  {
    return { static_cast<long>(std::floor(p.x() / cell_)), static_cast<long>(std::floor(p.y() / cell_)),
             static_cast<long>(std::floor(p.z() / cell_)) };
  }
  size_t index(long i, long j, long k) const
  {
    return static_cast<size_t>(((i - low_[0]) * size_[1] + (j - low_[1])) * size_[2] + (k - low_[2]));
  }
  template <class Each>
  void forCells(const std::array<long, 3>& a, const std::array<long, 3>& b, Each each) const
  {
    for (long i = a[0]; i <= b[0]; ++i)
      for (long j = a[1]; j <= b[1]; ++j)
        for (long k = a[2]; k <= b[2]; ++k)
          each(index(i, j, k));
  }
  double cell_;
  bool dense_ = false;
  std::array<long, 3> low_{ 0, 0, 0 }, size_{ 0, 0, 0 };
  std::vector<int> start_, entries_;  // dense: cell c's elements are entries_[start_[c]..start_[c + 1])
  std::unordered_map<std::array<long, 3>, std::vector<int>, KeyHash> cells_;
};

/// The gap between two axis-aligned boxes along the axis where it is widest (0 when they overlap).
double boxGap(const Vec3& lo_a, const Vec3& hi_a, const Vec3& lo_b, const Vec3& hi_b)
{
  return std::max(0.0, std::max((lo_b - hi_a).maxCoeff(), (lo_a - hi_b).maxCoeff()));
}

template <class Nodes>
void boundsOf(const Nodes& nodes, const Positions& x, Vec3& lo, Vec3& hi)
{
  lo = hi = x.col(nodes[0]);
  for (int n : nodes)
  {
    lo = lo.cwiseMin(x.col(n));
    hi = hi.cwiseMax(x.col(n));
  }
}

/// Unit normal of a triangle and the affine coordinates of `p`'s projection onto its plane.
struct Projection
{
  Vec3 normal = Vec3::Zero();
  std::array<double, 3> weights{ 0, 0, 0 };
  double distance = 0.0;  // signed, along the normal
  double area = 0.0;
  bool valid = false;
};

Projection project(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& p)
{
  Projection r;
  const Vec3 area = (b - a).cross(c - a);
  const double twice = area.norm();
  if (!(twice > 0))
    return r;
  r.normal = area / twice;
  r.area = twice / 2;
  r.distance = r.normal.dot(p - a);
  const Vec3 q = p - r.distance * r.normal;
  r.weights[0] = r.normal.dot((b - q).cross(c - q)) / twice;
  r.weights[1] = r.normal.dot((c - q).cross(a - q)) / twice;
  r.weights[2] = 1.0 - r.weights[0] - r.weights[1];
  r.valid = true;
  return r;
}

/// Distance in the crease pattern from a point to a triangle.
double patternDistance(const CurvedMesh& mesh, int triangle, const Vec2& p)
{
  const auto& t = mesh.triangles[triangle].nodes;
  double inside = std::numeric_limits<double>::infinity();
  double nearest = std::numeric_limits<double>::infinity();
  for (int k = 0; k < 3; ++k)
  {
    const Vec2& a = mesh.nodes[t[k]].crease_pattern;
    const Vec2& b = mesh.nodes[t[(k + 1) % 3]].crease_pattern;
    nearest = std::min(nearest, pointSegmentDistance(p, a, b));
    inside = std::min(inside, cross2(b - a, p - a));
  }
  return inside >= 0 ? 0.0 : nearest;
}

/// The crossing of two edges p1p2 and q1q2, seen along n = (p2 − p1) × (q2 − q1): the signed
/// distance g = n·(p1 − q1) of their lines and the parameters of their closest points, which
/// also weigh the derivatives: ∂g/∂p1 = (1 − s)n, ∂g/∂p2 = s n, ∂g/∂q1 = −(1 − t)n, ∂g/∂q2 = −t n.
struct Crossing
{
  Vec3 normal = Vec3::Zero();
  double distance = 0.0, s = 0.0, t = 0.0;
  bool valid = false;  // not near parallel
};

Crossing cross(const Vec3& p1, const Vec3& p2, const Vec3& q1, const Vec3& q2)
{
  Crossing c;
  const Vec3 e1 = p2 - p1, e2 = q2 - q1, r = p1 - q1;
  const Vec3 n = e1.cross(e2);
  const double a = e1.squaredNorm(), b = e1.dot(e2), cc = e2.squaredNorm();
  // Nearly parallel edges have no stable crossing direction; node–triangle pairs hold them.
  if (!(n.squaredNorm() > 0.04 * a * cc))
    return c;
  c.normal = n.normalized();
  c.distance = c.normal.dot(r);
  const double d = e1.dot(r), e = e2.dot(r), den = a * cc - b * b;
  c.s = (b * e - cc * d) / den;
  c.t = (a * e - b * d) / den;
  c.valid = true;
  return c;
}

double segmentDistance2d(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d)
{
  return std::min({ pointSegmentDistance(a, c, d), pointSegmentDistance(b, c, d), pointSegmentDistance(c, a, b),
                    pointSegmentDistance(d, a, b) });
}
}  // namespace

int layerSide(const Paper& paper, int a, int b)
{
  for (const FaceOrder& o : paper.face_orders)
  {
    if (o.above == 0)
      continue;
    if (o.face == b && o.other == a)
      return o.above > 0 ? 1 : -1;
    if (o.face == a && o.other == b)
    {
      // b is on side `above` of a's front, so a is on the other side of a's front; turn that
      // into b's front.
      const double facing = paper.faceNormal(a).dot(paper.faceNormal(b));
      return (o.above > 0 ? -1 : 1) * (facing >= 0 ? 1 : -1);
    }
  }
  for (int e : paper.faces[a].edges)
  {
    const Edge& edge = paper.edges[e];
    if (edge.isCrease() && edge.otherFace(a) == b && std::abs(edge.fold_angle) > M_PI - 1e-3)
      return edge.fold_angle > 0 ? 1 : -1;  // valley: the fronts turn to face each other
  }
  return 0;
}

LayerContact::LayerContact(const CurvedMesh& mesh, const Paper& paper, const CurvedMaterial& material,
                           const ContactOptions& options)
  : mesh_(mesh)
  , paper_(paper)
  , thickness_(options.thickness > 0 ? options.thickness : 1e-3 * paper.scale())
  , stiffness_(options.stiffness > 0 ? options.stiffness : 10 * material.stretch / mesh.spacing)
  , range_(options.range > 0 ? options.range : mesh.spacing)
  , exclusion_(std::max(0.0, options.exclusion))
  , edge_margin_(options.edge_margin > 0 ? options.edge_margin : 0.5 * mesh.spacing)
  , skin_(range_)
{
  open_side_.assign(mesh.triangles.size(), { 0, 0, 0 });
  for (const MeshEdge& e : mesh.edges)
  {
    if (e.isHinge())
      continue;
    const int t = e.triangles[0] >= 0 ? e.triangles[0] : e.triangles[1];
    for (int k = 0; k < 3; ++k)
      if (mesh.triangles[t].nodes[k] != e.nodes[0] && mesh.triangles[t].nodes[k] != e.nodes[1])
        open_side_[t][k] = 1;
  }
  edge_face_.assign(mesh.edges.size(), -1);
  edge_middle_.resize(mesh.edges.size());
  for (size_t e = 0; e < mesh.edges.size(); ++e)
  {
    const MeshEdge& edge = mesh.edges[e];
    edge_middle_[e] = 0.5 * (mesh.nodes[edge.nodes[0]].crease_pattern + mesh.nodes[edge.nodes[1]].crease_pattern);
    const int t0 = edge.triangles[0], t1 = edge.triangles[1];
    const int f0 = t0 >= 0 ? mesh.triangles[t0].face : -1, f1 = t1 >= 0 ? mesh.triangles[t1].face : -1;
    edge_face_[e] = f0 < 0 ? f1 : (f1 < 0 || f1 == f0 ? f0 : -1);
  }
  node_faces_ = mesh.facesOfNodes(paper);
}

int LayerContact::sideFor(int node, int triangle, double signed_distance) const
{
  if (std::abs(signed_distance) > 0.5 * thickness_)
    return signed_distance > 0 ? 1 : -1;
  for (int a : node_faces_[node])
    if (const int side = layerSide(paper_, a, mesh_.triangles[triangle].face); side != 0)
      return side;
  if (std::abs(signed_distance) > 1e-12 * paper_.scale())
    return signed_distance > 0 ? 1 : -1;
  return 0;  // coincident with no order known: left alone until they part
}

int LayerContact::edgeSideFor(int a, int b, double signed_distance, const Vec3& normal, const Positions& x) const
{
  if (std::abs(signed_distance) > 0.5 * thickness_)
    return signed_distance > 0 ? 1 : -1;
  for (int ta : mesh_.edges[a].triangles)
    for (int tb : mesh_.edges[b].triangles)
    {
      if (ta < 0 || tb < 0)
        continue;
      const int side = layerSide(paper_, mesh_.triangles[ta].face, mesh_.triangles[tb].face);
      if (side == 0)
        continue;
      // The order is along b's front normal; turn it into `normal`.
      const auto& t = mesh_.triangles[tb].nodes;
      const Vec3 front = (x.col(t[1]) - x.col(t[0])).cross(x.col(t[2]) - x.col(t[0]));
      return front.dot(normal) >= 0 ? side : -side;
    }
  if (std::abs(signed_distance) > 1e-12 * paper_.scale())
    return signed_distance > 0 ? 1 : -1;
  return 0;
}

void LayerContact::findCandidates(const Positions& x)
{
  Candidates found = candidatesAt(x);
  candidates_ = std::move(found.nodes);
  edge_candidates_ = std::move(found.edges);
  candidates_at_ = std::move(found.at);
}

bool LayerContact::needsSearch(const Positions& x) const
{
  return !(skinUsed(x) <= 1.0);
}

double LayerContact::skinUsed(const Positions& x) const
{
  return skinUsedFrom(candidates_at_, x);
}

double LayerContact::skinUsedFrom(const Positions& at, const Positions& x) const
{
  if (at.cols() != x.cols() || at.cols() == 0)
    return INFINITY;
  // Every test of the search is unchanged by a translation of the whole sheet: what uses up
  // the skin is how far the nodes moved apart, the largest distance of a node's motion from a
  // common one (the middle of their range, per axis: a sheet carried along searches no more).
  const Positions moved = x - at;
  const Vec3 common = 0.5 * (moved.rowwise().minCoeff() + moved.rowwise().maxCoeff());
  return std::sqrt((moved.colwise() - common).colwise().squaredNorm().maxCoeff()) / (0.5 * skin_);
}

bool LayerContact::adoptCandidates(Candidates&& found, const Positions& x)
{
  if (found.at.cols() != x.cols())
    return false;
  // Taken when good for x and fresher than the kept ones (nearer x: longer until a search).
  const double found_used = skinUsedFrom(found.at, x);
  if (!(found_used <= 1.0) || !(found_used < skinUsed(x)))
    return false;
  candidates_ = std::move(found.nodes);
  edge_candidates_ = std::move(found.edges);
  candidates_at_ = std::move(found.at);
  return true;
}

LayerContact::Candidates LayerContact::candidatesAt(const Positions& x) const
{
  Candidates found;
  // Every element pair whose boxes come within reach + edge margin + skin, less those the rules below never
  // watch whatever the shape (a node's own triangles, neighbours within the exclusion, edges
  // sharing a node): while no node moves farther than half the skin, every pair that comes
  // within reach is among them. Nor are two parts of one face nearer on the paper than the
  // farthest two boxes that gap can hold (√3 of it): to come within reach of each other the
  // face would have to loop back on itself within about four mesh spacings, some 80° on each
  // hinge, a bend its mesh does not resolve. On a flat or gently bent sheet those are nearly
  // all the pairs the boxes find, and watching them made each update cost more than the
  // forces.
  const double reach = thickness_ + range_;
  const double wide = reach + edge_margin_ + skin_;
  const double one_face = std::sqrt(3.0) * wide;
  const ElementGrid grid(mesh_, x, std::max(wide, mesh_.spacing), wide);
  std::vector<int> stamp(mesh_.triangles.size(), -1);
  Vec3 lo, hi;
  for (size_t i = 0; i < mesh_.nodes.size(); ++i)
  {
    const int node = static_cast<int>(i);
    const Vec3 p = x.col(node);
    const Vec2& at = mesh_.nodes[node].crease_pattern;
    grid.near(p, p, stamp, node, [&](int t) {
      const auto& tri = mesh_.triangles[t].nodes;
      if (tri[0] == node || tri[1] == node || tri[2] == node)
        return;
      // As for edges: a corner of the triangle near on the paper settles most visits.
      if ((mesh_.nodes[tri[0]].crease_pattern - at).squaredNorm() < one_face * one_face &&
          inFace(node, mesh_.triangles[t].face))
        return;
      boundsOf(tri, x, lo, hi);
      if (boxGap(lo, hi, p, p) > wide)
        return;
      const double apart = patternDistance(mesh_, t, mesh_.nodes[node].crease_pattern);
      if (apart < exclusion_ || (apart < one_face && inFace(node, mesh_.triangles[t].face)))
        return;
      found.nodes.push_back({ node, t });
    });
  }
  const auto edge_nodes = [this](size_t e) { return mesh_.edges[e].nodes; };
  const ElementGrid edges(mesh_.edges.size(), x, std::max(wide, mesh_.spacing), wide, edge_nodes);
  std::vector<int> edge_stamp(mesh_.edges.size(), -1);
  Vec3 lo_b, hi_b;
  for (size_t ea = 0; ea < mesh_.edges.size(); ++ea)
  {
    const auto& na = mesh_.edges[ea].nodes;
    boundsOf(na, x, lo, hi);
    const int face_a = edge_face_[ea];
    const Vec2& middle_a = edge_middle_[ea];
    edges.near(lo, hi, edge_stamp, static_cast<int>(ea), [&](int eb) {
      if (eb <= static_cast<int>(ea))
        return;
      // Most visits are neighbours inside one face: their middles alone settle it, before
      // any geometry (the segments are nearer than their middles).
      if (face_a >= 0 && edge_face_[eb] == face_a && (edge_middle_[eb] - middle_a).squaredNorm() < one_face * one_face)
        return;
      const auto& nb = mesh_.edges[eb].nodes;
      if (nb[0] == na[0] || nb[0] == na[1] || nb[1] == na[0] || nb[1] == na[1])
        return;
      boundsOf(nb, x, lo_b, hi_b);
      if (boxGap(lo, hi, lo_b, hi_b) > wide)
        return;
      // Neighbours in one face bend smoothly past each other; only layers are kept apart.
      // Across a crease they are layers as soon as they cross (a fold near 180°).
      bool same_face = false;
      for (int ta : mesh_.edges[ea].triangles)
        for (int tb : mesh_.edges[eb].triangles)
          same_face = same_face || (ta >= 0 && tb >= 0 && mesh_.triangles[ta].face == mesh_.triangles[tb].face);
      if (same_face &&
          segmentDistance2d(mesh_.nodes[na[0]].crease_pattern, mesh_.nodes[na[1]].crease_pattern,
                            mesh_.nodes[nb[0]].crease_pattern, mesh_.nodes[nb[1]].crease_pattern) < one_face)
        return;
      found.edges.push_back({ static_cast<int>(ea), eb });
    });
  }
  found.at = x;
  return found;
}

void LayerContact::update(const Positions& x)
{
  if (!x.allFinite())
    return;  // a diverged state: the solver rolls it back; keep the pairs of the last good one
  if (needsSearch(x))
    findCandidates(x);
  const double reach = thickness_ + range_;
  std::map<std::pair<int, int>, Pair> nearest;  // per (node, paper face), the nearest triangle
  std::map<std::pair<int, int>, double> nearest_distance;
  Vec3 lo, hi, lo_b, hi_b;
  for (const auto& [node, t] : candidates_)
  {
    const Vec3 p = x.col(node);
    const auto& tri = mesh_.triangles[t].nodes;
    // A watched node lies within reach of the triangle's plane, over it or at most the edge
    // margin past its side: within reach + margin of its box.
    boundsOf(tri, x, lo, hi);
    if (boxGap(lo, hi, p, p) > reach + edge_margin_)
      continue;
    const Projection pr = project(x.col(tri[0]), x.col(tri[1]), x.col(tri[2]), p);
    if (!pr.valid || std::abs(pr.distance) > reach)
      continue;
    bool outside = false;
    for (int k = 0; k < 3 && !outside; ++k)
    {
      // A node over an edge between two triangles must count for one of them, whatever
      // the rounding: a little slack (the nearest triangle per face wins anyway).
      if (pr.weights[k] >= -1e-3)
        continue;
      // Outside across side k: only past the sheet's edge, and not far.
      const Vec3 side = x.col(tri[(k + 2) % 3]) - x.col(tri[(k + 1) % 3]);
      const double height = 2 * pr.area / side.norm();
      outside = !open_side_[t][k] || -pr.weights[k] * height > edge_margin_;
    }
    if (outside)
      continue;
    const std::pair<int, int> key{ node, mesh_.triangles[t].face };
    const auto known = nearest_distance.find(key);
    if (known != nearest_distance.end() && known->second <= std::abs(pr.distance))
      continue;
    const auto remembered = sides_.find(key);
    const int side = remembered != sides_.end() ? remembered->second : sideFor(node, t, pr.distance);
    if (side == 0)
      continue;
    nearest[key] = { node, t, side };
    nearest_distance[key] = std::abs(pr.distance);
  }
  pairs_.clear();
  sides_.clear();
  for (const auto& [key, pair] : nearest)
  {
    pairs_.push_back(pair);
    sides_[key] = pair.side;
  }

  std::map<std::pair<int, int>, int> edge_sides;
  edge_pairs_.clear();
  for (const auto& [ea, eb] : edge_candidates_)
  {
    const auto& na = mesh_.edges[ea].nodes;
    const auto& nb = mesh_.edges[eb].nodes;
    boundsOf(na, x, lo, hi);
    boundsOf(nb, x, lo_b, hi_b);
    if (boxGap(lo, hi, lo_b, hi_b) > reach)
      continue;
    const Crossing c = cross(x.col(na[0]), x.col(na[1]), x.col(nb[0]), x.col(nb[1]));
    if (!c.valid || std::abs(c.distance) > reach || c.s < 0 || c.s > 1 || c.t < 0 || c.t > 1)
      continue;
    const std::pair<int, int> key{ ea, eb };
    const auto remembered = edge_sides_.find(key);
    const int side =
        remembered != edge_sides_.end() ? remembered->second : edgeSideFor(ea, eb, c.distance, c.normal, x);
    if (side == 0)
      continue;
    edge_pairs_.push_back({ ea, eb, side });
    edge_sides[key] = side;
  }
  edge_sides_ = std::move(edge_sides);
}

double LayerContact::evaluate(const Positions& x, const Assembly& out) const
{
  double energy = 0.0;
  for (const Pair& pair : pairs_)
  {
    const auto& tri = mesh_.triangles[pair.triangle].nodes;
    const Projection pr = project(x.col(tri[0]), x.col(tri[1]), x.col(tri[2]), x.col(pair.node));
    if (!pr.valid)
      continue;
    const double gap = pair.side * pr.distance;
    if (gap >= thickness_)
      continue;
    // ∂g/∂p = n and ∂g/∂x_k = −β_k n for the triangle's corners (β: the projection's affine
    // coordinates), times the side.
    Eigen::Matrix<double, 3, 4> grad;
    grad.col(0) = pair.side * pr.normal;
    for (int k = 0; k < 3; ++k)
      grad.col(k + 1) = -pr.weights[k] * grad.col(0);
    energy += addTerm<4>({ pair.node, tri[0], tri[1], tri[2] }, stiffness_, gap - thickness_, grad, out);
  }
  for (const EdgePair& pair : edge_pairs_)
  {
    const auto& na = mesh_.edges[pair.a].nodes;
    const auto& nb = mesh_.edges[pair.b].nodes;
    const Crossing c = cross(x.col(na[0]), x.col(na[1]), x.col(nb[0]), x.col(nb[1]));
    if (!c.valid)
      continue;
    const double gap = pair.side * c.distance;
    if (gap >= thickness_)
      continue;
    const Vec3 n = pair.side * c.normal;
    Eigen::Matrix<double, 3, 4> grad;
    grad << (1 - c.s) * n, c.s * n, -(1 - c.t) * n, -c.t * n;
    energy += addTerm<4>({ na[0], na[1], nb[0], nb[1] }, stiffness_, gap - thickness_, grad, out);
  }
  return energy;
}

std::vector<std::array<int, 4>> LayerContact::pairNodes() const
{
  std::vector<std::array<int, 4>> groups;
  for (const Pair& pair : pairs_)
  {
    const auto& tri = mesh_.triangles[pair.triangle].nodes;
    groups.push_back({ pair.node, tri[0], tri[1], tri[2] });
  }
  for (const EdgePair& pair : edge_pairs_)
  {
    const auto& na = mesh_.edges[pair.a].nodes;
    const auto& nb = mesh_.edges[pair.b].nodes;
    groups.push_back({ na[0], na[1], nb[0], nb[1] });
  }
  return groups;
}

double LayerContact::worstGap(const Positions& x) const
{
  double worst = std::numeric_limits<double>::infinity();
  for (const Pair& pair : pairs_)
  {
    const auto& tri = mesh_.triangles[pair.triangle].nodes;
    const Projection pr = project(x.col(tri[0]), x.col(tri[1]), x.col(tri[2]), x.col(pair.node));
    if (pr.valid)
      worst = std::min(worst, pair.side * pr.distance);
  }
  for (const EdgePair& pair : edge_pairs_)
  {
    const auto& na = mesh_.edges[pair.a].nodes;
    const auto& nb = mesh_.edges[pair.b].nodes;
    const Crossing c = cross(x.col(na[0]), x.col(na[1]), x.col(nb[0]), x.col(nb[1]));
    if (c.valid)
      worst = std::min(worst, pair.side * c.distance);
  }
  return worst;
}

int LayerContact::touching(const Positions& x) const
{
  int count = 0;
  for (const Pair& pair : pairs_)
  {
    const auto& tri = mesh_.triangles[pair.triangle].nodes;
    const Projection pr = project(x.col(tri[0]), x.col(tri[1]), x.col(tri[2]), x.col(pair.node));
    count += pr.valid && pair.side * pr.distance < thickness_ ? 1 : 0;
  }
  return count;
}

std::vector<std::array<int, 2>> findPenetrations(const CurvedMesh& mesh, const Positions& x, double tolerance)
{
  if (!x.allFinite())
    return {};
  const ElementGrid grid(mesh, x, std::max(mesh.spacing, 1e-9), tolerance);
  std::vector<int> stamp(mesh.triangles.size(), -1);
  std::vector<std::array<int, 2>> found;
  for (size_t e = 0; e < mesh.edges.size(); ++e)
  {
    const int i = mesh.edges[e].nodes[0], j = mesh.edges[e].nodes[1];
    const Vec3 p = x.col(i), q = x.col(j);
    grid.near(p.cwiseMin(q), p.cwiseMax(q), stamp, static_cast<int>(e), [&](int t) {
      const auto& tri = mesh.triangles[t].nodes;
      for (int n : tri)
        if (n == i || n == j)
          return;
      const Projection pp = project(x.col(tri[0]), x.col(tri[1]), x.col(tri[2]), p);
      if (!pp.valid)
        return;
      const double dp = pp.distance, dq = pp.normal.dot(q - x.col(tri[0]));
      if (!((dp > tolerance && dq < -tolerance) || (dp < -tolerance && dq > tolerance)))
        return;
      const Vec3 s = p + dp / (dp - dq) * (q - p);
      const Projection ps = project(x.col(tri[0]), x.col(tri[1]), x.col(tri[2]), s);
      if (*std::min_element(ps.weights.begin(), ps.weights.end()) > 1e-9)
        found.push_back({ static_cast<int>(e), t });
    });
  }
  return found;
}

namespace
{
/// Segment a–b passes through the inside of triangle t0 t1 t2, crossing its plane with both
/// ends farther than `tolerance` from it.
bool segmentPierces(const Vec3& a, const Vec3& b, const Vec3& t0, const Vec3& t1, const Vec3& t2, double tolerance)
{
  const Projection pa = project(t0, t1, t2, a);
  if (!pa.valid)
    return false;
  const double da = pa.distance, db = pa.normal.dot(b - t0);
  if (!((da > tolerance && db < -tolerance) || (da < -tolerance && db > tolerance)))
    return false;
  const Projection ps = project(t0, t1, t2, a + da / (da - db) * (b - a));
  return *std::min_element(ps.weights.begin(), ps.weights.end()) > 1e-12;
}
}  // namespace

bool trianglesCross(const Vec3& p0, const Vec3& p1, const Vec3& p2, const Vec3& q0, const Vec3& q1, const Vec3& q2,
                    double tolerance)
{
  // Two triangles in general position intersect exactly when an edge of one pierces the
  // other; the segment they then share starts and ends at such piercings.
  const std::array<Vec3, 3> p = { p0, p1, p2 }, q = { q0, q1, q2 };
  for (int k = 0; k < 3; ++k)
    if (segmentPierces(p[k], p[(k + 1) % 3], q0, q1, q2, tolerance) ||
        segmentPierces(q[k], q[(k + 1) % 3], p0, p1, p2, tolerance))
      return true;
  return false;
}

std::vector<std::array<int, 2>> findTriangleCrossings(const CurvedMesh& mesh, const Positions& x, double tolerance)
{
  if (mesh.triangles.empty() || !x.allFinite())
    return {};
  // Cells of a mesh spacing, or of a sixteenth of the extent for a mesh without one.
  const double extent = (x.rowwise().maxCoeff() - x.rowwise().minCoeff()).norm();
  const ElementGrid grid(mesh, x, mesh.spacing > 0 ? mesh.spacing : std::max(extent / 16, 1e-9), tolerance);
  std::vector<int> stamp(mesh.triangles.size(), -1);
  std::vector<std::array<int, 2>> found;
  for (size_t t = 0; t < mesh.triangles.size(); ++t)
  {
    const auto& a = mesh.triangles[t].nodes;
    Vec3 lo = x.col(a[0]), hi = lo;
    for (int n : a)
    {
      lo = lo.cwiseMin(x.col(n));
      hi = hi.cwiseMax(x.col(n));
    }
    grid.near(lo, hi, stamp, static_cast<int>(t), [&](int u) {
      if (u <= static_cast<int>(t))
        return;
      const auto& b = mesh.triangles[u].nodes;
      for (int m : a)
        for (int n : b)
          if (m == n)
            return;  // neighbours on the sheet
      if (trianglesCross(x.col(a[0]), x.col(a[1]), x.col(a[2]), x.col(b[0]), x.col(b[1]), x.col(b[2]), tolerance))
        found.push_back({ static_cast<int>(t), u });
    });
  }
  return found;
}

}  // namespace virtual_origami::core

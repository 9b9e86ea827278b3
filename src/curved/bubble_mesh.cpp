#include "virtual_origami/curved/bubble_mesh.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <utility>

#include "virtual_origami/core/planar_geometry.h"
#include "virtual_origami/curved/delaunay.h"

namespace virtual_origami::core
{
namespace
{
Vec2 perp(const Vec2& v) { return Vec2(-v.y(), v.x()); }

/// A convex face, counter-clockwise, in units of the bubble diameter.
struct Polygon
{
  std::vector<Vec2> corners;

  /// Distance to the nearest side's line, positive inside.
  double inside(const Vec2& p) const
  {
    double d = std::numeric_limits<double>::infinity();
    for (size_t i = 0; i < corners.size(); ++i)
    {
      const Vec2& a = corners[i];
      const Vec2 t = (corners[(i + 1) % corners.size()] - a).normalized();
      d = std::min(d, perp(t).dot(p - a));
    }
    return d;
  }

  /// Moves `p` inwards along the nearest side's normal until it is `margin` inside; returns
  /// that normal (zero when `p` was deep enough already).
  Vec2 pushInside(Vec2& p, double margin) const
  {
    Vec2 normal = Vec2::Zero();
    for (int pass = 0; pass < 3; ++pass)  // a corner may need its two sides in turn
    {
      double worst = margin;
      Vec2 n = Vec2::Zero();
      for (size_t i = 0; i < corners.size(); ++i)
      {
        const Vec2& a = corners[i];
        const Vec2 inward = perp((corners[(i + 1) % corners.size()] - a).normalized());
        const double d = inward.dot(p - a);
        if (d < worst)
        {
          worst = d;
          n = inward;
        }
      }
      if (n.isZero())
        break;
      p += (margin - worst) * n;
      normal = n;
    }
    return normal;
  }
};

/// Points binned in square cells, for the neighbours within one cell size.
class Grid
{
public:
  Grid(const std::vector<Vec2>& points, double cell) : cell_(cell)
  {
    for (size_t i = 0; i < points.size(); ++i)
      cells_[key(points[i])].push_back(static_cast<int>(i));
  }

  template <class Visit>
  void near(const Vec2& p, Visit visit) const
  {
    const auto [cx, cy] = key(p);
    for (long x = cx - 1; x <= cx + 1; ++x)
      for (long y = cy - 1; y <= cy + 1; ++y)
      {
        const auto it = cells_.find({ x, y });
        if (it != cells_.end())
          for (int i : it->second)
            visit(i);
      }
  }

private:
  std::pair<long, long> key(const Vec2& p) const
  {
    return { static_cast<long>(std::floor(p.x() / cell_)), static_cast<long>(std::floor(p.y() / cell_)) };
  }
  double cell_;
  std::map<std::pair<long, long>, std::vector<int>> cells_;
};

/// The packing of one face, in units of the bubble diameter: boundary bubbles fixed, the
/// interior ones moved by the bubble force with damping, integrated by RK4 (seed 002 §4.1).
class FacePacking
{
public:
  FacePacking(Polygon polygon, std::vector<Vec2> fixed, const BubbleMeshOptions& options)
    : polygon_(std::move(polygon))
    , fixed_(std::move(fixed))
    , options_(options)
    , force_(BubbleForce::fit(1.0, options.reach, 1.0))
  {
  }

  /// The starting arrangement: an equilateral lattice laid along the face's longest side,
  /// where the force is already in balance (seed 002 Fig. 2.7).
  void seedLattice()
  {
    const std::vector<Vec2>& c = polygon_.corners;
    size_t longest = 0;
    for (size_t i = 1; i < c.size(); ++i)
      if ((c[(i + 1) % c.size()] - c[i]).norm() > (c[(longest + 1) % c.size()] - c[longest]).norm())
        longest = i;
    const Vec2 origin = c[longest];
    const Vec2 u = (c[(longest + 1) % c.size()] - origin).normalized();
    const Vec2 w = perp(u);
    double u_min = 0, u_max = 0, w_max = 0;
    for (const Vec2& p : c)
    {
      u_min = std::min(u_min, u.dot(p - origin));
      u_max = std::max(u_max, u.dot(p - origin));
      w_max = std::max(w_max, w.dot(p - origin));
    }
    const double row = std::sqrt(3.0) / 2;
    for (int j = 1; j * row < w_max; ++j)
      for (int i = static_cast<int>(std::floor(u_min)) - 1; i <= static_cast<int>(std::ceil(u_max)) + 1; ++i)
      {
        const Vec2 p = origin + (i + 0.5 * (j % 2)) * u + j * row * w;
        if (polygon_.inside(p) >= 0.5 && nearestFixed(p) >= 0.6)
          free_.push_back(p);
      }
  }

  /// Damped motion until the bubbles settle; returns the steps taken.
  int relax()
  {
    const size_t n = free_.size();
    std::vector<Vec2> v(n, Vec2::Zero());
    int steps = 0;
    const double dt = options_.time_step;
    for (; steps < options_.max_steps && n > 0; ++steps)
    {
      collectPairs();
      // RK4 on (x, v) with x' = v, v' = F(x) − c v.
      std::vector<Vec2> x0 = free_, v0 = v, kx[4], kv[4];
      std::vector<Vec2> xs = x0, vs = v0;
      for (int s = 0; s < 4; ++s)
      {
        if (s > 0)
        {
          const double h = s == 3 ? dt : dt / 2;
          for (size_t i = 0; i < n; ++i)
          {
            xs[i] = x0[i] + h * kx[s - 1][i];
            vs[i] = v0[i] + h * kv[s - 1][i];
          }
        }
        kx[s] = vs;
        kv[s] = forces(xs);
        for (size_t i = 0; i < n; ++i)
          kv[s][i] -= options_.damping * vs[i];
      }
      double fastest = 0.0;
      for (size_t i = 0; i < n; ++i)
      {
        free_[i] = x0[i] + dt / 6 * (kx[0][i] + 2 * kx[1][i] + 2 * kx[2][i] + kx[3][i]);
        v[i] = v0[i] + dt / 6 * (kv[0][i] + 2 * kv[1][i] + 2 * kv[2][i] + kv[3][i]);
        // The fixed bubbles on the sides keep the others in; this catches one squeezed out.
        const Vec2 normal = polygon_.pushInside(free_[i], 0.3);
        if (!normal.isZero())
          v[i] -= std::min(0.0, v[i].dot(normal)) * normal;
        fastest = std::max(fastest, v[i].norm());
      }
      if (fastest < options_.settle_speed)
      {
        ++steps;
        break;
      }
    }
    return steps;
  }

  /// Deletes bubbles where the packing is too dense and inserts them in holes; returns
  /// whether anything changed.
  bool adjust(BubbleMeshReport& report)
  {
    bool changed = false;
    // Too dense: a bubble overlapping another by more than 40% of its diameter, or pressed
    // against the sides, goes (of two free ones, the first found).
    std::vector<char> gone(free_.size(), 0);
    const Grid fixed_grid(fixed_, 1.0);
    const Grid free_grid(free_, 1.0);
    for (size_t i = 0; i < free_.size(); ++i)
    {
      bool crowded = polygon_.inside(free_[i]) < 0.35;
      fixed_grid.near(free_[i], [&](int j) { crowded = crowded || (fixed_[j] - free_[i]).norm() < 0.6; });
      free_grid.near(free_[i], [&](int j) {
        crowded = crowded || (j != static_cast<int>(i) && !gone[j] && (free_[j] - free_[i]).norm() < 0.6);
      });
      if (crowded)
      {
        gone[i] = 1;
        ++report.deleted;
        changed = true;
      }
    }
    std::vector<Vec2> kept;
    for (size_t i = 0; i < free_.size(); ++i)
      if (!gone[i])
        kept.push_back(free_[i]);
    free_ = std::move(kept);

    // Too sparse: candidates on a lattice three times finer; while one lies farther than
    // 0.65 diameters from every bubble (close packing leaves at most 1/√3 ≈ 0.58), the
    // farthest gets a bubble. A looser bound misses the gaps the start lattice leaves along
    // the sides across its rows: 1.5 diameters wide, beyond the force's reach r1, so relaxing
    // never closes them, yet the largest empty circle in them has a radius of only ~0.75.
    std::vector<Vec2> candidates;
    const std::vector<Vec2>& c = polygon_.corners;
    Vec2 lo = c[0], hi = c[0];
    for (const Vec2& p : c)
    {
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
    const double step = 1.0 / 3, row = step * std::sqrt(3.0) / 2;
    for (int j = 0; lo.y() + j * row <= hi.y(); ++j)
      for (int i = 0; lo.x() + (i + 0.5 * (j % 2)) * step <= hi.x(); ++i)
      {
        const Vec2 p(lo.x() + (i + 0.5 * (j % 2)) * step, lo.y() + j * row);
        if (polygon_.inside(p) >= 0.5)
          candidates.push_back(p);
      }
    std::vector<double> gap(candidates.size());
    for (size_t k = 0; k < candidates.size(); ++k)
      gap[k] = std::min(nearestFixed(candidates[k]), nearestFree(candidates[k]));
    while (!candidates.empty())
    {
      const size_t best = static_cast<size_t>(std::max_element(gap.begin(), gap.end()) - gap.begin());
      if (gap[best] <= 0.65)
        break;
      const Vec2 p = candidates[best];
      free_.push_back(p);
      for (size_t k = 0; k < candidates.size(); ++k)
        gap[k] = std::min(gap[k], (candidates[k] - p).norm());
      ++report.inserted;
      changed = true;
    }
    return changed;
  }

  const std::vector<Vec2>& bubbles() const { return free_; }

private:
  double nearestFixed(const Vec2& p) const
  {
    double d = std::numeric_limits<double>::infinity();
    for (const Vec2& q : fixed_)
      d = std::min(d, (q - p).norm());
    return d;
  }
  double nearestFree(const Vec2& p) const
  {
    double d = std::numeric_limits<double>::infinity();
    for (const Vec2& q : free_)
      d = std::min(d, (q - p).norm());
    return d;
  }

  /// Pairs within reach (with a margin, kept for the four RK4 stages of one step): free–free
  /// with j > i, and free–fixed with the fixed index stored as −1 − j.
  void collectPairs()
  {
    pairs_.clear();
    const double cutoff = options_.reach * 1.25;
    const Grid free_grid(free_, cutoff), fixed_grid(fixed_, cutoff);
    for (size_t i = 0; i < free_.size(); ++i)
    {
      free_grid.near(free_[i], [&](int j) {
        if (j > static_cast<int>(i) && (free_[j] - free_[i]).norm() < cutoff)
          pairs_.emplace_back(static_cast<int>(i), j);
      });
      fixed_grid.near(free_[i], [&](int j) {
        if ((fixed_[j] - free_[i]).norm() < cutoff)
          pairs_.emplace_back(static_cast<int>(i), -1 - j);
      });
    }
  }

  std::vector<Vec2> forces(const std::vector<Vec2>& x) const
  {
    std::vector<Vec2> f(x.size(), Vec2::Zero());
    for (const auto& [i, j] : pairs_)
    {
      const Vec2 r = x[i] - (j >= 0 ? x[j] : fixed_[-1 - j]);
      const double length = r.norm();
      if (!(length > 1e-12))
        continue;
      const Vec2 push = force_(length) / length * r;
      f[i] += push;
      if (j >= 0)
        f[j] -= push;
    }
    return f;
  }

  Polygon polygon_;
  std::vector<Vec2> fixed_;
  std::vector<Vec2> free_;
  std::vector<std::pair<int, int>> pairs_;
  BubbleMeshOptions options_;
  BubbleForce force_;
};

bool isCurved(const BubbleMeshOptions& options, int face)
{
  return options.curved_faces.empty() || (static_cast<size_t>(face) < options.curved_faces.size() &&
                                          options.curved_faces[face]);
}

double spacingOf(const Paper& paper, const BubbleMeshOptions& options)
{
  return options.spacing > 0 ? options.spacing : paper.scale() / 10;
}
}  // namespace

BubbleForce BubbleForce::fit(double r0, double r1, double k0)
{
  // c = 0 from f′(0) = 0; f(r0) = f(r1) = 0 give b = −a(r1³ − r0³)/(r1² − r0²); f′(r0) = −k0
  // then fixes a, and f(r0) = 0 fixes d.
  BubbleForce f;
  f.r0 = r0;
  f.r1 = r1;
  f.k0 = k0;
  const double ratio = (r1 * r1 + r0 * r1 + r0 * r0) / (r1 + r0);
  f.a = -k0 / (3 * r0 * r0 - 2 * r0 * ratio);
  f.b = -f.a * ratio;
  f.c = 0.0;
  f.d = -f.a * r0 * r0 * r0 - f.b * r0 * r0;
  return f;
}

int edgeBubbleCount(double length, double spacing)
{
  // Bubbles of diameter `spacing` centred on equal divisions cover the edge without a gap
  // when the divisions are no longer than `spacing`.
  const int divisions = static_cast<int>(std::ceil(length / spacing - 1e-9));
  return std::max(0, divisions - 1);
}

std::vector<MeshNode> placeBubbles(const Paper& paper, const BubbleMeshOptions& options, BubbleMeshReport* report)
{
  BubbleMeshReport local;
  BubbleMeshReport& rep = report ? *report : local;
  const double h = spacingOf(paper, options);
  std::vector<MeshNode> nodes;
  // 1. Vertices.
  for (size_t v = 0; v < paper.vertices.size(); ++v)
  {
    MeshNode node;
    node.crease_pattern = paper.vertices[v].crease_pattern;
    node.paper_vertex = static_cast<int>(v);
    nodes.push_back(node);
  }
  // 2. Edges: only where a face that bends needs them (a coarse face's own sides stay bare).
  std::vector<std::vector<int>> edge_nodes(paper.edges.size());
  for (size_t e = 0; e < paper.edges.size(); ++e)
  {
    const Edge& edge = paper.edges[e];
    bool needed = false;
    for (int f : edge.faces)
      needed = needed || (f >= 0 && isCurved(options, f));
    if (!needed)
      continue;
    const Vec2& a = paper.vertices[edge.vertices[0]].crease_pattern;
    const Vec2& b = paper.vertices[edge.vertices[1]].crease_pattern;
    const int count = edgeBubbleCount((b - a).norm(), h);
    for (int k = 1; k <= count; ++k)
    {
      MeshNode node;
      node.edge_t = static_cast<double>(k) / (count + 1);
      node.crease_pattern = a + node.edge_t * (b - a);
      node.paper_edge = static_cast<int>(e);
      edge_nodes[e].push_back(static_cast<int>(nodes.size()));
      nodes.push_back(node);
    }
  }
  // 3. Faces: packed by the simulation, each face on its own with its sides' bubbles fixed.
  for (size_t f = 0; f < paper.faces.size(); ++f)
  {
    if (!isCurved(options, static_cast<int>(f)))
      continue;
    const Face& face = paper.faces[f];
    Polygon polygon;
    std::vector<Vec2> fixed;
    for (size_t i = 0; i < face.vertices.size(); ++i)
    {
      polygon.corners.push_back(paper.vertices[face.vertices[i]].crease_pattern / h);
      fixed.push_back(polygon.corners.back());
      for (int node : edge_nodes[face.edges[i]])
        fixed.push_back(nodes[node].crease_pattern / h);
    }
    FacePacking packing(polygon, fixed, options);
    packing.seedLattice();
    rep.steps += packing.relax();
    for (int round = 0; round < options.adjust_rounds; ++round)
    {
      if (!packing.adjust(rep))
        break;
      rep.steps += packing.relax();
    }
    for (const Vec2& p : packing.bubbles())
    {
      MeshNode node;
      node.crease_pattern = p * h;
      node.paper_face = static_cast<int>(f);
      nodes.push_back(node);
    }
  }
  return nodes;
}

namespace
{
/// A row of nodes `width` inside each face beside every crease, one across from each node on
/// the crease, and one at each of the face's corners between two creases (`width` from both):
/// the triangles joining a crease to its faces are then `width` wide, so a fold can be drawn
/// with its two faces apart by less than that (layeredStart) without tilting whole triangles.
void addCreaseStrips(const Paper& paper, double width, std::vector<MeshNode>& nodes)
{
  std::vector<std::vector<double>> along(paper.edges.size());
  for (const MeshNode& n : nodes)
    if (n.paper_edge >= 0)
      along[n.paper_edge].push_back(n.edge_t);
  for (size_t e = 0; e < paper.edges.size(); ++e)
  {
    const Edge& edge = paper.edges[e];
    if (!edge.isCrease())
      continue;
    const Vec2 a = paper.vertices[edge.vertices[0]].crease_pattern, b = paper.vertices[edge.vertices[1]].crease_pattern;
    const Vec2 left = Vec2(a.y() - b.y(), b.x() - a.x()).normalized();  // faces[0] lies left of a→b
    for (int side = 0; side < 2; ++side)
      for (double t : along[e])
      {
        MeshNode n;
        n.crease_pattern = a + t * (b - a) + (side == 0 ? 1.0 : -1.0) * width * left;
        n.paper_face = edge.faces[side];
        nodes.push_back(n);
      }
  }
  for (size_t f = 0; f < paper.faces.size(); ++f)
  {
    const Face& face = paper.faces[f];
    const size_t count = face.vertices.size();
    for (size_t i = 0; i < count; ++i)
    {
      const int before = face.edges[(i + count - 1) % count], after = face.edges[i];
      // Only between two creases: at a corner on the sheet's edge the crease's own row of
      // nodes comes near enough.
      if (!paper.edges[before].isCrease() || !paper.edges[after].isCrease())
        continue;
      const Vec2 v = paper.vertices[face.vertices[i]].crease_pattern;
      const Vec2 u = (paper.vertices[face.vertices[(i + count - 1) % count]].crease_pattern - v).normalized();
      const Vec2 w = (paper.vertices[face.vertices[(i + 1) % count]].crease_pattern - v).normalized();
      const double half_sine = std::sqrt(std::max(0.0, (1 - u.dot(w)) / 2));
      if (half_sine < 0.1)
        continue;  // a sharp corner: its strip nodes beside the sides come near enough
      MeshNode n;
      n.crease_pattern = v + width / half_sine * (u + w).normalized();
      n.paper_face = static_cast<int>(f);
      nodes.push_back(n);
    }
  }
}
}  // namespace

Expected<CurvedMesh> bubbleMesh(const Paper& paper, const BubbleMeshOptions& options, BubbleMeshReport* report)
{
  CurvedMesh mesh;
  mesh.spacing = spacingOf(paper, options);
  mesh.nodes = placeBubbles(paper, options, report);
  mesh.vertex_nodes.resize(paper.vertices.size());
  for (size_t v = 0; v < paper.vertices.size(); ++v)
    mesh.vertex_nodes[v] = static_cast<int>(v);
  mesh.curved_faces.resize(paper.faces.size());
  for (size_t f = 0; f < paper.faces.size(); ++f)
    mesh.curved_faces[f] = isCurved(options, static_cast<int>(f)) ? 1 : 0;

  // Every paper edge, node to node along it, is a constraint: no triangle crosses a crease.
  std::vector<std::vector<std::pair<double, int>>> along(paper.edges.size());
  for (size_t e = 0; e < paper.edges.size(); ++e)
  {
    along[e].emplace_back(0.0, paper.edges[e].vertices[0]);
    along[e].emplace_back(1.0, paper.edges[e].vertices[1]);
  }
  if (options.crease_strip > 0)
    addCreaseStrips(paper, options.crease_strip, mesh.nodes);
  std::vector<Vec2> points;
  for (size_t i = 0; i < mesh.nodes.size(); ++i)
  {
    points.push_back(mesh.nodes[i].crease_pattern);
    if (mesh.nodes[i].paper_edge >= 0)
      along[mesh.nodes[i].paper_edge].emplace_back(mesh.nodes[i].edge_t, static_cast<int>(i));
  }
  std::vector<std::array<int, 2>> constraints;
  for (auto& nodes : along)
  {
    std::sort(nodes.begin(), nodes.end());
    for (size_t k = 0; k + 1 < nodes.size(); ++k)
      constraints.push_back({ nodes[k].second, nodes[k + 1].second });
  }
  Expected<std::vector<std::array<int, 3>>> triangles = constrainedDelaunay(points, constraints);
  if (!triangles.ok())
    return Expected<CurvedMesh>::failure("meshing failed: " + triangles.message());

  // The triangulation covers the hull of the nodes: keep the triangles inside the paper, each
  // in the face that holds its centroid (faces are convex, and no triangle crosses an edge).
  // Bubbles placed along a slanted side are collinear only up to rounding, so the hull grows
  // slivers of them outside the sheet whose centroids lie within rounding of the side: a
  // centroid must lie clearly inside, as every true triangle's does (a third of its height).
  const double margin = 1e-6 * mesh.spacing;
  const auto holds = [&](int f, const Vec2& centroid) {
    const std::vector<int>& vs = paper.faces[f].vertices;
    for (size_t i = 0; i < vs.size(); ++i)
    {
      const Vec2& a = paper.vertices[vs[i]].crease_pattern;
      const Vec2& b = paper.vertices[vs[(i + 1) % vs.size()]].crease_pattern;
      if (!(cross2(b - a, centroid - a) > margin * (b - a).norm()))
        return false;
    }
    return true;
  };
  // The faces of its corners first (no triangle crosses an edge): a scan of every face per
  // triangle made meshing quadratic (26 s at 50,000 vertices). Every face after them, for the
  // slivers outside the sheet and for a crease strip's node set out past a narrow face (which
  // then lies in another face than its own).
  const std::vector<std::vector<int>> node_faces = mesh.facesOfNodes(paper);
  std::vector<int> candidates;
  for (const auto& t : *triangles)
  {
    const Vec2 centroid = (points[t[0]] + points[t[1]] + points[t[2]]) / 3;
    candidates.clear();
    for (int node : t)
      candidates.insert(candidates.end(), node_faces[node].begin(), node_faces[node].end());
    std::sort(candidates.begin(), candidates.end());
    candidates.erase(std::unique(candidates.begin(), candidates.end()), candidates.end());
    int face = -1;
    for (size_t k = 0; k < candidates.size() && face < 0; ++k)
      face = holds(candidates[k], centroid) ? candidates[k] : -1;
    for (size_t f = 0; f < paper.faces.size() && face < 0; ++f)
      face = holds(static_cast<int>(f), centroid) ? static_cast<int>(f) : -1;
    if (face >= 0)
      mesh.triangles.push_back({ t, face });
  }
  const Status linked = linkMesh(mesh, paper);
  if (!linked.ok())
    return Expected<CurvedMesh>::failure("meshing failed: " + linked.message());
  return mesh;
}

}  // namespace virtual_origami::core

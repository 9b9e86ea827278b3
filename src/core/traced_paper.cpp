#include "virtual_origami/core/traced_paper.h"

#include <algorithm>
#include <cmath>
#include <deque>
#include <limits>
#include <map>
#include <numeric>
#include <string>
#include <utility>

#include "format_error.h"
#include "virtual_origami/core/planar_geometry.h"
#include "virtual_origami/core/planar_graph.h"

namespace virtual_origami::core
{
namespace
{
/// The graph as it is reworked: edges dropped, cut edges split in two, joints added.
struct Drawing
{
  std::vector<Vec2> points;
  std::vector<VertexSource> sources;
  std::vector<std::array<int, 2>> edges;
  std::vector<int> edge_sources;
  std::vector<Assignment> kinds;
};

struct UnionFind
{
  std::vector<int> parent;
  explicit UnionFind(size_t n) : parent(n)
  {
    std::iota(parent.begin(), parent.end(), 0);
  }
  int find(int i)
  {
    while (parent[i] != i)
      i = parent[i] = parent[parent[i]];
    return i;
  }
  void join(int a, int b)
  {
    parent[find(a)] = find(b);
  }
};

/// Where a point on drawn edge `drawn` comes from, as a fraction along it.
VertexSource sourceOnDrawnEdge(const std::vector<Vec2>& drawn_points, const std::array<int, 2>& drawn_edge,
                               const Vec2& p)
{
  const Vec2& a = drawn_points[drawn_edge[0]];
  const Vec2 d = drawn_points[drawn_edge[1]] - a;
  return { drawn_edge[0], drawn_edge[1], (p - a).dot(d) / d.squaredNorm() };
}

/// Splits edge e at point p (a new vertex, returned); the second piece is a new edge of its kind.
int splitEdge(Drawing& drawing, int e, const Vec2& p, const std::vector<Vec2>& drawn_points,
              const std::vector<std::array<int, 2>>& drawn_edges)
{
  const int v = static_cast<int>(drawing.points.size());
  drawing.points.push_back(p);
  drawing.sources.push_back(sourceOnDrawnEdge(drawn_points, drawn_edges[drawing.edge_sources[e]], p));
  const int end = drawing.edges[e][1];
  drawing.edges[e][1] = v;
  drawing.edges.push_back({ v, end });
  drawing.edge_sources.push_back(drawing.edge_sources[e]);
  drawing.kinds.push_back(drawing.kinds[e]);
  return v;
}

void removeEdges(Drawing& drawing, const std::vector<char>& remove)
{
  Drawing kept{ drawing.points, drawing.sources, {}, {}, {} };
  for (size_t e = 0; e < drawing.edges.size(); ++e)
    if (!remove[e])
    {
      kept.edges.push_back(drawing.edges[e]);
      kept.edge_sources.push_back(drawing.edge_sources[e]);
      kept.kinds.push_back(drawing.kinds[e]);
    }
  drawing = std::move(kept);
}

/// A chain of edges other than cuts that ends at a point nothing else reaches folds nothing: it
/// goes, edge by edge from its loose end. (A cut ending so is a slit, and stays.)
void dropLooseCreases(Drawing& drawing)
{
  std::vector<std::vector<int>> at(drawing.points.size());
  for (size_t e = 0; e < drawing.edges.size(); ++e)
    for (int v : drawing.edges[e])
      at[v].push_back(static_cast<int>(e));
  std::vector<char> removed(drawing.edges.size(), 0);
  std::vector<int> degree(drawing.points.size());
  for (size_t v = 0; v < at.size(); ++v)
    degree[v] = static_cast<int>(at[v].size());
  std::vector<int> loose;
  for (size_t v = 0; v < at.size(); ++v)
    if (degree[v] == 1)
      loose.push_back(static_cast<int>(v));
  while (!loose.empty())
  {
    const int v = loose.back();
    loose.pop_back();
    for (int e : at[v])
    {
      if (removed[e] || drawing.kinds[e] == Assignment::Cut || degree[v] != 1)
        continue;
      removed[e] = 1;
      for (int w : drawing.edges[e])
        if (--degree[w] == 1)
          loose.push_back(w);
    }
  }
  removeEdges(drawing, removed);
}

/// A cut edge whose both ends meet no other cut could not open (its sides would be two edges
/// between the same two points): its midpoint becomes a vertex, which opens.
void splitLoneCutEdges(Drawing& drawing, const std::vector<Vec2>& drawn_points,
                       const std::vector<std::array<int, 2>>& drawn_edges)
{
  std::vector<int> cuts_at(drawing.points.size(), 0);
  for (size_t e = 0; e < drawing.edges.size(); ++e)
    if (drawing.kinds[e] == Assignment::Cut)
      for (int v : drawing.edges[e])
        ++cuts_at[v];
  const size_t count = drawing.edges.size();
  for (size_t e = 0; e < count; ++e)
  {
    const auto [a, b] = drawing.edges[e];
    if (drawing.kinds[e] == Assignment::Cut && cuts_at[a] == 1 && cuts_at[b] == 1)
      splitEdge(drawing, static_cast<int>(e), 0.5 * (drawing.points[a] + drawing.points[b]), drawn_points, drawn_edges);
  }
}

/// The regions the drawing's edges bound and which of them are paper.
struct Regions
{
  Rotation rotation;
  std::vector<int> cycle_of;  // per half-edge
  std::vector<std::vector<int>> cycles;
  std::vector<double> areas;
  std::vector<char> paper;  // per cycle
  /// Components lying inside a paper region, touching nothing (each as its vertices).
  std::vector<std::vector<int>> islands;
};

bool contains(const std::vector<Vec2>& polygon, const Vec2& p)
{
  bool inside = false;
  for (size_t i = 0, j = polygon.size() - 1; i < polygon.size(); j = i++)
  {
    const Vec2& a = polygon[i];
    const Vec2& b = polygon[j];
    if ((a.y() > p.y()) != (b.y() > p.y()) && p.x() < a.x() + (p.y() - a.y()) * (b.x() - a.x()) / (b.y() - a.y()))
      inside = !inside;
  }
  return inside;
}

Regions findRegions(const Drawing& drawing, double min_area)
{
  Regions regions;
  const std::vector<Vec2>& points = drawing.points;
  const auto from = [&](int h) { return drawing.edges[h / 2][h % 2]; };
  regions.rotation = rotationSystem(points, drawing.edges);
  const int half_count = 2 * static_cast<int>(drawing.edges.size());
  regions.cycle_of.assign(half_count, -1);
  for (int start = 0; start < half_count; ++start)
  {
    if (regions.cycle_of[start] >= 0)
      continue;
    std::vector<int> cycle;
    for (int h = start; regions.cycle_of[h] < 0; h = regions.rotation.next[h])
    {
      regions.cycle_of[h] = static_cast<int>(regions.cycles.size());
      cycle.push_back(h);
    }
    std::vector<int> corners;
    for (int h : cycle)
      corners.push_back(from(h));
    regions.areas.push_back(signedArea(points, corners));
    regions.cycles.push_back(std::move(cycle));
  }
  const int cycle_count = static_cast<int>(regions.cycles.size());

  // Components, and the outer cycle of each (the one of least signed area).
  UnionFind components(points.size());
  for (const auto& edge : drawing.edges)
    components.join(edge[0], edge[1]);
  std::map<int, int> outer;  // component root → its outer cycle
  for (int c = 0; c < cycle_count; ++c)
  {
    const int root = components.find(from(regions.cycles[c][0]));
    const auto it = outer.find(root);
    if (it == outer.end() || regions.areas[c] < regions.areas[it->second])
      outer[root] = c;
  }
  // Each outer cycle lies in the smallest bounded cycle of another component around it, or
  // outside everything (-1). Regions are cycles merged so: an outer cycle joins its surroundings.
  std::vector<std::vector<Vec2>> polygons(cycle_count);
  for (int c = 0; c < cycle_count; ++c)
    for (int h : regions.cycles[c])
      polygons[c].push_back(points[from(h)]);
  std::vector<int> region(cycle_count);
  std::iota(region.begin(), region.end(), 0);
  const int outside = cycle_count;
  std::map<int, int> enclosing;  // component root → cycle around it, or outside
  for (const auto& [root, o] : outer)
  {
    const Vec2& p = points[from(regions.cycles[o][0])];
    int best = outside;
    for (int c = 0; c < cycle_count; ++c)
      if (regions.areas[c] > min_area && components.find(from(regions.cycles[c][0])) != root &&
          (best == outside || regions.areas[c] < regions.areas[best]) && contains(polygons[c], p))
        best = c;
    enclosing[root] = best;
  }
  // An enclosing cycle may be another component's outer cycle only if it is bounded, which an
  // outer cycle is not (its area is negative): so one pass resolves every region.
  for (const auto& [root, o] : outer)
    region[o] = enclosing[root];

  // Breadth first from outside: the first way into a region decides it.
  std::vector<std::vector<int>> half_edges_of(cycle_count + 1);
  for (int h = 0; h < half_count; ++h)
    half_edges_of[region[regions.cycle_of[h]]].push_back(h);
  std::vector<signed char> state(cycle_count + 1, -1);
  state[outside] = 0;
  std::deque<int> queue{ outside };
  while (!queue.empty())
  {
    const int r = queue.front();
    queue.pop_front();
    for (int h : half_edges_of[r])
    {
      const int across = region[regions.cycle_of[h ^ 1]];
      if (state[across] >= 0)
        continue;
      const bool boundary = drawing.kinds[h / 2] == Assignment::Boundary || r == outside;
      state[across] = boundary ? 1 - state[r] : state[r];
      queue.push_back(across);
    }
  }
  regions.paper.resize(cycle_count);
  for (int c = 0; c < cycle_count; ++c)
    regions.paper[c] = state[region[c]] == 1;
  std::map<int, std::vector<int>> vertices_of;
  for (const auto& edge : drawing.edges)
    for (int v : edge)
      vertices_of[components.find(v)].push_back(v);
  for (const auto& [root, around] : enclosing)
    if (around != outside && regions.paper[around])
    {
      std::vector<int>& vertices = vertices_of[root];
      std::sort(vertices.begin(), vertices.end());
      vertices.erase(std::unique(vertices.begin(), vertices.end()), vertices.end());
      regions.islands.push_back(vertices);
    }
  return regions;
}

/// A joint from vertex v along the unit direction d to the first thing it meets: a vertex, or an
/// edge, split there. False when it meets nothing.
bool addJoint(Drawing& drawing, int v, const Vec2& d, double tolerance, const std::vector<Vec2>& drawn_points,
              const std::vector<std::array<int, 2>>& drawn_edges)
{
  const Vec2 s = drawing.points[v];
  double nearest = std::numeric_limits<double>::infinity();
  int hit_edge = -1, hit_vertex = -1;
  const auto meetVertex = [&](int end) {
    const double along = (drawing.points[end] - s).dot(d);
    if (along > tolerance && along < nearest)
    {
      nearest = along;
      hit_vertex = end;
      hit_edge = -1;
    }
  };
  for (size_t e = 0; e < drawing.edges.size(); ++e)
  {
    const auto [a, b] = drawing.edges[e];
    if (a == v || b == v)
      continue;
    const Vec2 &p = drawing.points[a], r = drawing.points[b] - p;
    const double length = r.norm();
    const double denominator = cross2(d, r);
    if (std::abs(denominator) <= 1e-12 * length)
    {
      if (std::abs(cross2(p - s, d)) <= tolerance)  // along the ray: met at its nearer end
      {
        meetVertex(a);
        meetVertex(b);
      }
      continue;
    }
    const double along = cross2(p - s, r) / denominator, at = cross2(p - s, d) / denominator;
    if (!(along > tolerance && along < nearest) || at * length < -tolerance || (1 - at) * length < -tolerance)
      continue;
    if (at * length <= tolerance)
      meetVertex(a);
    else if ((1 - at) * length <= tolerance)
      meetVertex(b);
    else
    {
      nearest = along;
      hit_edge = static_cast<int>(e);
      hit_vertex = -1;
    }
  }
  if (hit_edge >= 0)
    hit_vertex = splitEdge(drawing, hit_edge, s + nearest * d, drawn_points, drawn_edges);
  if (hit_vertex < 0)
    return false;
  drawing.edges.push_back({ v, hit_vertex });
  drawing.edge_sources.push_back(-1);
  drawing.kinds.push_back(Assignment::Flat);
  return true;
}

/// A cut that ends inside the paper (a slit's tip) would leave the face around it turning back
/// on itself there: the cut's line runs on from the tip, flat, to the first line it meets, so
/// the faces beside the tip are straight there. A tip outside the paper meets nothing, or its
/// joint borders no paper and goes.
void extendSlitTips(Drawing& drawing, double tolerance, const std::vector<Vec2>& drawn_points,
                    const std::vector<std::array<int, 2>>& drawn_edges)
{
  std::vector<std::vector<int>> at(drawing.points.size());
  for (size_t e = 0; e < drawing.edges.size(); ++e)
    for (int v : drawing.edges[e])
      at[v].push_back(static_cast<int>(e));
  for (size_t v = 0; v < at.size(); ++v)
    if (at[v].size() == 1 && drawing.kinds[at[v][0]] == Assignment::Cut)
    {
      const auto& edge = drawing.edges[at[v][0]];
      const Vec2 d =
          (drawing.points[v] - drawing.points[edge[0] == static_cast<int>(v) ? edge[1] : edge[0]]).normalized();
      addJoint(drawing, static_cast<int>(v), d, tolerance, drawn_points, drawn_edges);
    }
}

/// Joins every island to its surroundings from its rightmost point rightwards and its leftmost
/// leftwards: what each meets reaches further out, so every face ends up with one boundary, and
/// the two joints together leave none of them a bridge walked on both sides.
void joinIslands(Drawing& drawing, const std::vector<std::vector<int>>& islands, double tolerance,
                 const std::vector<Vec2>& drawn_points, const std::vector<std::array<int, 2>>& drawn_edges,
                 const DrawingNames& names)
{
  const auto by_x = [&](int a, int b) {
    const Vec2 &p = drawing.points[a], &q = drawing.points[b];
    return p.x() < q.x() || (p.x() == q.x() && p.y() < q.y());
  };
  for (double sign : { 1.0, -1.0 })
    for (const std::vector<int>& island : islands)
    {
      const int v = sign > 0 ? *std::max_element(island.begin(), island.end(), by_x) :
                               *std::min_element(island.begin(), island.end(), by_x);
      if (!addJoint(drawing, v, Vec2(sign, 0.0), tolerance, drawn_points, drawn_edges))
        fail("the lines at " + names.point(drawing.sources[v].a) +
             " lie inside a face but nothing surrounds them to join them to");
    }
}

/// Each vertex as one copy per fan of paper around it (fans parted by cut edges and by what is
/// not paper), the faces and edges over those copies.
TracedPaper openedPaper(const Drawing& drawing, const Regions& regions, double min_area, const DrawingNames& names)
{
  const auto& outgoing = regions.rotation.outgoing;
  const auto& next = regions.rotation.next;
  const auto paperLeftOf = [&](int h) { return regions.paper[regions.cycle_of[h]] != 0; };
  const int half_count = 2 * static_cast<int>(drawing.edges.size());
  std::vector<int> copy_of(half_count, -1);  // the copy of its start the face left of h uses
  TracedPaper traced;
  for (size_t v = 0; v < outgoing.size(); ++v)
  {
    const std::vector<int>& around = outgoing[v];
    const int n = static_cast<int>(around.size());
    // Wedge i lies left of around[i]; wedges i - 1 and i share around[i].
    UnionFind fans(n);
    for (int i = 0; i < n; ++i)
    {
      const int previous = (i + n - 1) % n;
      if (paperLeftOf(around[i]) && paperLeftOf(around[previous]) && drawing.kinds[around[i] / 2] != Assignment::Cut)
        fans.join(i, previous);
    }
    std::map<int, int> copy;
    for (int i = 0; i < n; ++i)
    {
      if (!paperLeftOf(around[i]))
        continue;
      const auto [it, added] = copy.emplace(fans.find(i), static_cast<int>(traced.points.size()));
      if (added)
      {
        traced.points.push_back(drawing.points[v]);
        traced.sources.push_back(drawing.sources[v]);
      }
      copy_of[around[i]] = it->second;
    }
  }
  // Edges: one per side of paper, merged where both sides meet the same copies.
  for (size_t e = 0; e < drawing.edges.size(); ++e)
  {
    const int h0 = 2 * static_cast<int>(e), h1 = h0 + 1;
    std::vector<std::array<int, 2>> sides;
    if (paperLeftOf(h0))
      sides.push_back({ copy_of[h0], copy_of[next[h0]] });
    if (paperLeftOf(h1))
      sides.push_back({ copy_of[next[h1]], copy_of[h1] });
    if (sides.size() == 2 && sides[0] == sides[1])
      sides.pop_back();
    if (sides.size() == 2 && drawing.kinds[e] != Assignment::Cut)
      fail(names.edge(drawing.edge_sources[e]) + " has paper on both sides that do not meet along it");
    if (sides.size() == 1 && paperLeftOf(h0) && paperLeftOf(h1) && drawing.kinds[e] == Assignment::Cut)
      fail(names.edge(drawing.edge_sources[e]) + " is a cut that could not be opened");
    for (const auto& side : sides)
    {
      traced.edges.push_back(side);
      traced.edge_sources.push_back(drawing.edge_sources[e]);
    }
  }
  for (size_t c = 0; c < regions.cycles.size(); ++c)
  {
    if (!regions.paper[c] || !(regions.areas[c] > min_area))
      continue;
    std::vector<int> face;
    for (int h : regions.cycles[c])
      face.push_back(copy_of[h]);
    std::vector<int> sorted = face;
    std::sort(sorted.begin(), sorted.end());
    const auto twice = std::adjacent_find(sorted.begin(), sorted.end());
    if (twice != sorted.end())
      fail("a face passes " + names.point(traced.sources[*twice].a) + " twice");
    traced.faces.push_back(std::move(face));
  }
  // A sliver's edges may reach copies no face uses: keep only what faces use.
  std::vector<char> used(traced.points.size(), 0);
  for (const auto& face : traced.faces)
    for (int v : face)
      used[v] = 1;
  std::vector<int> number(traced.points.size(), -1);
  TracedPaper compact;
  for (size_t v = 0; v < traced.points.size(); ++v)
    if (used[v])
    {
      number[v] = static_cast<int>(compact.points.size());
      compact.points.push_back(traced.points[v]);
      compact.sources.push_back(traced.sources[v]);
    }
  for (size_t e = 0; e < traced.edges.size(); ++e)
  {
    const auto [a, b] = traced.edges[e];
    if (a >= 0 && b >= 0 && used[a] && used[b])
    {
      compact.edges.push_back({ number[a], number[b] });
      compact.edge_sources.push_back(traced.edge_sources[e]);
    }
  }
  for (const auto& face : traced.faces)
  {
    std::vector<int> renumbered;
    for (int v : face)
      renumbered.push_back(number[v]);
    compact.faces.push_back(std::move(renumbered));
  }
  return compact;
}

TracedPaper trace(const std::vector<Vec2>& points, const std::vector<std::array<int, 2>>& edges,
                  const std::vector<Assignment>& assignments, double min_area, const DrawingNames& names)
{
  Drawing drawing;
  drawing.points = points;
  for (size_t v = 0; v < points.size(); ++v)
    drawing.sources.push_back({ static_cast<int>(v), static_cast<int>(v), 0.0 });
  drawing.edges = edges;
  for (size_t e = 0; e < edges.size(); ++e)
    drawing.edge_sources.push_back(static_cast<int>(e));
  drawing.kinds = assignments;
  dropLooseCreases(drawing);
  splitLoneCutEdges(drawing, points, edges);
  const double tolerance = 1e-9 * boundingDiagonal(points);
  extendSlitTips(drawing, tolerance, points, edges);
  Regions regions = findRegions(drawing, min_area);
  // A crease with the same paper on both sides (the stick of a ring of creases hung inside a
  // face) folds nothing either: it goes, and what it held becomes an island.
  std::vector<char> sticks(drawing.edges.size(), 0);
  bool any_stick = false;
  for (size_t e = 0; e < drawing.edges.size(); ++e)
  {
    const int left = regions.cycle_of[2 * e], right = regions.cycle_of[2 * e + 1];
    sticks[e] = left == right && regions.paper[left] && drawing.kinds[e] != Assignment::Cut;
    any_stick = any_stick || sticks[e];
  }
  if (any_stick)
  {
    removeEdges(drawing, sticks);
    dropLooseCreases(drawing);
    regions = findRegions(drawing, min_area);
  }
  if (!regions.islands.empty())
  {
    joinIslands(drawing, regions.islands, tolerance, points, edges, names);
    regions = findRegions(drawing, min_area);
    if (!regions.islands.empty())
      fail("lines inside a face could not be joined to the paper around them");
  }
  TracedPaper traced = openedPaper(drawing, regions, min_area, names);
  if (traced.faces.empty())
    fail("the lines enclose no paper");
  return traced;
}

}  // namespace

Expected<TracedPaper> tracePaper(const std::vector<Vec2>& points, const std::vector<std::array<int, 2>>& edges,
                                 const std::vector<Assignment>& assignments, double min_area, const DrawingNames& names)
{
  return guarded<TracedPaper>([&] { return trace(points, edges, assignments, min_area, names); });
}

}  // namespace virtual_origami::core

#include "virtual_origami/core/compliant_faces.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <map>
#include <set>
#include <utility>

#include "virtual_origami/core/convex_partition.h"
#include "virtual_origami/core/planar_geometry.h"

namespace virtual_origami::core
{
namespace
{
/// The smallest angle of the triangle a, b, c.
double smallestAngle(const Vec2& a, const Vec2& b, const Vec2& c)
{
  return std::min({ angleBetween(b - a, c - a), angleBetween(c - b, a - b), angleBetween(a - c, b - c) });
}

/// A (nearly) convex polygon's triangles, cut ear by ear, each time the ear whose smallest angle
/// is the largest (across a band, a strip from one side to the other). An ear's apex turns left,
/// and no other corner lies in it or on its sides: a corner where the polygon runs straight on
/// (a curve drawn finely) is never cut off as a sliver, nor left for last with its neighbours.
/// Empty if no ear is found.
std::vector<std::array<int, 3>> triangulateConvex(const Paper& paper, std::vector<int> polygon)
{
  std::vector<Vec2> corners;
  for (int v : polygon)
    corners.push_back(paper.vertices[v].crease_pattern);
  const double diagonal = boundingDiagonal(corners);
  const double straight = 1e-12 * diagonal * diagonal;
  const auto at = [&](int v) { return paper.vertices[v].crease_pattern; };
  std::vector<std::array<int, 3>> triangles;
  while (polygon.size() > 3)
  {
    const size_t n = polygon.size();
    size_t best = n;
    double best_angle = -1.0;
    for (size_t i = 0; i < n; ++i)
    {
      const int a = polygon[(i + n - 1) % n], b = polygon[i], c = polygon[(i + 1) % n];
      if (cross2(at(b) - at(a), at(c) - at(b)) <= straight)
        continue;
      bool empty = true;
      for (size_t k = 0; k < n && empty; ++k)
      {
        const Vec2 q = at(polygon[k]);
        const int v = polygon[k];
        if (v == a || v == b || v == c)
          continue;
        empty = !(cross2(at(b) - at(a), q - at(a)) >= -straight && cross2(at(c) - at(b), q - at(b)) >= -straight &&
                  cross2(at(a) - at(c), q - at(c)) >= -straight);
      }
      const double angle = empty ? smallestAngle(at(a), at(b), at(c)) : -1.0;
      if (empty && angle > best_angle)
      {
        best_angle = angle;
        best = i;
      }
    }
    if (best == n)
      return {};
    triangles.push_back({ polygon[(best + n - 1) % n], polygon[best], polygon[(best + 1) % n] });
    polygon.erase(polygon.begin() + static_cast<long>(best));
  }
  triangles.push_back({ polygon[0], polygon[1], polygon[2] });
  return triangles;
}

/// Lawson's flips over the facets (edges inside compliant faces, between two triangles): each
/// flipped where the two triangles' smallest angle grows, until none does — the constrained
/// Delaunay triangulation of each compliant face, whose sides and creases stay. A band cut into
/// convex pieces at load has slivers (three corners of a finely drawn curve) that no bending
/// stiffness can hold; flipped, its triangles span the band.
void flipToDelaunay(Paper& paper, const std::vector<char>& facet)
{
  const auto at = [&](int v) { return paper.vertices[v].crease_pattern; };
  const auto third = [&](int f, int u, int v) {
    for (int w : paper.faces[f].vertices)
      if (w != u && w != v)
        return w;
    return -1;
  };
  std::map<std::pair<int, int>, int> edge_of;
  for (size_t e = 0; e < paper.edges.size(); ++e)
    edge_of[std::minmax(paper.edges[e].vertices[0], paper.edges[e].vertices[1])] = static_cast<int>(e);
  std::vector<int> queue;
  std::vector<char> queued(paper.edges.size(), 0);
  for (size_t e = 0; e < paper.edges.size(); ++e)
    if (facet[e])
    {
      queue.push_back(static_cast<int>(e));
      queued[e] = 1;
    }
  const double scale = paper.scale();
  const double straight = 1e-12 * scale * scale;
  for (size_t guard = 0; !queue.empty() && guard < 100 * paper.edges.size(); ++guard)
  {
    const int e = queue.back();
    queue.pop_back();
    queued[e] = 0;
    Edge& edge = paper.edges[e];
    const int left = edge.faces[0], right = edge.faces[1];
    if (paper.faces[left].vertices.size() != 3 || paper.faces[right].vertices.size() != 3)
      continue;
    const int u = edge.vertices[0], v = edge.vertices[1];
    const int p = third(left, u, v), q = third(right, u, v);
    // The quadrilateral u, q, v, p (counter-clockwise) must be strictly convex at u and v.
    if (cross2(at(u) - at(p), at(q) - at(u)) <= straight || cross2(at(v) - at(q), at(p) - at(v)) <= straight)
      continue;
    const double now = std::min(smallestAngle(at(u), at(v), at(p)), smallestAngle(at(v), at(u), at(q)));
    const double flipped = std::min(smallestAngle(at(u), at(q), at(p)), smallestAngle(at(q), at(v), at(p)));
    if (!(flipped > now + 1e-12))
      continue;
    paper.faces[left].vertices = { u, q, p };
    paper.faces[right].vertices = { q, v, p };
    edge_of.erase(std::minmax(u, v));
    edge.vertices = { q, p };
    edge_of[std::minmax(q, p)] = e;
    edge.faces = { left, right };  // left of q→p: u, q, p
    // The quadrilateral's sides: u–q and v–p changed triangles.
    const int uq = edge_of.at(std::minmax(u, q)), vp = edge_of.at(std::minmax(v, p));
    for (int k = 0; k < 2; ++k)
    {
      if (paper.edges[uq].faces[k] == right)
        paper.edges[uq].faces[k] = left;
      if (paper.edges[vp].faces[k] == left)
        paper.edges[vp].faces[k] = right;
    }
    for (int side : { uq, vp, edge_of.at(std::minmax(q, v)), edge_of.at(std::minmax(p, u)) })
      if (facet[side] && !queued[side])
      {
        queue.push_back(side);
        queued[side] = 1;
      }
  }
}

/// Distance of p from the line through a and b, in the crease pattern.
double fromLine(const Vec2& a, const Vec2& b, const Vec2& p)
{
  const Vec2 axis = b - a;
  const double length = axis.norm();
  return length > 0 ? std::abs(cross2(axis, p - a)) / length : (p - a).norm();
}
/// Cuts every face marked compliant (whole faces of the file) into triangles and makes every
/// split edge between two compliant faces a facet.
CompliantFaces cutIntoFacets(Paper& paper, std::vector<char> compliant, const std::vector<int>& file_face)
{
  CompliantFaces made;
  const size_t face_count = paper.faces.size();
  // Each compliant face cut into triangles; the new edges inside it are its diagonals.
  std::vector<char> counted(face_count, 0);
  bool to_cut = false;
  for (size_t f = 0; f < face_count; ++f)
    if (compliant[f])
    {
      const int body = file_face[f];
      made.bodies += counted[body] ? 0 : 1;
      counted[body] = 1;
      to_cut = to_cut || paper.faces[f].vertices.size() > 3;
    }
  if (made.bodies == 0)
    return made;
  // Cut on a copy: the paper changes only if the cut is linked.
  Paper cut = to_cut ? paper : Paper{};
  Paper& out = to_cut ? cut : paper;
  for (size_t f = 0; f < face_count; ++f)
  {
    if (!compliant[f])
      continue;
    const std::vector<int> polygon = out.faces[f].vertices;
    if (polygon.size() <= 3)
    {
      ++made.triangles;
      continue;
    }
    const std::vector<std::array<int, 3>> triangles = triangulateConvex(out, polygon);
    if (triangles.empty())
      return CompliantFaces{};  // coincident corners: left as it was
    // The triangle with the face's first side keeps its number and first vertex.
    size_t keep = 0;
    for (size_t t = 0; t < triangles.size(); ++t)
      for (int k = 0; k < 3; ++k)
        if (triangles[t][k] == polygon[0] && triangles[t][(k + 1) % 3] == polygon[1])
          keep = t;
    std::set<std::pair<int, int>> diagonals;
    for (size_t t = 0; t < triangles.size(); ++t)
    {
      std::vector<int> cycle(triangles[t].begin(), triangles[t].end());
      if (t == keep)
        out.faces[f].vertices = startingAt(cycle, polygon[0]);
      else
      {
        out.faces.push_back({ cycle, {} });
        compliant.push_back(1);
      }
      for (int k = 0; k < 3; ++k)
      {
        const int u = cycle[k], v = cycle[(k + 1) % 3];
        const size_t i = std::find(polygon.begin(), polygon.end(), u) - polygon.begin();
        const bool side =
            polygon[(i + 1) % polygon.size()] == v || polygon[(i + polygon.size() - 1) % polygon.size()] == v;
        if (!side && diagonals.insert(std::minmax(u, v)).second)
        {
          Edge edge;
          edge.vertices = { u, v };
          edge.assignment = Assignment::Flat;
          edge.split = true;
          out.edges.push_back(edge);
        }
      }
    }
    made.triangles += static_cast<int>(triangles.size());
  }
  // Cutting convex faces along their own diagonals keeps every edge between two faces.
  if (to_cut && !linkTopology(out))
    return CompliantFaces{};
  // Every split edge inside a compliant face bends.
  std::vector<char> facet(out.edges.size(), 0);
  for (size_t e = 0; e < out.edges.size(); ++e)
  {
    Edge& edge = out.edges[e];
    if (edge.split && edge.isCrease() && compliant[edge.faces[0]] && compliant[edge.faces[1]])
    {
      if (!edge.target_angle)
        edge.target_angle = 0.0;
      facet[e] = 1;
      ++made.facets;
    }
  }
  if (to_cut)
  {
    flipToDelaunay(out, facet);
    if (!linkTopology(out))
      return CompliantFaces{};
  }
  if (to_cut)
    paper = std::move(cut);
  return made;
}
/// For each face, the one that stands for its face of the file (pieces joined by split edges).
std::vector<int> fileFaces(const Paper& paper)
{
  std::vector<int> parent(paper.faces.size());
  for (size_t f = 0; f < parent.size(); ++f)
    parent[f] = static_cast<int>(f);
  const std::function<int(int)> root = [&](int f) { return parent[f] == f ? f : parent[f] = root(parent[f]); };
  for (const Edge& e : paper.edges)
    if (e.split && e.isCrease())
      parent[root(e.faces[0])] = root(e.faces[1]);
  for (size_t f = 0; f < parent.size(); ++f)
    root(static_cast<int>(f));
  return parent;
}
}  // namespace

CompliantFaces makeLockedFacesCompliant(Paper& paper)
{
  CompliantFaces made;
  // Two convex faces meet along one straight side: only a face of the file in pieces can lock.
  // (Every preview frame asks: a pattern without one answers at the cost of one pass.)
  if (std::none_of(paper.edges.begin(), paper.edges.end(), [](const Edge& e) { return e.split && e.isCrease(); }))
    return made;
  const size_t face_count = paper.faces.size();
  // The faces of the file: pieces joined by split edges.
  const std::vector<int> file_face = fileFaces(paper);
  const auto root = [&](int f) { return file_face[f]; };
  std::vector<int> pieces(face_count, 0);
  for (size_t f = 0; f < face_count; ++f)
    ++pieces[root(static_cast<int>(f))];

  // Two rigid bodies turn about one axis: the creases between them must lie on one line. Off it
  // by a thousandth of the sheet or less is a drawing's rounding (the straight creases of Origami
  // Simulator's library lie within 8e-4 of theirs; its curves' pieces further than 1e-3 from
  // their neighbours' lines), which costs a rigid fold little strain.
  const double tolerance = 1e-3 * paper.scale();
  std::vector<char> locked(face_count, 0);
  std::map<std::pair<int, int>, int> first_crease;  // per pair of bodies, the first crease between them
  for (size_t e = 0; e < paper.edges.size(); ++e)
  {
    const Edge& edge = paper.edges[e];
    if (!edge.isCrease() || edge.split)
      continue;
    const int a = root(edge.faces[0]), b = root(edge.faces[1]);
    if (pieces[a] == 1 && pieces[b] == 1)
      continue;
    if (a == b)
    {
      locked[a] = 1;
      continue;
    }
    const auto [at, added] = first_crease.emplace(std::minmax(a, b), static_cast<int>(e));
    if (added)
      continue;
    const Edge& first = paper.edges[at->second];
    const Vec2 p = paper.vertices[first.vertices[0]].crease_pattern;
    const Vec2 q = paper.vertices[first.vertices[1]].crease_pattern;
    if (fromLine(p, q, paper.vertices[edge.vertices[0]].crease_pattern) > tolerance ||
        fromLine(p, q, paper.vertices[edge.vertices[1]].crease_pattern) > tolerance)
      locked[a] = locked[b] = 1;
  }

  std::vector<char> compliant(face_count, 0);
  for (size_t f = 0; f < face_count; ++f)
    compliant[f] = locked[root(static_cast<int>(f))];
  return cutIntoFacets(paper, compliant, file_face);
}

CompliantFaces makeFacesCompliant(Paper& paper, const std::vector<int>& faces)
{
  const size_t face_count = paper.faces.size();
  const std::vector<int> file_face = fileFaces(paper);
  const auto root = [&](int f) { return file_face[f]; };
  // Faces of the file already compliant stay as they are: only the others are new.
  std::vector<char> bending(face_count, 0), body(face_count, 0);
  for (const Edge& e : paper.edges)
    if (isFacet(e))
      bending[root(e.faces[0])] = 1;
  for (int f : faces)
    if (f >= 0 && static_cast<size_t>(f) < face_count && !bending[root(f)])
      body[root(f)] = 1;
  std::vector<char> compliant(face_count, 0);
  for (size_t f = 0; f < face_count; ++f)
    compliant[f] = body[root(static_cast<int>(f))];
  return cutIntoFacets(paper, compliant, file_face);
}

int compliantFaceCount(const Paper& paper)
{
  const std::vector<int> file_face = fileFaces(paper);
  std::vector<char> bending(file_face.size(), 0);
  for (const Edge& e : paper.edges)
    if (isFacet(e))
      bending[file_face[e.faces[0]]] = 1;
  return static_cast<int>(std::count(bending.begin(), bending.end(), 1));
}

}  // namespace virtual_origami::core

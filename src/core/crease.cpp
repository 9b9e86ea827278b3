#include "virtual_origami/core/crease.h"

#include <cmath>
#include <map>
#include <set>
#include <sstream>
#include <string>

#include <Eigen/Geometry>

#include "virtual_origami/core/face_orders.h"
#include "virtual_origami/core/geometry.h"
#include "virtual_origami/core/planar_geometry.h"

namespace virtual_origami::core
{
namespace
{
/// Sharpest corner a cut may leave in a piece of a face, in radians.
constexpr double kMinCutAngle = 1e-5;
/// Smallest area of a piece of a face a cut may leave, relative to the sheet's area.
constexpr double kMinPieceArea = 1e-9;

/// The part of a plane a crease cuts with: a strip (no eye) or a wedge from the eye.
struct CutRegion
{
  Vec3 normal = Vec3::UnitZ();  // unit normal of the cutting plane
  Vec3 origin = Vec3::Zero();   // a point on the plane
  // Strip: 0 ≤ (p − origin)·across ≤ width.  Wedge: p − eye = a·ray_a + b·ray_b, a, b ≥ 0.
  bool wedge = false;
  Vec3 across = Vec3::Zero();
  double width = 0.0;
  Vec3 ray_a = Vec3::Zero(), ray_b = Vec3::Zero();

  double signedDistance(const Vec3& p) const { return normal.dot(p - origin); }

  bool contains(const Vec3& p, double tolerance) const
  {
    if (!wedge)
    {
      const double s = (p - origin).dot(across);
      return s >= -tolerance && s <= width + tolerance;
    }
    // Inside the wedge: on the inner side of both bounding rays.
    const Vec3 q = p - origin;
    const double side_a = normal.dot(ray_a.cross(q));
    const double side_b = normal.dot(q.cross(ray_b));
    const double ahead = q.dot(ray_a + ray_b);
    return side_a >= -tolerance && side_b >= -tolerance && ahead > 0;
  }
};

/// The face the line is drawn on: under its midpoint (or nearest it), topmost.
int faceUnderLine(const Paper& paper, const Vec3& start, const Vec3& end)
{
  const double reach = 0.05 * paper.scale();
  for (double t : { 0.5, 0.25, 0.75, 0.0, 1.0 })
  {
    const int f = faceAt(paper, start + t * (end - start), reach);
    if (f >= 0)
      return f;
  }
  return -1;
}

Expected<CutRegion> makeRegion(const Paper& paper, const Vec3& start, const Vec3& end,
                               const std::optional<Vec3>& eye_point)
{
  const Vec3 line = end - start;
  CutRegion region;
  region.origin = start;
  if (eye_point)
  {
    const Vec3& eye = *eye_point;
    region.wedge = true;
    region.origin = eye;
    region.ray_a = (start - eye).normalized();
    region.ray_b = (end - eye).normalized();
    const Vec3 n = region.ray_a.cross(region.ray_b);
    if (n.norm() < 1e-9)
      return Expected<CutRegion>::failure("the eye point lies on the crease line: the two rays coincide");
    region.normal = n.normalized();
    return region;
  }
  const int top = faceUnderLine(paper, start, end);
  if (top < 0)
    return Expected<CutRegion>::failure("the crease line misses the paper");
  const Vec3 face_normal = paper.faceNormal(top);
  const Vec3 n = line.cross(face_normal);
  if (n.norm() < 1e-9 * line.norm())
    return Expected<CutRegion>::failure("the crease line is perpendicular to the face under it");
  region.normal = n.normalized();
  region.across = (line - line.dot(face_normal) * face_normal).normalized();
  region.width = line.dot(region.across);
  return region;
}

/// A point where the cutting plane meets a face's boundary: a vertex, or inside an edge.
struct Crossing
{
  int vertex = -1;  // on an existing vertex
  int edge = -1;    // else inside this edge, at parameter t from vertices[0]
  double t = 0.0;
  Vec3 point = Vec3::Zero();
  bool operator==(const Crossing& o) const { return vertex == o.vertex && edge == o.edge; }
};

struct FaceCut
{
  int face = -1;
  std::array<Crossing, 2> ends;
};

class Creaser
{
public:
  Creaser(Paper& paper, const CutRegion& region) : paper_(paper), region_(region)
  {
    scale_ = paper.scale();
    plane_tol_ = 1e-9 * scale_;
    region_tol_ = 1e-7 * scale_;
    snap_tol_ = 1e-6 * scale_;
  }

  Expected<CreaseResult> run()
  {
    classifyVertices();
    std::vector<FaceCut> cuts;
    bool along_edge = false, partial = false;
    for (size_t f = 0; f < paper_.faces.size(); ++f)
    {
      std::vector<Crossing> xs = crossings(static_cast<int>(f));
      if (xs.size() < 2)
        continue;
      bool inside = true;
      for (const Crossing& c : xs)
        inside = inside && region_.contains(c.point, region_tol_);
      if (alongSide(static_cast<int>(f), xs))
      {
        (inside ? along_edge : partial) = true;
        if (inside)
          collectSplitEdgesOnPlane(static_cast<int>(f));
        continue;
      }
      if (xs.size() > 2 || !inside)
      {
        partial = true;
        continue;
      }
      if (sliver(static_cast<int>(f), xs[0], xs[1]))
      {
        along_edge = true;  // a cut a hair off a side would leave a sliver: it runs along it
        continue;
      }
      cuts.push_back({ static_cast<int>(f), { xs[0], xs[1] } });
    }
    if (cuts.empty() && split_edges_.empty())
    {
      if (along_edge)
        return Expected<CreaseResult>::failure("the crease line runs along an existing edge: nothing new to crease");
      if (partial)
        return Expected<CreaseResult>::failure(
            "the crease line does not cross any face completely (seed 000 makes only creases that split a face)");
      return Expected<CreaseResult>::failure("the crease line misses the paper");
    }
    CreaseResult result;
    // An edge added on reading only to make a concave face convex becomes the crease asked for.
    for (int e : split_edges_)
    {
      paper_.edges[e].split = false;
      paper_.edges[e].assignment = Assignment::Unassigned;
      result.new_edges.push_back(e);
    }
    for (FaceCut& cut : cuts)
      for (Crossing& c : cut.ends)
        if (c.vertex < 0)
          c.vertex = splitEdge(c, result);
    const int first_new_face = static_cast<int>(paper_.faces.size());
    for (const FaceCut& cut : cuts)
      splitFace(cut, result);
    const Status linked = linkTopology(paper_);
    if (!linked)
      return Expected<CreaseResult>::failure("internal error while creasing: " + linked.message());
    // Both halves of a split face keep its place in the layer order, with the faces they
    // still overlap.
    for (size_t k = 0; k < cuts.size(); ++k)
      inheritFaceOrders(paper_, cuts[k].face, first_new_face + static_cast<int>(k));
    if (!paper_.face_orders.empty())
      pruneFaceOrders(paper_, region_tol_);
    return result;
  }

private:
  void classifyVertices()
  {
    side_.resize(paper_.vertices.size());
    distance_.resize(paper_.vertices.size());
    for (size_t v = 0; v < paper_.vertices.size(); ++v)
    {
      distance_[v] = region_.signedDistance(paper_.vertices[v].folded);
      side_[v] = distance_[v] > plane_tol_ ? 1 : distance_[v] < -plane_tol_ ? -1 : 0;
    }
    // A crossing a hair from an edge's end is that end: a new vertex there would make an edge
    // too short for any solver's strain measure, or a corner piece with no area (fuzzing).
    for (const Edge& edge : paper_.edges)
    {
      const int a = edge.vertices[0], b = edge.vertices[1];
      if (side_[a] * side_[b] >= 0)
        continue;
      const double t = distance_[a] / (distance_[a] - distance_[b]);
      const double length = (paper_.vertices[b].crease_pattern - paper_.vertices[a].crease_pattern).norm();
      if (t * length < snap_tol_)
        side_[a] = 0;
      else if ((1 - t) * length < snap_tol_)
        side_[b] = 0;
    }
  }

  /// Where the plane meets the face boundary, in cycle order, without repeats.
  std::vector<Crossing> crossings(int face) const
  {
    const Face& f = paper_.faces[face];
    const size_t n = f.vertices.size();
    std::vector<Crossing> xs;
    for (size_t i = 0; i < n; ++i)
    {
      const int a = f.vertices[i], b = f.vertices[(i + 1) % n];
      if (side_[a] == 0)
        xs.push_back({ a, -1, 0.0, paper_.vertices[a].folded });
      if (side_[a] * side_[b] < 0)
      {
        const int e = f.edges[i];
        const Edge& edge = paper_.edges[e];
        const int e0 = edge.vertices[0], e1 = edge.vertices[1];
        // Parameter from the edge's own first vertex, so both faces of the edge agree.
        const double t = distance_[e0] / (distance_[e0] - distance_[e1]);
        const Vec3 p = paper_.vertices[e0].folded + t * (paper_.vertices[e1].folded - paper_.vertices[e0].folded);
        xs.push_back({ -1, e, t, p });
      }
    }
    return xs;
  }

  Vec2 creasePatternPoint(const Crossing& c) const
  {
    if (c.vertex >= 0)
      return paper_.vertices[c.vertex].crease_pattern;
    const Edge& edge = paper_.edges[c.edge];
    const Vec2& a = paper_.vertices[edge.vertices[0]].crease_pattern;
    return a + c.t * (paper_.vertices[edge.vertices[1]].crease_pattern - a);
  }

  /// Area of the piece of the face from crossing `from` counter-clockwise round to `to`,
  /// closed by the chord: a triangle fan from `from`.
  double pieceArea(int face, const Crossing& from, const Vec2& p_from, const Crossing& to, const Vec2& p_to) const
  {
    const Face& f = paper_.faces[face];
    const size_t n = f.vertices.size();
    // The first boundary vertex after `from`, going counter-clockwise.
    size_t i = 0;
    if (from.vertex >= 0)
    {
      while (f.vertices[i] != from.vertex)
        ++i;
      i = (i + 1) % n;
    }
    else
    {
      while (f.edges[i] != from.edge)
        ++i;
      i = (i + 1) % n;
    }
    std::vector<Vec2> polygon{ p_from };
    for (size_t k = 0; k < n; ++k, i = (i + 1) % n)
    {
      const int v = f.vertices[i];
      if (v == to.vertex)
        break;
      polygon.push_back(paper_.vertices[v].crease_pattern);
      if (to.vertex < 0 && f.edges[i] == to.edge)
        break;
    }
    polygon.push_back(p_to);
    double twice = 0.0;
    for (size_t k = 1; k + 1 < polygon.size(); ++k)
    {
      const Vec2 u = polygon[k] - polygon[0], w = polygon[k + 1] - polygon[0];
      twice += cross2(u, w);
    }
    return 0.5 * std::abs(twice);
  }

  /// True when cutting the face from `a` to `b` would leave a piece with almost no area or a
  /// corner sharper than kMinCutAngle (a line a hair off a side or a corner): such slivers
  /// break the solvers' strain measure and FOLD readers (ours refuses corners under 1e-6 rad
  /// and faces under 1e-12 of the squared diagonal). Found by fuzzing.
  bool sliver(int face, const Crossing& a, const Crossing& b) const
  {
    const Vec2 pa = creasePatternPoint(a), pb = creasePatternPoint(b);
    if (std::min(pieceArea(face, a, pa, b, pb), pieceArea(face, b, pb, a, pa)) < kMinPieceArea * scale_ * scale_)
      return true;
    const std::vector<int>& vs = paper_.faces[face].vertices;
    const size_t n = vs.size();
    for (const auto& [end, chord] : { std::pair(a, Vec2(pb - pa)), std::pair(b, Vec2(pa - pb)) })
    {
      std::array<Vec2, 2> sides;  // along the face's boundary, both ways from the cut's end
      if (end.vertex >= 0)
      {
        size_t i = 0;
        while (vs[i] != end.vertex)
          ++i;
        const Vec2& here = paper_.vertices[end.vertex].crease_pattern;
        sides = { paper_.vertices[vs[(i + n - 1) % n]].crease_pattern - here,
                  paper_.vertices[vs[(i + 1) % n]].crease_pattern - here };
      }
      else
      {
        const Edge& edge = paper_.edges[end.edge];
        const Vec2 along = paper_.vertices[edge.vertices[1]].crease_pattern -
                           paper_.vertices[edge.vertices[0]].crease_pattern;
        sides = { along, Vec2(-along) };
      }
      for (const Vec2& side : sides)
        if (angleBetween(chord, side) < kMinCutAngle)
          return true;
    }
    return false;
  }

  /// True when every crossing is a vertex and they run along one side of the face.
  bool alongSide(int face, const std::vector<Crossing>& xs) const
  {
    for (const Crossing& c : xs)
      if (c.vertex < 0)
        return false;
    return chainOnPlane(face, xs.front().vertex, xs.back().vertex) ||
           chainOnPlane(face, xs.back().vertex, xs.front().vertex);
  }

  /// Notes the face's split edges (Edge::split) that lie on the plane.
  void collectSplitEdgesOnPlane(int face)
  {
    const Face& f = paper_.faces[face];
    for (size_t i = 0; i < f.vertices.size(); ++i)
    {
      const Edge& edge = paper_.edges[f.edges[i]];
      if (edge.split && side_[edge.vertices[0]] == 0 && side_[edge.vertices[1]] == 0 &&
          region_.contains(paper_.vertices[edge.vertices[0]].folded, region_tol_) &&
          region_.contains(paper_.vertices[edge.vertices[1]].folded, region_tol_))
        split_edges_.insert(f.edges[i]);
    }
  }

  bool chainOnPlane(int face, int from, int to) const
  {
    const std::vector<int>& vs = paper_.faces[face].vertices;
    const size_t n = vs.size();
    size_t i = 0;
    while (vs[i] != from)
      ++i;
    for (size_t k = 0; k < n; ++k)
    {
      const int v = vs[(i + k) % n];
      if (side_[v] != 0)
        return false;
      if (v == to)
        return true;
    }
    return false;
  }

  /// Splits an edge at a crossing once (both faces share the new vertex); returns the vertex.
  int splitEdge(const Crossing& c, CreaseResult& result)
  {
    auto known = split_vertex_.find(c.edge);
    if (known != split_vertex_.end())
      return known->second;
    const int e = c.edge;
    const int a = paper_.edges[e].vertices[0], b = paper_.edges[e].vertices[1];
    Vertex v;
    v.crease_pattern = paper_.vertices[a].crease_pattern + c.t * (paper_.vertices[b].crease_pattern -
                                                                  paper_.vertices[a].crease_pattern);
    v.folded = c.point;
    const int m = static_cast<int>(paper_.vertices.size());
    paper_.vertices.push_back(v);
    result.new_vertices.push_back(m);
    // The edge keeps its id for a–m; m–b is new, with the same assignment and angle.
    Edge tail = paper_.edges[e];
    tail.vertices = { m, b };
    paper_.edges[e].vertices = { a, m };
    paper_.edges.push_back(tail);
    // Every face using a–b now passes through m.
    for (Face& face : paper_.faces)
    {
      const size_t n = face.vertices.size();
      for (size_t i = 0; i < n; ++i)
      {
        const int p = face.vertices[i], q = face.vertices[(i + 1) % n];
        if ((p == a && q == b) || (p == b && q == a))
        {
          face.vertices.insert(face.vertices.begin() + static_cast<long>(i) + 1, m);
          break;
        }
      }
    }
    split_vertex_[e] = m;
    return m;
  }

  void splitFace(const FaceCut& cut, CreaseResult& result)
  {
    const std::vector<int> cycle = paper_.faces[cut.face].vertices;
    const size_t n = cycle.size();
    size_t i = 0, j = 0;
    while (cycle[i] != cut.ends[0].vertex)
      ++i;
    while (cycle[j] != cut.ends[1].vertex)
      ++j;
    std::vector<int> first, second;
    for (size_t k = i;; k = (k + 1) % n)
    {
      first.push_back(cycle[k]);
      if (k == j)
        break;
    }
    for (size_t k = j;; k = (k + 1) % n)
    {
      second.push_back(cycle[k]);
      if (k == i)
        break;
    }
    paper_.faces[cut.face].vertices = first;
    paper_.faces.push_back({ second, {} });
    Edge crease_edge;
    crease_edge.vertices = { cut.ends[0].vertex, cut.ends[1].vertex };
    crease_edge.assignment = Assignment::Unassigned;
    crease_edge.fold_angle = 0.0;
    result.new_edges.push_back(static_cast<int>(paper_.edges.size()));
    result.split_faces.push_back(cut.face);
    paper_.edges.push_back(crease_edge);
  }

  Paper& paper_;
  const CutRegion& region_;
  double scale_ = 1.0, plane_tol_ = 0.0, region_tol_ = 0.0, snap_tol_ = 0.0;
  std::vector<int> side_;
  std::vector<double> distance_;
  std::map<int, int> split_vertex_;
  std::set<int> split_edges_;  // split edges the line runs along
};

/// A point of the request farther than this many sheet sizes from the paper is refused: no
/// line drawn on the paper needs it, and the cut's products of such coordinates overflow (ends
/// at 1e308 made NaN distances, refused as a line "along an existing edge").
constexpr double kFarthest = 1e3;

/// Why `point` (named `what`) cannot be creased with, or empty when it can.
std::string unusablePoint(const Paper& paper, const Vec3& point, const std::string& what)
{
  if (!point.allFinite())
    return what + " is not a finite point";
  if (paper.vertices.empty())
    return {};
  Vec3 low = paper.vertices[0].folded, high = low;
  for (const Vertex& v : paper.vertices)
  {
    low = low.cwiseMin(v.folded);
    high = high.cwiseMax(v.folded);
  }
  // Componentwise, so nothing squares the coordinates (1e308² overflows).
  const double outside = (low - point).cwiseMax(point - high).cwiseMax(0.0).lpNorm<Eigen::Infinity>();
  if (outside <= kFarthest * paper.scale())
    return {};
  std::ostringstream msg;
  msg << what << " lies far outside the paper (at " << point.x() << ", " << point.y() << ", " << point.z()
      << "; more than " << kFarthest << " times the sheet's size from it)";
  return msg.str();
}
}  // namespace

Expected<CreaseResult> crease(Paper& paper, const CreaseRequest& request, const SnapSettings& snap_settings)
{
  std::string problem = unusablePoint(paper, request.start, "the crease line's start");
  if (problem.empty())
    problem = unusablePoint(paper, request.end, "the crease line's end");
  if (problem.empty() && request.eye)
    problem = unusablePoint(paper, *request.eye, "the eye point");
  if (!problem.empty())
    return Expected<CreaseResult>::failure(problem);
  // The line's ends, snapped when asked (the eye point is never snapped).
  Vec3 start = request.start, end = request.end;
  Snap start_snap, end_snap;
  if (request.snap)
  {
    start_snap = snapPoint(paper, request.start, snap_settings);
    start = start_snap.point;
    end_snap = snapPoint(paper, request.end, snap_settings, start_snap.kind == SnapKind::Vertex ? start_snap.vertex : -1);
    end = end_snap.point;
  }
  if ((end - start).norm() < 1e-9 * paper.scale())
    return Expected<CreaseResult>::failure("the crease line has zero length");
  const Expected<CutRegion> region = makeRegion(paper, start, end, request.eye);
  if (!region)
    return Expected<CreaseResult>::failure(region.message());
  Paper next = paper;
  Expected<CreaseResult> result = Creaser(next, *region).run();
  if (!result)
    return result;
  result->start_snap = start_snap;
  result->end_snap = end_snap;
  paper = std::move(next);
  return result;
}

}  // namespace virtual_origami::core

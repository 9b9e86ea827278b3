#include "virtual_origami/core/kept_bend.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <sstream>

#include <Eigen/Geometry>

#include "virtual_origami/core/compliant_faces.h"
#include "virtual_origami/core/flat_fold.h"
#include "virtual_origami/core/metrics.h"

namespace virtual_origami::core
{
namespace
{
using Failure = Expected<KeptBend>;

std::string at(const Vec2& p)
{
  std::ostringstream s;
  s << "(" << p.x() << ", " << p.y() << ")";
  return s.str();
}

double cross(const Vec2& a, const Vec2& b)
{
  return a.x() * b.y() - a.y() * b.x();
}

/// Twice the signed area of the triangle, counter-clockwise positive.
double signedArea2(const Vec2& a, const Vec2& b, const Vec2& c)
{
  return cross(b - a, c - a);
}

/// Whether `p` lies in the convex face (its sides included, within `tolerance`).
bool inFace(const Paper& paper, int face, const Vec2& p, double tolerance)
{
  const std::vector<int>& cycle = paper.faces[face].vertices;
  for (size_t i = 0; i < cycle.size(); ++i)
  {
    const Vec2& a = paper.vertices[cycle[i]].crease_pattern;
    const Vec2& b = paper.vertices[cycle[(i + 1) % cycle.size()]].crease_pattern;
    const double length = (b - a).norm();
    if (length > 0 && cross(b - a, p - a) / length < -tolerance)
      return false;
  }
  return true;
}

/// The paper vertex each sheet point lies on (within `tolerance`), or -1; and for each paper
/// vertex its point, or -1.
struct VertexPoints
{
  std::vector<int> vertex_of_point;
  std::vector<int> point_of_vertex;
};

VertexPoints matchVertices(const Paper& paper, const BentSheet& sheet, double tolerance)
{
  VertexPoints out{ std::vector<int>(sheet.points.size(), -1), std::vector<int>(paper.vertices.size(), -1) };
  std::vector<int> by_x(sheet.points.size());
  std::iota(by_x.begin(), by_x.end(), 0);
  std::sort(by_x.begin(), by_x.end(), [&](int a, int b) { return sheet.points[a].x() < sheet.points[b].x(); });
  for (size_t v = 0; v < paper.vertices.size(); ++v)
  {
    const Vec2& p = paper.vertices[v].crease_pattern;
    auto it = std::lower_bound(by_x.begin(), by_x.end(), p.x() - tolerance,
                               [&](int k, double x) { return sheet.points[k].x() < x; });
    for (; it != by_x.end() && sheet.points[*it].x() <= p.x() + tolerance; ++it)
      if ((sheet.points[*it] - p).norm() <= tolerance && out.vertex_of_point[*it] < 0)
      {
        out.vertex_of_point[*it] = static_cast<int>(v);
        out.point_of_vertex[v] = *it;
        break;
      }
  }
  return out;
}

/// How far the points lie off the rigid motion that places their crease-pattern points best.
double offRigid(const BentSheet& sheet, const std::vector<int>& points)
{
  Eigen::Matrix3Xd from(3, points.size()), to(3, points.size());
  for (size_t i = 0; i < points.size(); ++i)
  {
    const Vec2& p = sheet.points[points[i]];
    from.col(static_cast<Eigen::Index>(i)) = Vec3(p.x(), p.y(), 0.0);
    to.col(static_cast<Eigen::Index>(i)) = sheet.positions[points[i]];
  }
  Eigen::Isometry3d motion;
  motion.matrix() = Eigen::umeyama(from, to, false);
  double largest = 0.0;
  for (size_t i = 0; i < points.size(); ++i)
    largest = std::max(largest,
                       (motion * from.col(static_cast<Eigen::Index>(i)) - to.col(static_cast<Eigen::Index>(i))).norm());
  return largest;
}

std::pair<int, int> key(int a, int b)
{
  return { std::min(a, b), std::max(a, b) };
}

}  // namespace

std::vector<char> keptBendFaces(const Paper& paper)
{
  std::vector<char> kept(paper.faces.size(), 0);
  for (const Edge& e : paper.edges)
    if (isFacet(e) && *e.target_angle != 0.0)
      for (int f : e.faces)
        kept[f] = 1;
  return kept;
}

Expected<KeptBend> keepBend(Paper& paper, const BentSheet& sheet)
{
  const double scale = paper.scale();
  const double tolerance = 1e-9 * scale;
  const size_t n = sheet.points.size();
  if (n == 0 || sheet.triangles.empty())
    return Failure::failure("the bent sheet is empty: nothing to keep");
  if (sheet.positions.size() != n)
    return Failure::failure("the bent sheet has " + std::to_string(n) + " points but " +
                            std::to_string(sheet.positions.size()) + " positions");
  for (size_t k = 0; k < n; ++k)
    if (!sheet.points[k].allFinite() || !sheet.positions[k].allFinite())
      return Failure::failure("point " + std::to_string(k) + " of the bent sheet is not a finite point");

  // Every paper vertex is a node of the sheet.
  const VertexPoints match = matchVertices(paper, sheet, tolerance);
  for (size_t v = 0; v < paper.vertices.size(); ++v)
    if (match.point_of_vertex[v] < 0)
      return Failure::failure("the bent sheet has no point at vertex " + std::to_string(v) + " " +
                              at(paper.vertices[v].crease_pattern) + ": it is not this paper's sheet");

  // Each triangle inside one face, and the faces covered.
  std::vector<std::vector<int>> triangles_of(paper.faces.size());
  std::vector<double> covered(paper.faces.size(), 0.0);
  for (size_t t = 0; t < sheet.triangles.size(); ++t)
  {
    const std::array<int, 3>& tri = sheet.triangles[t];
    for (int k : tri)
      if (k < 0 || k >= static_cast<int>(n))
        return Failure::failure("triangle " + std::to_string(t) + " of the bent sheet names point " +
                                std::to_string(k) + ", which does not exist");
    const Vec2 &a = sheet.points[tri[0]], &b = sheet.points[tri[1]], &c = sheet.points[tri[2]];
    const double area2 = signedArea2(a, b, c);
    if (!(area2 > tolerance * scale))
      return Failure::failure("triangle " + std::to_string(t) +
                              " of the bent sheet is not counter-clockwise (or has "
                              "no area) in the crease pattern");
    const int face = faceContaining(paper, (a + b + c) / 3.0);
    if (face < 0 || !inFace(paper, face, a, tolerance) || !inFace(paper, face, b, tolerance) ||
        !inFace(paper, face, c, tolerance))
      return Failure::failure("triangle " + std::to_string(t) + " of the bent sheet, at " + at((a + b + c) / 3.0) +
                              ", lies in no face of the paper (it crosses a crease or leaves the sheet)");
    triangles_of[face].push_back(static_cast<int>(t));
    covered[face] += 0.5 * area2;
  }
  for (size_t f = 0; f < paper.faces.size(); ++f)
  {
    const double area = paper.faceArea(static_cast<int>(f));
    if (std::abs(covered[f] - area) > 1e-9 * std::max(area, scale * scale))
      return Failure::failure("the bent sheet's triangles cover " + std::to_string(covered[f]) + " of face " +
                              std::to_string(f) + "'s area " + std::to_string(area) +
                              ": the sheet does not fit the paper");
  }

  // Which faces bent: their nodes lie off every rigid placement of the face.
  KeptBend result;
  std::vector<char> bent(paper.faces.size(), 0);
  std::vector<std::vector<int>> points_of(paper.faces.size());
  for (size_t f = 0; f < paper.faces.size(); ++f)
  {
    std::vector<int>& points = points_of[f];
    for (int t : triangles_of[f])
      points.insert(points.end(), sheet.triangles[t].begin(), sheet.triangles[t].end());
    std::sort(points.begin(), points.end());
    points.erase(std::unique(points.begin(), points.end()), points.end());
    const double off = offRigid(sheet, points);
    if (off > kBentFaceTolerance * scale)
    {
      bent[f] = 1;
      result.bent_faces.push_back(static_cast<int>(f));
    }
  }
  if (result.bent_faces.empty())
    return Failure::failure("nothing bent: every face of the sheet lies rigid (within " +
                            std::to_string(kBentFaceTolerance) + " of the sheet), so there is no bend to keep");

  Paper next = paper;
  for (size_t v = 0; v < paper.vertices.size(); ++v)
    next.vertices[v].folded = sheet.positions[match.point_of_vertex[v]];
  // The bent faces' nodes become vertices.
  std::vector<int> vertex_of_point = match.vertex_of_point;
  for (int f : result.bent_faces)
    for (int k : points_of[f])
      if (vertex_of_point[k] < 0)
      {
        vertex_of_point[k] = static_cast<int>(next.vertices.size());
        next.vertices.push_back({ sheet.points[k], sheet.positions[k] });
      }

  // Nodes inside a side of a bent face split that paper edge; the face beside keeps them too.
  std::map<int, std::vector<std::pair<double, int>>> inside_edge;  // edge → (t, vertex)
  for (int f : result.bent_faces)
    for (int e : paper.faces[f].edges)
    {
      const Edge& edge = paper.edges[e];
      const Vec2& a = paper.vertices[edge.vertices[0]].crease_pattern;
      const Vec2& b = paper.vertices[edge.vertices[1]].crease_pattern;
      const double length2 = (b - a).squaredNorm();
      for (int k : points_of[f])
      {
        const int v = vertex_of_point[k];
        if (v < static_cast<int>(paper.vertices.size()))
          continue;  // a paper vertex: already an end of its edges
        const Vec2& p = sheet.points[k];
        const double t = (p - a).dot(b - a) / length2;
        if (t > 0 && t < 1 && std::abs(cross(b - a, p - a)) / std::sqrt(length2) <= tolerance)
        {
          auto& list = inside_edge[e];
          if (std::none_of(list.begin(), list.end(), [&](const auto& entry) { return entry.second == v; }))
            list.emplace_back(t, v);
        }
      }
    }
  for (auto& [e, list] : inside_edge)
  {
    std::sort(list.begin(), list.end());
    const Edge original = paper.edges[e];
    std::vector<int> chain{ original.vertices[0] };
    for (const auto& entry : list)
      chain.push_back(entry.second);
    chain.push_back(original.vertices[1]);
    next.edges[e].vertices = { chain[0], chain[1] };
    for (size_t i = 1; i + 1 < chain.size(); ++i)
    {
      Edge piece = original;
      piece.vertices = { chain[i], chain[i + 1] };
      next.edges.push_back(piece);
    }
    for (int face : original.faces)
    {
      if (face < 0 || bent[face])
        continue;
      // The face beside goes round its side in either direction.
      std::vector<int>& cycle = next.faces[face].vertices;
      for (size_t i = 0; i < cycle.size(); ++i)
      {
        const int from = cycle[i], to = cycle[(i + 1) % cycle.size()];
        if (key(from, to) != key(chain.front(), chain.back()))
          continue;
        std::vector<int> between(chain.begin() + 1, chain.end() - 1);
        if (from != chain.front())
          std::reverse(between.begin(), between.end());
        cycle.insert(cycle.begin() + static_cast<std::ptrdiff_t>(i) + 1, between.begin(), between.end());
        break;
      }
    }
  }

  // The bent faces become their triangles; the triangles' sides inside a face become facets.
  std::map<std::pair<int, int>, int> edge_of;
  for (size_t e = 0; e < next.edges.size(); ++e)
    edge_of[key(next.edges[e].vertices[0], next.edges[e].vertices[1])] = static_cast<int>(e);
  const size_t first_facet = next.edges.size();
  for (int f : result.bent_faces)
    for (size_t i = 0; i < triangles_of[f].size(); ++i)
    {
      const std::array<int, 3>& tri = sheet.triangles[triangles_of[f][i]];
      Face face;
      face.vertices = { vertex_of_point[tri[0]], vertex_of_point[tri[1]], vertex_of_point[tri[2]] };
      for (int s = 0; s < 3; ++s)
      {
        const int a = face.vertices[s], b = face.vertices[(s + 1) % 3];
        if (edge_of.count(key(a, b)))
          continue;
        Edge facet;
        facet.vertices = { a, b };
        facet.assignment = Assignment::Flat;
        facet.split = true;
        edge_of[key(a, b)] = static_cast<int>(next.edges.size());
        next.edges.push_back(facet);
      }
      if (i == 0)
        next.faces[f] = std::move(face);
      else
        next.faces.push_back(std::move(face));
      ++result.triangles;
    }
  if (const Status linked = linkTopology(next); !linked)
    return Failure::failure("the bent sheet's triangles do not fit the paper: " + linked.message());
  for (size_t e = first_facet; e < next.edges.size(); ++e)
    if (!next.edges[e].isCrease())
      return Failure::failure("the bent sheet leaves a gap: a side of its triangles inside face " +
                              std::to_string(std::max(next.edges[e].faces[0], next.edges[e].faces[1])) +
                              " has a triangle on one side only");

  // Every crease measured again, by continuity, its assignment kept; the facets' angles are
  // the bend they keep.
  updateFoldAngles(next, 4.0 * M_PI);
  for (size_t e = first_facet; e < next.edges.size(); ++e)
  {
    Edge& facet = next.edges[e];
    facet.target_angle = facet.fold_angle;
    result.largest_bend = std::max(result.largest_bend, std::abs(facet.fold_angle));
    ++result.facets;
  }
  next.face_orders.erase(std::remove_if(next.face_orders.begin(), next.face_orders.end(),
                                        [&](const FaceOrder& o) {
                                          return (o.face < static_cast<int>(bent.size()) && bent[o.face]) ||
                                                 (o.other < static_cast<int>(bent.size()) && bent[o.other]);
                                        }),
                         next.face_orders.end());
  result.max_strain = edgeStrain(next).max;
  if (!(result.max_strain <= kKeptBendMaxStrain))
    return Failure::failure("the bent sheet stretches the paper by " + std::to_string(100.0 * result.max_strain) +
                            " % (at most " + std::to_string(100.0 * kKeptBendMaxStrain) +
                            " % is paper bending): not kept");
  paper = std::move(next);
  return result;
}

}  // namespace virtual_origami::core

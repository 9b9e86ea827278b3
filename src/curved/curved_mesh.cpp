#include "virtual_origami/curved/curved_mesh.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <string>

#include "virtual_origami/core/kinematics.h"
#include "virtual_origami/core/planar_geometry.h"

namespace virtual_origami::core
{
namespace
{
/// The paper edge both nodes lie on, or -1.
int sharedPaperEdge(const CurvedMesh& mesh, const Paper& paper, const std::map<std::pair<int, int>, int>& paper_edge_of,
                    int a, int b)
{
  const MeshNode& na = mesh.nodes[a];
  const MeshNode& nb = mesh.nodes[b];
  if (na.paper_edge >= 0 && nb.paper_edge >= 0)
    return na.paper_edge == nb.paper_edge ? na.paper_edge : -1;
  if (na.paper_edge >= 0 || nb.paper_edge >= 0)
  {
    const MeshNode& on_edge = na.paper_edge >= 0 ? na : nb;
    const MeshNode& other = na.paper_edge >= 0 ? nb : na;
    const Edge& e = paper.edges[on_edge.paper_edge];
    return other.paper_vertex >= 0 && (e.vertices[0] == other.paper_vertex || e.vertices[1] == other.paper_vertex) ?
               on_edge.paper_edge :
               -1;
  }
  if (na.paper_vertex >= 0 && nb.paper_vertex >= 0)
  {
    // The first of parallel edges, as Paper::findEdge gives it.
    const auto found = paper_edge_of.find(std::minmax(na.paper_vertex, nb.paper_vertex));
    return found == paper_edge_of.end() ? -1 : found->second;
  }
  return -1;
}
}  // namespace

double CurvedMesh::restArea(int triangle) const
{
  const auto& t = triangles[triangle].nodes;
  return 0.5 * cross2(nodes[t[1]].crease_pattern - nodes[t[0]].crease_pattern,
                      nodes[t[2]].crease_pattern - nodes[t[0]].crease_pattern);
}

Vec3 CurvedMesh::restPosition(int node) const
{
  const Vec2& c = nodes[node].crease_pattern;
  return Vec3(c.x(), c.y(), 0.0);
}

std::vector<int> CurvedMesh::facesOfNode(const Paper& paper, int node) const
{
  const MeshNode& n = nodes[node];
  if (n.paper_vertex >= 0)
    return paper.facesOfVertex(n.paper_vertex);
  if (n.paper_edge >= 0)
  {
    std::vector<int> faces;
    for (int f : paper.edges[n.paper_edge].faces)
      if (f >= 0)
        faces.push_back(f);
    return faces;
  }
  return { n.paper_face };
}

std::vector<std::vector<int>> CurvedMesh::facesOfNodes(const Paper& paper) const
{
  std::vector<std::vector<int>> of_vertex(paper.vertices.size());
  for (size_t f = 0; f < paper.faces.size(); ++f)
    for (int v : paper.faces[f].vertices)
      if (of_vertex[v].empty() || of_vertex[v].back() != static_cast<int>(f))
        of_vertex[v].push_back(static_cast<int>(f));
  std::vector<std::vector<int>> out(nodes.size());
  for (size_t i = 0; i < nodes.size(); ++i)
    out[i] = nodes[i].paper_vertex >= 0 ? of_vertex[nodes[i].paper_vertex] : facesOfNode(paper, static_cast<int>(i));
  return out;
}

Status linkMesh(CurvedMesh& mesh, const Paper& paper)
{
  mesh.edges.clear();
  // The paper's edges by their vertices, for mesh edges between two paper vertices (one scan of
  // every edge each was quadratic in the pattern's size).
  std::map<std::pair<int, int>, int> paper_edge_of;
  for (size_t e = 0; e < paper.edges.size(); ++e)
    paper_edge_of.emplace(std::minmax(paper.edges[e].vertices[0], paper.edges[e].vertices[1]), static_cast<int>(e));
  std::map<std::pair<int, int>, int> edge_of;
  for (size_t t = 0; t < mesh.triangles.size(); ++t)
  {
    const auto& tri = mesh.triangles[t].nodes;
    if (!(mesh.restArea(static_cast<int>(t)) > 0))
      return failure("triangle " + std::to_string(t) + " is not counter-clockwise");
    for (int k = 0; k < 3; ++k)
    {
      const int a = tri[k], b = tri[(k + 1) % 3];
      const auto key = std::minmax(a, b);
      auto it = edge_of.find(key);
      if (it == edge_of.end())
      {
        MeshEdge edge;
        edge.nodes = { a, b };
        edge.paper_edge = sharedPaperEdge(mesh, paper, paper_edge_of, a, b);
        it = edge_of.emplace(key, static_cast<int>(mesh.edges.size())).first;
        mesh.edges.push_back(edge);
      }
      MeshEdge& edge = mesh.edges[it->second];
      // The triangle lies left of a→b because it is counter-clockwise.
      const int side = edge.nodes[0] == a ? 0 : 1;
      if (edge.triangles[side] >= 0)
        return failure("mesh edge " + std::to_string(a) + "-" + std::to_string(b) + " has two triangles on one side");
      edge.triangles[side] = static_cast<int>(t);
    }
  }
  return success();
}

Positions placeNodes(const CurvedMesh& mesh, const Paper& paper)
{
  Positions x(3, static_cast<Eigen::Index>(mesh.nodes.size()));
  std::vector<Eigen::Isometry3d> poses(paper.faces.size());
  std::vector<char> posed(paper.faces.size(), 0);
  for (size_t i = 0; i < mesh.nodes.size(); ++i)
  {
    const MeshNode& n = mesh.nodes[i];
    if (n.paper_vertex >= 0)
      x.col(i) = paper.vertices[n.paper_vertex].folded;
    else if (n.paper_edge >= 0)
    {
      const Edge& e = paper.edges[n.paper_edge];
      x.col(i) = (1 - n.edge_t) * paper.vertices[e.vertices[0]].folded + n.edge_t * paper.vertices[e.vertices[1]].folded;
    }
    else
    {
      if (!posed[n.paper_face])
      {
        poses[n.paper_face] = facePose(paper, n.paper_face);
        posed[n.paper_face] = 1;
      }
      x.col(i) = poses[n.paper_face] * mesh.restPosition(static_cast<int>(i));
    }
  }
  return x;
}

Positions transferNodes(const CurvedMesh& from, const Positions& from_positions, const CurvedMesh& to,
                        const Positions& fallback)
{
  Positions x = fallback;
  // Triangles binned by their bounding boxes in the crease pattern.
  const double cell = std::max(from.spacing, 1e-9);
  std::map<std::pair<long, long>, std::vector<int>> bins;
  const auto key = [cell](double v) { return static_cast<long>(std::floor(v / cell)); };
  for (size_t t = 0; t < from.triangles.size(); ++t)
  {
    Vec2 lo = from.nodes[from.triangles[t].nodes[0]].crease_pattern, hi = lo;
    for (int n : from.triangles[t].nodes)
    {
      lo = lo.cwiseMin(from.nodes[n].crease_pattern);
      hi = hi.cwiseMax(from.nodes[n].crease_pattern);
    }
    for (long i = key(lo.x()); i <= key(hi.x()); ++i)
      for (long j = key(lo.y()); j <= key(hi.y()); ++j)
        bins[{ i, j }].push_back(static_cast<int>(t));
  }
  for (size_t i = 0; i < to.nodes.size(); ++i)
  {
    const Vec2& p = to.nodes[i].crease_pattern;
    const auto it = bins.find({ key(p.x()), key(p.y()) });
    if (it == bins.end())
      continue;
    // The triangle that holds the point best (largest smallest barycentric coordinate).
    double best = -1e-9;
    for (int t : it->second)
    {
      const auto& tri = from.triangles[t].nodes;
      const Vec2& a = from.nodes[tri[0]].crease_pattern;
      const Vec2& b = from.nodes[tri[1]].crease_pattern;
      const Vec2& c = from.nodes[tri[2]].crease_pattern;
      const double area = cross2(b - a, c - a);
      const double wa = cross2(b - p, c - p) / area, wb = cross2(c - p, a - p) / area, wc = 1 - wa - wb;
      const double worst = std::min({ wa, wb, wc });
      if (worst > best)
      {
        best = worst;
        x.col(i) = wa * from_positions.col(tri[0]) + wb * from_positions.col(tri[1]) + wc * from_positions.col(tri[2]);
      }
    }
  }
  return x;
}

void applyToPaper(const CurvedMesh& mesh, const Positions& positions, Paper& paper)
{
  for (size_t v = 0; v < paper.vertices.size() && v < mesh.vertex_nodes.size(); ++v)
    paper.vertices[v].folded = positions.col(mesh.vertex_nodes[v]);
  updateFoldAngles(paper);
}

MeshQuality meshQuality(const CurvedMesh& mesh, const Paper& paper)
{
  const std::vector<std::vector<int>> node_faces = mesh.facesOfNodes(paper);
  MeshQuality q;
  q.min_angle = M_PI;
  q.min_edge = std::numeric_limits<double>::infinity();
  for (size_t t = 0; t < mesh.triangles.size(); ++t)
  {
    const auto& tri = mesh.triangles[t].nodes;
    const double area = mesh.restArea(static_cast<int>(t));
    q.area += area;
    double perimeter = 0, edge_product = 1;
    bool well_shaped = true;
    for (int k = 0; k < 3; ++k)
    {
      const Vec2& o = mesh.nodes[tri[k]].crease_pattern;
      const Vec2 u = mesh.nodes[tri[(k + 1) % 3]].crease_pattern - o;
      const Vec2 v = mesh.nodes[tri[(k + 2) % 3]].crease_pattern - o;
      const double angle = angleBetween(u, v);
      q.min_angle = std::min(q.min_angle, angle);
      q.max_angle = std::max(q.max_angle, angle);
      q.min_edge = std::min(q.min_edge, u.norm() / mesh.spacing);
      q.max_edge = std::max(q.max_edge, u.norm() / mesh.spacing);
      perimeter += u.norm();
      edge_product *= u.norm();
      well_shaped = well_shaped && angle >= M_PI / 4 && angle <= 5 * M_PI / 12;
    }
    // 2r/R with r = 2A/perimeter and R = abc/(4A).
    q.mean_radius_ratio += perimeter > 0 && edge_product > 0 ? 16 * area * area / (perimeter * edge_product) : 0.0;
    q.well_shaped += well_shaped ? 1.0 : 0.0;
    bool in_face = true;
    for (int n : tri)
    {
      const std::vector<int>& faces = node_faces[n];
      in_face = in_face && std::find(faces.begin(), faces.end(), mesh.triangles[t].face) != faces.end();
    }
    q.crossing_triangles += in_face ? 0 : 1;
  }
  if (!mesh.triangles.empty())
  {
    q.mean_radius_ratio /= static_cast<double>(mesh.triangles.size());
    q.well_shaped /= static_cast<double>(mesh.triangles.size());
  }
  return q;
}

}  // namespace virtual_origami::core

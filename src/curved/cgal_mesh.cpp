// CGAL's headers compile slowly: the mesher's are included here only.
#include "virtual_origami/curved/cgal_mesh.h"

#include <algorithm>
#include <cmath>
#include <deque>
#include <exception>
#include <map>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Delaunay_mesh_face_base_2.h>
#include <CGAL/Delaunay_mesh_size_criteria_2.h>
#include <CGAL/Delaunay_mesh_vertex_base_2.h>
#include <CGAL/Delaunay_mesher_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/lloyd_optimize_mesh_2.h>

#include "virtual_origami/core/planar_geometry.h"

namespace virtual_origami::core
{
namespace
{
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using VertexBase = CGAL::Delaunay_mesh_vertex_base_2<Kernel>;
// The paper face a triangle belongs to, set by the flood fill (-1: outside the paper).
using FaceBase = CGAL::Triangulation_face_base_with_info_2<int, Kernel, CGAL::Delaunay_mesh_face_base_2<Kernel>>;
using DataStructure = CGAL::Triangulation_data_structure_2<VertexBase, FaceBase>;
// Paper edges meet only at shared vertices: crossing ones are an error, not a construction.
using Triangulation =
    CGAL::Constrained_Delaunay_triangulation_2<Kernel, DataStructure, CGAL::No_constraint_intersection_tag>;
using Criteria = CGAL::Delaunay_mesh_size_criteria_2<Triangulation>;
using Point = Kernel::Point_2;

/// Whether `p` lies strictly inside the polygon (even–odd rule).
bool insidePolygon(const std::vector<Vec2>& polygon, const Vec2& p)
{
  bool inside = false;
  for (size_t i = 0, j = polygon.size() - 1; i < polygon.size(); j = i++)
  {
    const Vec2& a = polygon[i];
    const Vec2& b = polygon[j];
    if ((a.y() > p.y()) != (b.y() > p.y()) && p.x() < (b.x() - a.x()) * (p.y() - a.y()) / (b.y() - a.y()) + a.x())
      inside = !inside;
  }
  return inside;
}

/// A point inside the face, from which the flood fill starts: its centroid when the face is
/// convex, else the centroid of the first fan triangle that lies inside it.
Vec2 pointInsideFace(const Paper& paper, int face)
{
  std::vector<Vec2> polygon;
  for (int v : paper.faces[face].vertices)
    polygon.push_back(paper.vertices[v].crease_pattern);
  Vec2 centroid = Vec2::Zero();
  for (const Vec2& p : polygon)
    centroid += p;
  centroid /= static_cast<double>(polygon.size());
  if (insidePolygon(polygon, centroid))
    return centroid;
  for (size_t i = 1; i + 1 < polygon.size(); ++i)
  {
    const Vec2 c = (polygon[0] + polygon[i] + polygon[i + 1]) / 3;
    if (cross2(polygon[i] - polygon[0], polygon[i + 1] - polygon[0]) > 0 && insidePolygon(polygon, c))
      return c;
  }
  return centroid;
}

bool isCurved(const CgalMeshOptions& options, int face)
{
  return options.curved_faces.empty() ||
         (static_cast<size_t>(face) < options.curved_faces.size() && options.curved_faces[face]);
}

/// The paper's faces with their area and finite corners, or why not.
Status checkPaper(const Paper& paper)
{
  if (paper.faces.empty())
    return failure("the paper has no faces");
  for (size_t v = 0; v < paper.vertices.size(); ++v)
    if (!paper.vertices[v].crease_pattern.allFinite())
      return failure("paper vertex " + std::to_string(v) + " is not finite");
  const double scale = paper.scale();
  if (!(scale > 0) || !std::isfinite(scale))
    return failure("the paper has no area");
  for (size_t f = 0; f < paper.faces.size(); ++f)
  {
    if (paper.faces[f].vertices.size() < 3 || paper.faces[f].edges.size() != paper.faces[f].vertices.size())
      return failure("paper face " + std::to_string(f) + " is not a linked polygon");
    if (!(paper.faceArea(static_cast<int>(f)) > 1e-12 * scale * scale))
      return failure("paper face " + std::to_string(f) + " has no area (or is clockwise)");
  }
  return success();
}

/// Gives every triangle the paper face whose seed reaches it without crossing a constraint;
/// fails when two seeds reach one triangle (faces not closed off by edges).
Status floodFill(Triangulation& cdt, const std::vector<Point>& seeds)
{
  for (auto f = cdt.all_faces_begin(); f != cdt.all_faces_end(); ++f)
    f->info() = -1;
  // Each seed located from the face the seed before lay in: the seeds of neighbouring paper
  // faces lie near each other, and a walk from the triangulation's start for each made the flood
  // fill grow faster than the pattern (a fifth of the mesher's time at 50,000 vertices).
  Triangulation::Face_handle hint;
  for (size_t s = 0; s < seeds.size(); ++s)
  {
    const Triangulation::Face_handle start = hint == nullptr ? cdt.locate(seeds[s]) : cdt.locate(seeds[s], hint);
    if (start == nullptr || cdt.is_infinite(start))
      return failure("paper face " + std::to_string(s) + " lies outside the triangulation");
    hint = start;
    if (start->info() >= 0)
      return failure("paper faces " + std::to_string(start->info()) + " and " + std::to_string(s) +
                     " are not separated by edges");
    std::deque<Triangulation::Face_handle> queue{ start };
    start->info() = static_cast<int>(s);
    while (!queue.empty())
    {
      const Triangulation::Face_handle f = queue.front();
      queue.pop_front();
      for (int i = 0; i < 3; ++i)
      {
        if (f->is_constrained(i))
          continue;
        const Triangulation::Face_handle n = f->neighbor(i);
        if (cdt.is_infinite(n))
          return failure("paper face " + std::to_string(s) + " is open to the outside");
        if (n->info() == static_cast<int>(s))
          continue;
        if (n->info() >= 0)
          return failure("paper faces " + std::to_string(n->info()) + " and " + std::to_string(s) +
                         " are not separated by edges");
        n->info() = static_cast<int>(s);
        queue.push_back(n);
      }
    }
  }
  return success();
}

/// The paper's edges binned by the grid cells their boxes, widened by `tolerance`, cover: the
/// edges a point can lie within `tolerance` of (a scan of every edge per node on an edge made
/// meshing quadratic in the pattern's size).
class EdgeBins
{
public:
  EdgeBins(const Paper& paper, double tolerance)
    : cell_(paper.scale() / std::max(1.0, std::sqrt(static_cast<double>(paper.edges.size()))))
  {
    for (size_t e = 0; e < paper.edges.size(); ++e)
    {
      const Vec2& a = paper.vertices[paper.edges[e].vertices[0]].crease_pattern;
      const Vec2& b = paper.vertices[paper.edges[e].vertices[1]].crease_pattern;
      const Vec2 lo = a.cwiseMin(b).array() - tolerance, hi = a.cwiseMax(b).array() + tolerance;
      for (long x = cellOf(lo.x()); x <= cellOf(hi.x()); ++x)
        for (long y = cellOf(lo.y()); y <= cellOf(hi.y()); ++y)
          bins_[{ x, y }].push_back(static_cast<int>(e));  // in ascending order
    }
  }

  /// The edges binned where `p` lies, in ascending order.
  const std::vector<int>& near(const Vec2& p) const
  {
    static const std::vector<int> none;
    const auto found = bins_.find({ cellOf(p.x()), cellOf(p.y()) });
    return found == bins_.end() ? none : found->second;
  }

private:
  long cellOf(double v) const { return static_cast<long>(std::floor(v / cell_)); }

  double cell_;
  std::map<std::pair<long, long>, std::vector<int>> bins_;
};

/// The paper edge a node inside an edge lies on, and where along it; -1 when none is within
/// `tolerance` (the tolerance `bins` were made with).
std::pair<int, double> paperEdgeAt(const Paper& paper, const EdgeBins& bins, const Vec2& p, double tolerance)
{
  int best = -1;
  double best_distance = tolerance, best_t = 0;
  for (const int e : bins.near(p))
  {
    const Vec2& a = paper.vertices[paper.edges[e].vertices[0]].crease_pattern;
    const Vec2& b = paper.vertices[paper.edges[e].vertices[1]].crease_pattern;
    const Vec2 ab = b - a;
    const double t = std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
    const double distance = (a + t * ab - p).norm();
    if (distance <= best_distance)
    {
      best = e;
      best_distance = distance;
      best_t = t;
    }
  }
  return { best, best_t };
}
}  // namespace

Expected<CurvedMesh> cgalMesh(const Paper& paper, const CgalMeshOptions& options)
{
  using Failure = Expected<CurvedMesh>;
  if (std::isnan(options.spacing) || !std::isfinite(options.spacing) || options.spacing < 0)
    return Failure::failure("mesh spacing must be a positive number (0 for the default), not " +
                            std::to_string(options.spacing));
  if (!(options.shape_bound > 0 && options.shape_bound <= 0.125))
    return Failure::failure("shape bound must be in (0, 0.125] (sin² of at most 20.7°), not " +
                            std::to_string(options.shape_bound));
  if (options.lloyd_iterations < 0)
    return Failure::failure("Lloyd iterations must not be negative");
  const Status sound = checkPaper(paper);
  if (!sound.ok())
    return Failure::failure("cannot mesh: " + sound.message());
  const double scale = paper.scale();
  const double spacing = options.spacing > 0 ? options.spacing : scale / 10;
  // An equilateral mesh of edge `spacing` has one node per √3/2·spacing² of area.
  if (paper.sheet_area / (std::sqrt(3.0) / 2 * spacing * spacing) > 4e6)
    return Failure::failure("mesh spacing " + std::to_string(spacing) + " would make millions of nodes");

  CurvedMesh mesh;
  mesh.spacing = spacing;
  mesh.curved_faces.resize(paper.faces.size());
  for (size_t f = 0; f < paper.faces.size(); ++f)
    mesh.curved_faces[f] = isCurved(options, static_cast<int>(f)) ? 1 : 0;
  try
  {
    Triangulation cdt;
    std::vector<Triangulation::Vertex_handle> corner(paper.vertices.size());
    for (size_t v = 0; v < paper.vertices.size(); ++v)
      corner[v] = cdt.insert(Point(paper.vertices[v].crease_pattern.x(), paper.vertices[v].crease_pattern.y()));
    if (cdt.number_of_vertices() != paper.vertices.size())
      return Failure::failure("cannot mesh: paper vertices coincide");
    for (const Edge& e : paper.edges)
      cdt.insert_constraint(corner[e.vertices[0]], corner[e.vertices[1]]);
    if (cdt.number_of_vertices() != paper.vertices.size())
      return Failure::failure("cannot mesh: paper edges cross");

    std::vector<Point> seeds, curved_seeds;
    for (size_t f = 0; f < paper.faces.size(); ++f)
    {
      const Vec2 p = pointInsideFace(paper, static_cast<int>(f));
      seeds.emplace_back(p.x(), p.y());
      if (mesh.curved_faces[f])
        curved_seeds.push_back(seeds.back());
    }
    // Check the faces are closed off before refining: refinement would fill a leak.
    const Status filled = floodFill(cdt, seeds);
    if (!filled.ok())
      return Failure::failure("cannot mesh: " + filled.message());
    if (!curved_seeds.empty())
    {
      // Only the curved faces are the domain (mark = true: the seeds' components).
      // Refinement leaves edges between about half the size bound and the bound: a bound of
      // √2·spacing gives mean edges near `spacing` (measured on the square: 0.98), as the
      // bubble mesh's, so one spacing means one resolution for both meshers.
      CGAL::refine_Delaunay_mesh_2(cdt, curved_seeds.begin(), curved_seeds.end(),
                                   Criteria(options.shape_bound, std::sqrt(2.0) * spacing), true);
      if (options.lloyd_iterations > 0)
        CGAL::lloyd_optimize_mesh_2(cdt, CGAL::parameters::max_iteration_number = options.lloyd_iterations,
                                    CGAL::parameters::seeds_begin = curved_seeds.begin(),
                                    CGAL::parameters::seeds_end = curved_seeds.end(), CGAL::parameters::mark = true);
    }
    const Status refilled = floodFill(cdt, seeds);
    if (!refilled.ok())
      return Failure::failure("meshing failed: " + refilled.message());

    // Classify the triangulation's vertices: on a paper vertex, inside a paper edge (an end
    // of a constrained edge), or inside the one face its triangles belong to.
    std::map<std::pair<double, double>, int> vertex_at;
    for (size_t v = 0; v < paper.vertices.size(); ++v)
      vertex_at[{ paper.vertices[v].crease_pattern.x(), paper.vertices[v].crease_pattern.y() }] = static_cast<int>(v);
    const double node_tolerance = 1e-9 * scale;
    const EdgeBins edge_bins(paper, node_tolerance);
    std::vector<std::tuple<int, double, Triangulation::Vertex_handle>> on_edges;
    std::vector<std::pair<int, Triangulation::Vertex_handle>> in_faces;
    for (auto v = cdt.finite_vertices_begin(); v != cdt.finite_vertices_end(); ++v)
    {
      const Vec2 p(v->point().x(), v->point().y());
      if (vertex_at.count({ p.x(), p.y() }))
        continue;
      bool constrained = false;
      int face = -1;
      auto f = cdt.incident_faces(v), done = f;
      do
      {
        const int i = f->index(v);
        constrained = constrained || f->is_constrained((i + 1) % 3) || f->is_constrained((i + 2) % 3);
        if (!cdt.is_infinite(f) && f->info() >= 0)
          face = f->info();
      } while (++f != done);
      if (constrained)
      {
        const auto [edge, t] = paperEdgeAt(paper, edge_bins, p, node_tolerance);
        if (edge < 0)
          return Failure::failure("meshing failed: a node on a constraint lies on no paper edge");
        on_edges.emplace_back(edge, t, v);
      }
      else if (face >= 0)
        in_faces.emplace_back(face, v);
      else
        return Failure::failure("meshing failed: a node lies outside the paper");
    }
    std::sort(on_edges.begin(), on_edges.end(), [](const auto& a, const auto& b) {
      return std::tie(std::get<0>(a), std::get<1>(a)) < std::tie(std::get<0>(b), std::get<1>(b));
    });
    std::stable_sort(in_faces.begin(), in_faces.end(), [](const auto& a, const auto& b) { return a.first < b.first; });

    std::map<Triangulation::Vertex_handle, int> node_of;
    for (size_t v = 0; v < paper.vertices.size(); ++v)
    {
      MeshNode node;
      node.crease_pattern = paper.vertices[v].crease_pattern;
      node.paper_vertex = static_cast<int>(v);
      node_of[corner[v]] = static_cast<int>(mesh.nodes.size());
      mesh.nodes.push_back(node);
    }
    for (const auto& [edge, t, handle] : on_edges)
    {
      MeshNode node;
      node.paper_edge = edge;
      node.edge_t = t;
      // On the edge exactly, as the rigid placement puts it.
      const Vec2& a = paper.vertices[paper.edges[edge].vertices[0]].crease_pattern;
      const Vec2& b = paper.vertices[paper.edges[edge].vertices[1]].crease_pattern;
      node.crease_pattern = a + t * (b - a);
      node_of[handle] = static_cast<int>(mesh.nodes.size());
      mesh.nodes.push_back(node);
    }
    for (const auto& [face, handle] : in_faces)
    {
      MeshNode node;
      node.paper_face = face;
      node.crease_pattern = Vec2(handle->point().x(), handle->point().y());
      node_of[handle] = static_cast<int>(mesh.nodes.size());
      mesh.nodes.push_back(node);
    }
    mesh.vertex_nodes.resize(paper.vertices.size());
    for (size_t v = 0; v < paper.vertices.size(); ++v)
      mesh.vertex_nodes[v] = static_cast<int>(v);
    for (auto f = cdt.finite_faces_begin(); f != cdt.finite_faces_end(); ++f)
      if (f->info() >= 0)
        mesh.triangles.push_back(
            { { node_of.at(f->vertex(0)), node_of.at(f->vertex(1)), node_of.at(f->vertex(2)) }, f->info() });
  }
  catch (const std::exception& e)
  {
    return Failure::failure(std::string("cannot mesh: ") + e.what());
  }
  const Status linked = linkMesh(mesh, paper);
  if (!linked.ok())
    return Failure::failure("meshing failed: " + linked.message());
  return mesh;
}

}  // namespace virtual_origami::core

// CGAL's headers compile slowly: this is the only source that includes them.
#include "virtual_origami/curved/delaunay.h"

#include <exception>
#include <string>
#include <utility>

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

namespace virtual_origami::core
{
namespace
{
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using VertexBase = CGAL::Triangulation_vertex_base_with_info_2<int, Kernel>;
using FaceBase = CGAL::Constrained_triangulation_face_base_2<Kernel>;
using DataStructure = CGAL::Triangulation_data_structure_2<VertexBase, FaceBase>;
// Constraints meet only at shared end points: crossing ones are an error, not a construction.
using Triangulation =
    CGAL::Constrained_Delaunay_triangulation_2<Kernel, DataStructure, CGAL::No_constraint_intersection_tag>;
}  // namespace

Expected<std::vector<std::array<int, 3>>> constrainedDelaunay(const std::vector<Vec2>& points,
                                                              const std::vector<std::array<int, 2>>& constraints)
{
  using Result = Expected<std::vector<std::array<int, 3>>>;
  const int n = static_cast<int>(points.size());
  for (const auto& c : constraints)
    if (c[0] < 0 || c[1] < 0 || c[0] >= n || c[1] >= n || c[0] == c[1])
      return Result::failure("constraint names a point out of range");
  try
  {
    std::vector<std::pair<Kernel::Point_2, int>> input;
    input.reserve(points.size());
    for (int i = 0; i < n; ++i)
      input.emplace_back(Kernel::Point_2(points[i].x(), points[i].y()), i);
    Triangulation triangulation;
    triangulation.insert(input.begin(), input.end());  // spatially sorted insertion
    if (static_cast<int>(triangulation.number_of_vertices()) != n)
      return Result::failure("coincident points: " + std::to_string(n - triangulation.number_of_vertices()) +
                             " of " + std::to_string(n) + " merged");
    std::vector<Triangulation::Vertex_handle> handle(n);
    for (auto v = triangulation.finite_vertices_begin(); v != triangulation.finite_vertices_end(); ++v)
      handle[v->info()] = v;
    for (const auto& c : constraints)
      triangulation.insert_constraint(handle[c[0]], handle[c[1]]);
    if (static_cast<int>(triangulation.number_of_vertices()) != n)
      return Result::failure("constraints cross: the triangulation had to add points");
    std::vector<std::array<int, 3>> triangles;
    triangles.reserve(triangulation.number_of_faces());
    for (auto f = triangulation.finite_faces_begin(); f != triangulation.finite_faces_end(); ++f)
      triangles.push_back({ f->vertex(0)->info(), f->vertex(1)->info(), f->vertex(2)->info() });
    return triangles;
  }
  catch (const std::exception& e)
  {
    return Result::failure(std::string("constrained Delaunay failed: ") + e.what());
  }
}

}  // namespace virtual_origami::core

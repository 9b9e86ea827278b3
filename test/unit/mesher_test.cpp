// Both meshers (SPEC §4.2) on the reference crease patterns: one conforming mesh (every
// paper edge covered by mesh edges, crease nodes shared by the faces on both sides), each
// triangle inside exactly one face, the faces' areas kept, and no angle below 20° except
// at corners whose own angle is smaller. Then the CGAL mesher's contract: bad input refused,
// coarse faces left coarse.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "test_models.h"
#include "virtual_origami/core/planar_geometry.h"
#include "virtual_origami/core/reference_patterns.h"
#include "virtual_origami/curved/bubble_mesh.h"
#include "virtual_origami/curved/cgal_mesh.h"

using namespace virtual_origami::core;
using namespace virtual_origami::core::test;

namespace
{
constexpr double kDeg = M_PI / 180;

double angleAt(const Vec2& corner, const Vec2& a, const Vec2& b)
{
  const Vec2 u = a - corner, v = b - corner;
  return angleBetween(u, v);
}

/// Whether `p` lies inside the counter-clockwise face, at least `margin` from each side.
bool insideFace(const Paper& paper, int face, const Vec2& p, double margin)
{
  const std::vector<int>& vs = paper.faces[face].vertices;
  for (size_t i = 0; i < vs.size(); ++i)
  {
    const Vec2& a = paper.vertices[vs[i]].crease_pattern;
    const Vec2& b = paper.vertices[vs[(i + 1) % vs.size()]].crease_pattern;
    if (cross2(b - a, p - a) / (b - a).norm() < margin)
      return false;
  }
  return true;
}

struct Pattern
{
  std::string name;
  Paper paper;
};

std::vector<Pattern> patterns()
{
  Paper diagonal = Paper::square(1.0);
  creaseLine(diagonal, p3(1, 0), p3(0, 1));
  return {
    { "square", Paper::square(1.0) },
    { "diagonal", diagonal },
    { "miura", miuraOri(3, 3, 1.0, 1.0, 60 * kDeg) },
    { "degree4", degree4Vertex({ M_PI / 2, M_PI / 2, M_PI / 2, M_PI / 2 }) },
    // The 150° sector's triangle has corners of 15° on the sheet's side.
    { "degree4_narrow", degree4Vertex({ 30 * kDeg, 90 * kDeg, 150 * kDeg, 90 * kDeg }) },
  };
}

using Mesher = std::function<Expected<CurvedMesh>(const Paper&, double)>;

Expected<CurvedMesh> bubble(const Paper& paper, double spacing)
{
  BubbleMeshOptions options;
  options.spacing = spacing;
  return bubbleMesh(paper, options);
}

Expected<CurvedMesh> cgal(const Paper& paper, double spacing)
{
  CgalMeshOptions options;
  options.spacing = spacing;
  return cgalMesh(paper, options);
}

/// Every property a mesh of a fully curved paper must have (the angle bound where asked).
void expectConformingMesh(const CurvedMesh& mesh, const Paper& paper, bool check_angles = true)
{
  // Paper vertices first: node v is vertex v.
  ASSERT_EQ(mesh.vertex_nodes.size(), paper.vertices.size());
  for (size_t v = 0; v < paper.vertices.size(); ++v)
  {
    EXPECT_EQ(mesh.vertex_nodes[v], static_cast<int>(v));
    EXPECT_EQ(mesh.nodes[v].paper_vertex, static_cast<int>(v));
  }
  // Each triangle counter-clockwise, all its nodes in its face, its centroid strictly inside
  // that face and no other; the faces' areas add up.
  std::vector<double> area(paper.faces.size(), 0.0);
  const double margin = 1e-9 * paper.scale();
  for (size_t t = 0; t < mesh.triangles.size(); ++t)
  {
    const MeshTriangle& tri = mesh.triangles[t];
    ASSERT_GE(tri.face, 0);
    ASSERT_LT(tri.face, static_cast<int>(paper.faces.size()));
    EXPECT_GT(mesh.restArea(static_cast<int>(t)), 0.0);
    area[tri.face] += mesh.restArea(static_cast<int>(t));
    Vec2 centroid = Vec2::Zero();
    for (int n : tri.nodes)
    {
      centroid += mesh.nodes[n].crease_pattern / 3;
      const std::vector<int> faces = mesh.facesOfNode(paper, n);
      EXPECT_NE(std::find(faces.begin(), faces.end(), tri.face), faces.end()) << "triangle " << t << " node " << n;
    }
    int holders = 0;
    for (size_t f = 0; f < paper.faces.size(); ++f)
      holders += insideFace(paper, static_cast<int>(f), centroid, margin) ? 1 : 0;
    EXPECT_EQ(holders, 1) << "triangle " << t;
    EXPECT_TRUE(insideFace(paper, tri.face, centroid, margin)) << "triangle " << t;
  }
  for (size_t f = 0; f < paper.faces.size(); ++f)
    EXPECT_NEAR(area[f], paper.faceArea(static_cast<int>(f)), 1e-9 * paper.faceArea(static_cast<int>(f)))
        << "face " << f;

  // Every paper edge is a chain of mesh edges through the nodes on it, each with a triangle of
  // the face on each side (one conforming mesh, not a mesh per face).
  std::map<std::pair<int, int>, const MeshEdge*> edge_of;
  for (const MeshEdge& e : mesh.edges)
    edge_of[std::minmax(e.nodes[0], e.nodes[1])] = &e;
  for (size_t e = 0; e < paper.edges.size(); ++e)
  {
    const Edge& edge = paper.edges[e];
    std::vector<std::pair<double, int>> chain{ { 0.0, edge.vertices[0] }, { 1.0, edge.vertices[1] } };
    for (size_t n = 0; n < mesh.nodes.size(); ++n)
      if (mesh.nodes[n].paper_edge == static_cast<int>(e))
        chain.emplace_back(mesh.nodes[n].edge_t, static_cast<int>(n));
    std::sort(chain.begin(), chain.end());
    std::set<int> expected_faces;
    for (int f : edge.faces)
      if (f >= 0)
        expected_faces.insert(f);
    for (size_t k = 0; k + 1 < chain.size(); ++k)
    {
      const auto it = edge_of.find(std::minmax(chain[k].second, chain[k + 1].second));
      ASSERT_NE(it, edge_of.end()) << "paper edge " << e << " is not covered between nodes " << chain[k].second
                                   << " and " << chain[k + 1].second;
      const MeshEdge& m = *it->second;
      EXPECT_EQ(m.paper_edge, static_cast<int>(e));
      std::set<int> faces;
      for (int t : m.triangles)
        if (t >= 0)
          faces.insert(mesh.triangles[t].face);
      EXPECT_EQ(faces, expected_faces) << "paper edge " << e;
    }
  }
  // And every node on a crease is a corner of triangles on both sides.
  for (size_t n = 0; n < mesh.nodes.size(); ++n)
  {
    const int e = mesh.nodes[n].paper_edge;
    if (e < 0 || !paper.edges[e].isCrease())
      continue;
    std::set<int> faces;
    for (const MeshTriangle& t : mesh.triangles)
      if (std::find(t.nodes.begin(), t.nodes.end(), static_cast<int>(n)) != t.nodes.end())
        faces.insert(t.face);
    EXPECT_EQ(faces, std::set<int>({ paper.edges[e].faces[0], paper.edges[e].faces[1] })) << "node " << n;
  }
  if (!check_angles)
    return;
  // No angle below 20° but in triangles at a corner whose own angle is below 20°.
  std::set<std::pair<int, int>> sharp_corners;  // (face, vertex)
  for (size_t f = 0; f < paper.faces.size(); ++f)
  {
    const std::vector<int>& vs = paper.faces[f].vertices;
    for (size_t i = 0; i < vs.size(); ++i)
    {
      const Vec2& prev = paper.vertices[vs[(i + vs.size() - 1) % vs.size()]].crease_pattern;
      const Vec2& next = paper.vertices[vs[(i + 1) % vs.size()]].crease_pattern;
      if (angleAt(paper.vertices[vs[i]].crease_pattern, prev, next) < 20 * kDeg)
        sharp_corners.insert({ static_cast<int>(f), vs[i] });
    }
  }
  for (size_t t = 0; t < mesh.triangles.size(); ++t)
  {
    const MeshTriangle& tri = mesh.triangles[t];
    bool at_sharp_corner = false;
    for (int n : tri.nodes)
      at_sharp_corner = at_sharp_corner || sharp_corners.count({ tri.face, mesh.nodes[n].paper_vertex });
    if (at_sharp_corner)
      continue;
    for (int k = 0; k < 3; ++k)
    {
      const double angle =
          angleAt(mesh.nodes[tri.nodes[k]].crease_pattern, mesh.nodes[tri.nodes[(k + 1) % 3]].crease_pattern,
                  mesh.nodes[tri.nodes[(k + 2) % 3]].crease_pattern);
      EXPECT_GE(angle, 20 * kDeg) << "triangle " << t << " in face " << tri.face;
    }
  }
}

void expectConformingMeshes(const std::string& mesher_name, const Mesher& mesher, bool angles_at_sharp_corners)
{
  for (const Pattern& pattern : patterns())
    for (double relative : { 0.2, 0.07 })
    {
      SCOPED_TRACE(mesher_name + " on " + pattern.name + " at spacing " + std::to_string(relative));
      const Expected<CurvedMesh> mesh = mesher(pattern.paper, relative * pattern.paper.scale());
      ASSERT_TRUE(mesh.ok()) << mesh.message();
      expectConformingMesh(*mesh, pattern.paper, angles_at_sharp_corners || pattern.name != "degree4_narrow");
      EXPECT_EQ(meshQuality(*mesh, pattern.paper).crossing_triangles, 0);
    }
}
}  // namespace

// The bubble mesh spaces bubbles evenly right up to a corner: between the sides of a 15°
// corner, triangles a few spacings from it (not touching it) get angles near 15°, where
// CGAL's refinement grades the mesh down into the corner. There it is checked for
// conformity only (docs/CURVED.md, Meshing).
TEST(Meshers, BubbleMeshConformsToEveryReferencePattern)
{
  expectConformingMeshes("bubble", bubble, false);
}

TEST(Meshers, CgalMeshConformsToEveryReferencePattern)
{
  expectConformingMeshes("cgal", cgal, true);
}

// All nodes' faces at once, as each node's: paper vertices, nodes on edges, inside faces and
// beside the creases (the strips of a layered start).
TEST(Meshers, TheFacesOfEveryNodeAtOnceAreEachNodesFaces)
{
  for (const Pattern& pattern : patterns())
  {
    BubbleMeshOptions options;
    options.spacing = 0.07 * pattern.paper.scale();
    options.crease_strip = 0.002 * pattern.paper.scale();
    const Expected<CurvedMesh> mesh = bubbleMesh(pattern.paper, options);
    ASSERT_TRUE(mesh.ok()) << pattern.name << ": " << mesh.message();
    const std::vector<std::vector<int>> faces = mesh->facesOfNodes(pattern.paper);
    ASSERT_EQ(faces.size(), mesh->nodes.size());
    for (size_t i = 0; i < faces.size(); ++i)
      EXPECT_EQ(faces[i], mesh->facesOfNode(pattern.paper, static_cast<int>(i))) << pattern.name << ", node " << i;
  }
}

TEST(Meshers, BubbleMeshAnglesNearASharpCornerStayNearTheCornersAngle)
{
  const Paper paper = degree4Vertex({ 30 * kDeg, 90 * kDeg, 150 * kDeg, 90 * kDeg });
  const Expected<CurvedMesh> mesh = bubble(paper, 0.07 * paper.scale());
  ASSERT_TRUE(mesh.ok()) << mesh.message();
  const MeshQuality q = meshQuality(*mesh, paper);
  // Measured 14.3° beside the 15° corners; 20° or more everywhere in the other patterns.
  EXPECT_GT(q.min_angle, 12 * kDeg);
  EXPECT_LT(q.min_angle, 20 * kDeg);
}

TEST(CgalMesh, MeanEdgeNearTheSpacing)
{
  const Paper paper = Paper::square(1.0);
  const Expected<CurvedMesh> mesh = cgal(paper, 0.05);
  ASSERT_TRUE(mesh.ok()) << mesh.message();
  double sum = 0;
  for (const MeshEdge& e : mesh->edges)
    sum += (mesh->nodes[e.nodes[0]].crease_pattern - mesh->nodes[e.nodes[1]].crease_pattern).norm();
  const double mean = sum / static_cast<double>(mesh->edges.size());
  EXPECT_GT(mean, 0.8 * 0.05);
  EXPECT_LT(mean, 1.2 * 0.05);
  EXPECT_GT(meshQuality(*mesh, paper).mean_radius_ratio, 0.9);
}

TEST(CgalMesh, RefusesBadSpacingAndDegeneratePapers)
{
  const Paper square = Paper::square(1.0);
  for (double spacing : { -0.1, std::nan(""), std::numeric_limits<double>::infinity(), 1e-6 })
  {
    CgalMeshOptions options;
    options.spacing = spacing;
    const Expected<CurvedMesh> mesh = cgalMesh(square, options);
    EXPECT_FALSE(mesh.ok()) << spacing;
    EXPECT_NE(mesh.message().find("spacing"), std::string::npos) << mesh.message();
  }
  CgalMeshOptions bad_shape;
  bad_shape.shape_bound = 0.2;  // beyond what refinement can guarantee
  EXPECT_FALSE(cgalMesh(square, bad_shape).ok());

  EXPECT_FALSE(cgalMesh(Paper{}).ok());
  Paper flat = Paper::square(1.0);
  flat.vertices[2].crease_pattern = Vec2(0.5, 0.5);  // corner c on the diagonal: face without area
  flat.vertices[3].crease_pattern = Vec2(0.0, 0.0);
  const Expected<CurvedMesh> degenerate = cgalMesh(flat);
  EXPECT_FALSE(degenerate.ok());
  Paper infinite = Paper::square(1.0);
  infinite.vertices[1].crease_pattern.x() = std::numeric_limits<double>::infinity();
  EXPECT_FALSE(cgalMesh(infinite).ok());
}

TEST(CgalMesh, CoarseFacesKeepOnlyTheirCornersAndSharedEdgeNodes)
{
  Paper paper = Paper::square(1.0);
  creaseLine(paper, p3(0.5, -0.1), p3(0.5, 1.1));
  ASSERT_EQ(paper.faces.size(), 2u);
  CgalMeshOptions options;
  options.spacing = 0.1;
  options.curved_faces = { 1, 0 };
  const Expected<CurvedMesh> mesh = cgalMesh(paper, options);
  ASSERT_TRUE(mesh.ok()) << mesh.message();
  EXPECT_EQ(mesh->curved_faces, std::vector<char>({ 1, 0 }));
  int in_curved = 0;
  for (const MeshNode& n : mesh->nodes)
  {
    EXPECT_NE(n.paper_face, 1);
    in_curved += n.paper_face == 0 ? 1 : 0;
  }
  EXPECT_GT(in_curved, 10);
  // Face 1 is fanned from its sides' nodes (refinement splits a side near face 0 that a new
  // node encroaches on), so it keeps a handful of triangles.
  int triangles[2] = { 0, 0 };
  for (const MeshTriangle& t : mesh->triangles)
    ++triangles[t.face];
  EXPECT_LT(triangles[1] * 5, triangles[0]);
  double area = 0;
  for (size_t t = 0; t < mesh->triangles.size(); ++t)
    area += mesh->restArea(static_cast<int>(t));
  EXPECT_NEAR(area, 1.0, 1e-12);
}

TEST(MeshQuality, RadiusRatioAndWellShapedShareOfKnownTriangles)
{
  // The unit square as two right isosceles triangles: 2r/R = 2(√2 − 1), no angle in 45°–75°
  // throughout (each has a right angle).
  const Paper square = Paper::square(1.0);
  CurvedMesh halves;
  for (int v = 0; v < 4; ++v)
  {
    MeshNode node;
    node.crease_pattern = square.vertices[v].crease_pattern;
    node.paper_vertex = v;
    halves.nodes.push_back(node);
  }
  halves.triangles = { { { 0, 1, 2 }, 0 }, { { 0, 2, 3 }, 0 } };
  halves.spacing = 1.0;
  const MeshQuality q = meshQuality(halves, square);
  EXPECT_NEAR(q.mean_radius_ratio, 2 * (std::sqrt(2.0) - 1), 1e-12);
  EXPECT_EQ(q.well_shaped, 0.0);
  EXPECT_NEAR(q.min_angle, 45 * kDeg, 1e-12);
  EXPECT_NEAR(q.max_angle, 90 * kDeg, 1e-12);
  EXPECT_NEAR(q.area, 1.0, 1e-12);

  // Miura-ori of 60° parallelograms with sides equal to the spacing: every triangle is
  // equilateral, 2r/R = 1 and all of them well shaped.
  const Paper miura = miuraOri(3, 3, 1.0, 1.0, 60 * kDeg);
  const Expected<CurvedMesh> mesh = cgal(miura, 1.0);
  ASSERT_TRUE(mesh.ok()) << mesh.message();
  const MeshQuality m = meshQuality(*mesh, miura);
  EXPECT_NEAR(m.mean_radius_ratio, 1.0, 1e-9);
  EXPECT_EQ(m.well_shaped, 1.0);
}

// Bubble mesh (seed 002 §2.2): the force law, edge covering, packing quality, and a mesh
// that respects the creases (shared nodes, no triangle across a crease).
#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "test_models.h"
#include "virtual_origami/curved/bubble_mesh.h"
#include "virtual_origami/curved/delaunay.h"

using namespace virtual_origami::core;
using namespace virtual_origami::core::test;

namespace
{
constexpr double kDeg = M_PI / 180;

void expectSoundMesh(const CurvedMesh& mesh, const Paper& paper)
{
  const MeshQuality q = meshQuality(mesh, paper);
  double paper_area = 0;
  for (size_t f = 0; f < paper.faces.size(); ++f)
    paper_area += paper.faceArea(static_cast<int>(f));
  EXPECT_NEAR(q.area, paper_area, 1e-12 * paper_area);
  EXPECT_EQ(q.crossing_triangles, 0);
  // Each mesh edge on the sheet's boundary lies on a boundary paper edge, and every mesh edge
  // that joins triangles of two faces lies on the crease between them.
  for (const MeshEdge& e : mesh.edges)
  {
    if (!e.isHinge())
    {
      ASSERT_GE(e.paper_edge, 0);
      EXPECT_FALSE(paper.edges[e.paper_edge].isCrease());
    }
    else if (mesh.triangles[e.triangles[0]].face != mesh.triangles[e.triangles[1]].face)
    {
      ASSERT_GE(e.paper_edge, 0);
      EXPECT_TRUE(paper.edges[e.paper_edge].isCrease());
    }
  }
}
}  // namespace

TEST(BubbleForce, MeetsTheSeedConditionsWithAStableRestDistance)
{
  const BubbleForce f = BubbleForce::fit(1.0, 1.5, 2.0);
  EXPECT_NEAR(f(1.0), 0.0, 1e-12);
  EXPECT_NEAR(f(1.5 - 1e-12), 0.0, 1e-9);
  EXPECT_EQ(f(1.6), 0.0);
  EXPECT_NEAR(f.slope(0.0), 0.0, 1e-12);
  EXPECT_NEAR(f.slope(1.0), -2.0, 1e-12);
  // Repulsive inside the rest distance, attractive beyond it: r0 is stable.
  for (double r = 0.0; r < 1.0; r += 0.05)
    EXPECT_GT(f(r), 0.0) << r;
  for (double r = 1.05; r < 1.5; r += 0.05)
    EXPECT_LT(f(r), 0.0) << r;
}

TEST(BubbleMesh, EdgesGetTheFewestBubblesThatCoverThem)
{
  EXPECT_EQ(edgeBubbleCount(0.5, 1.0), 0);  // the end bubbles cover it
  EXPECT_EQ(edgeBubbleCount(1.0, 1.0), 0);
  EXPECT_EQ(edgeBubbleCount(1.01, 1.0), 1);
  EXPECT_EQ(edgeBubbleCount(10.0, 1.0), 9);
  EXPECT_EQ(edgeBubbleCount(10.5, 1.0), 10);
}

TEST(ConstrainedDelaunay, KeepsConstraintsAndRefusesCoincidentPoints)
{
  // A square with a point near one diagonal: the other diagonal is forced in.
  const std::vector<Vec2> points{ { 0, 0 }, { 1, 0 }, { 1, 1 }, { 0, 1 } };
  const auto free_triangles = constrainedDelaunay(points, {});
  ASSERT_TRUE(free_triangles.ok()) << free_triangles.message();
  EXPECT_EQ(free_triangles->size(), 2u);
  for (const std::array<int, 2>& diagonal : { std::array<int, 2>{ 0, 2 }, std::array<int, 2>{ 1, 3 } })
  {
    const auto triangles = constrainedDelaunay(points, { diagonal });
    ASSERT_TRUE(triangles.ok()) << triangles.message();
    for (const auto& t : *triangles)
    {
      const std::set<int> corners(t.begin(), t.end());
      EXPECT_TRUE(corners.count(diagonal[0]) && corners.count(diagonal[1]));
      const Vec2 u = points[t[1]] - points[t[0]], v = points[t[2]] - points[t[0]];
      EXPECT_GT(u.x() * v.y() - u.y() * v.x(), 0);  // counter-clockwise
    }
  }
  EXPECT_FALSE(constrainedDelaunay({ { 0, 0 }, { 1, 0 }, { 0, 0 } }, {}).ok());
  EXPECT_FALSE(constrainedDelaunay(points, { { 0, 2 }, { 1, 3 } }).ok());  // crossing
}

TEST(BubbleMesh, PacksAnUncreasedSquareIntoNearEquilateralTriangles)
{
  const Paper paper = Paper::square(1.0);
  BubbleMeshOptions options;
  options.spacing = 0.1;
  BubbleMeshReport report;
  const Expected<CurvedMesh> mesh = bubbleMesh(paper, options, &report);
  ASSERT_TRUE(mesh.ok()) << mesh.message();
  expectSoundMesh(*mesh, paper);
  const MeshQuality q = meshQuality(*mesh, paper);
  EXPECT_GT(q.min_angle, 30 * kDeg);
  EXPECT_LT(q.max_angle, 100 * kDeg);
  EXPECT_GT(q.min_edge, 0.6);
  EXPECT_LT(q.max_edge, 1.5);
  // About one node per equilateral cell of side 0.1: area / (√3/2 · 0.01) ≈ 115.
  EXPECT_GT(mesh->nodes.size(), 100u);
  EXPECT_LT(mesh->nodes.size(), 150u);
  EXPECT_GT(report.steps, 0);
}

TEST(BubbleMesh, NodesOnACreaseAreSharedByBothFaces)
{
  Paper paper = Paper::square(1.0);
  creaseLine(paper, p3(1, 0), p3(0, 1));  // diagonal bd
  BubbleMeshOptions options;
  options.spacing = 0.08;
  const Expected<CurvedMesh> mesh = bubbleMesh(paper, options);
  ASSERT_TRUE(mesh.ok()) << mesh.message();
  expectSoundMesh(*mesh, paper);
  int crease = -1;
  for (size_t e = 0; e < paper.edges.size(); ++e)
    if (paper.edges[e].isCrease())
      crease = static_cast<int>(e);
  ASSERT_GE(crease, 0);
  // √2 / 0.08 = 17.7: 18 divisions, 17 bubbles inside the crease, each a node of triangles
  // in both faces.
  int on_crease = 0;
  for (size_t i = 0; i < mesh->nodes.size(); ++i)
  {
    if (mesh->nodes[i].paper_edge != crease)
      continue;
    ++on_crease;
    std::set<int> faces;
    for (const MeshTriangle& t : mesh->triangles)
      for (int n : t.nodes)
        if (n == static_cast<int>(i))
          faces.insert(t.face);
    EXPECT_EQ(faces.size(), 2u);
  }
  EXPECT_EQ(on_crease, 17);
  EXPECT_GT(meshQuality(*mesh, paper).min_angle, 25 * kDeg);
}

TEST(BubbleMesh, CreaseStripsMakeTheTrianglesBesideACreaseThatNarrow)
{
  Paper paper = Paper::square(1.0);
  creaseLine(paper, p3(1, 0), p3(0, 1));  // diagonal bd
  BubbleMeshOptions options;
  options.spacing = 0.08;
  options.crease_strip = 1e-3;
  const Expected<CurvedMesh> mesh = bubbleMesh(paper, options);
  ASSERT_TRUE(mesh.ok()) << mesh.message();
  expectSoundMesh(*mesh, paper);
  // Every triangle with a side on the crease has its third node a strip's width from it (the
  // rows beside the crease), on its own side; without strips they lie about a spacing away.
  const Vec2 b(1, 0), d(0, 1);
  const Vec2 across = Vec2(1, 1).normalized();
  int beside = 0;
  for (const MeshEdge& e : mesh->edges)
  {
    if (e.paper_edge < 0 || !paper.edges[e.paper_edge].isCrease())
      continue;
    for (int t : e.triangles)
    {
      ASSERT_GE(t, 0);
      for (int n : mesh->triangles[t].nodes)
        if (n != e.nodes[0] && n != e.nodes[1])
        {
          const double distance = std::abs(across.dot(mesh->nodes[n].crease_pattern - b));
          // Near the crease's ends the row meets the sheet's edge: a node there may lie on the
          // crease's end beside it, farther along, still within a strip's width of the row.
          EXPECT_LT(distance, 1e-3 + 1e-9) << "triangle " << t;
          ++beside;
        }
    }
  }
  EXPECT_EQ(beside, 2 * 18);  // 18 pieces of the crease, a triangle on each side
  (void)d;
}

TEST(BubbleMesh, CoarseFacesGetNoInteriorBubbles)
{
  Paper paper = Paper::square(1.0);
  creaseLine(paper, p3(0.5, -0.1), p3(0.5, 1.1));
  BubbleMeshOptions options;
  options.spacing = 0.1;
  options.curved_faces.assign(paper.faces.size(), 0);
  options.curved_faces[0] = 1;
  const Expected<CurvedMesh> mesh = bubbleMesh(paper, options);
  ASSERT_TRUE(mesh.ok()) << mesh.message();
  expectSoundMesh(*mesh, paper);
  for (const MeshNode& n : mesh->nodes)
    EXPECT_NE(n.paper_face, 1);
  int in_face0 = 0;
  for (const MeshNode& n : mesh->nodes)
    in_face0 += n.paper_face == 0 ? 1 : 0;
  EXPECT_GT(in_face0, 20);
}

TEST(BubbleMesh, RemeshesAFoldedStackAndPlacesNodesOnTheFoldedFaces)
{
  Paper paper = stackOfLayers(2);
  const Expected<CurvedMesh> mesh = bubbleMesh(paper, {});
  ASSERT_TRUE(mesh.ok()) << mesh.message();
  expectSoundMesh(*mesh, paper);
  const Positions x = placeNodes(*mesh, paper);
  // Folded flat into [0, .5]²: every node is there, at z = 0, and every mesh edge keeps its length.
  for (Eigen::Index i = 0; i < x.cols(); ++i)
  {
    EXPECT_NEAR(x(2, i), 0.0, 1e-12);
    EXPECT_GT(x(0, i), -1e-12);
    EXPECT_LT(x(0, i), 0.5 + 1e-12);
  }
  for (const MeshEdge& e : mesh->edges)
    EXPECT_NEAR((x.col(e.nodes[0]) - x.col(e.nodes[1])).norm(),
                (mesh->nodes[e.nodes[0]].crease_pattern - mesh->nodes[e.nodes[1]].crease_pattern).norm(), 1e-12);
}

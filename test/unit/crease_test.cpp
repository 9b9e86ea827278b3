#include <gtest/gtest.h>

#include "test_models.h"
#include "virtual_origami/core/crease.h"
#include "virtual_origami/core/validity.h"

using namespace virtual_origami::core;
using namespace virtual_origami::core::test;

namespace
{
/// Fails the crease and checks the message and that nothing changed.
void expectRejected(Paper& paper, const CreaseRequest& request, const std::string& words)
{
  const Paper before = paper;
  const Expected<CreaseResult> result = crease(paper, request);
  EXPECT_FALSE(result.ok());
  EXPECT_NE(result.message().find(words), std::string::npos) << result.message();
  EXPECT_TRUE(paper == before);
}

CreaseRequest line(const Vec3& a, const Vec3& b)
{
  CreaseRequest r;
  r.start = a;
  r.end = b;
  return r;
}
}  // namespace

TEST(Crease, SplitsASingleFace)
{
  Paper paper = Paper::square(1.0);
  const CreaseResult r = creaseLine(paper, p3(0.5, -0.2), p3(0.5, 1.2));
  ASSERT_EQ(r.new_edges.size(), 1u);
  EXPECT_EQ(r.new_vertices.size(), 2u);
  EXPECT_EQ(paper.faces.size(), 2u);
  EXPECT_EQ(paper.vertices.size(), 6u);
  EXPECT_EQ(paper.edges.size(), 7u);
  const Edge& c = paper.edges[r.new_edges[0]];
  EXPECT_TRUE(c.isCrease());
  EXPECT_EQ(c.assignment, Assignment::Unassigned);
  EXPECT_EQ(c.fold_angle, 0.0);
  for (int v : c.vertices)
    EXPECT_NEAR(paper.vertices[v].crease_pattern.x(), 0.5, 1e-15);
  EXPECT_NEAR(paper.faceArea(0), 0.5, 1e-15);
  EXPECT_NEAR(paper.faceArea(1), 0.5, 1e-15);
  expectValid(paper);
}

TEST(Crease, ThroughExistingVertices)
{
  Paper paper = Paper::square(1.0);
  const CreaseResult r = creaseLine(paper, p3(0, 0), p3(1, 1));
  EXPECT_TRUE(r.new_vertices.empty());
  ASSERT_EQ(r.new_edges.size(), 1u);
  EXPECT_EQ(paper.vertices.size(), 4u);
  EXPECT_EQ(paper.faces.size(), 2u);
  const auto& ends = paper.edges[r.new_edges[0]].vertices;
  EXPECT_EQ(std::min(ends[0], ends[1]), 0);
  EXPECT_EQ(std::max(ends[0], ends[1]), 2);
  expectValid(paper);
  // A second crease through the new crease's midpoint makes one vertex there, shared.
  const CreaseResult r2 = creaseLine(paper, p3(1, 0), p3(0, 1));
  EXPECT_EQ(r2.new_vertices.size(), 1u);
  EXPECT_EQ(r2.new_edges.size(), 2u);
  EXPECT_EQ(paper.faces.size(), 4u);
  EXPECT_TRUE(paper.vertices[r2.new_vertices[0]].crease_pattern.isApprox(Vec2(0.5, 0.5)));
  expectValid(paper);
}

TEST(Crease, AlongAnExistingEdgeChangesNothing)
{
  Paper paper = Paper::square(1.0);
  creaseLine(paper, p3(0, 0), p3(1, 1));
  expectRejected(paper, line(p3(0, 0), p3(1, 1)), "existing edge");
  expectRejected(paper, line(p3(-0.5, 0), p3(1.5, 0)), "existing edge");  // along the boundary
}

TEST(Crease, NearParallelSliver)
{
  Paper paper = Paper::square(1.0);
  creaseLine(paper, p3(0.5, -0.1), p3(0.5, 1.1));
  const CreaseResult r = creaseLine(paper, p3(0.5 + 1e-4, -0.1), p3(0.5 + 3e-4, 1.1));
  ASSERT_EQ(r.split_faces.size(), 1u);
  EXPECT_EQ(paper.faces.size(), 3u);
  double smallest = 1;
  for (size_t f = 0; f < paper.faces.size(); ++f)
    smallest = std::min(smallest, paper.faceArea(static_cast<int>(f)));
  EXPECT_NEAR(smallest, 2e-4, 1e-12);  // a trapezoid 1.17e-4 and 2.83e-4 wide
  expectValid(paper);
}

TEST(Crease, EveryLayerOfAStackIsCreased)
{
  for (int times : { 1, 2, 3 })
  {
    Paper paper = stackOfLayers(times);
    expectValid(paper);
    const size_t layers = size_t{ 1 } << times;
    // A line across the stack's footprint (within x ∈ [0, 0.5]) at y = 0.2.
    const Paper before = paper;
    const CreaseResult r = creaseLine(paper, p3(-0.1, 0.2), p3(0.6, 0.2));
    SCOPED_TRACE(times);
    EXPECT_EQ(r.split_faces.size(), layers);
    EXPECT_EQ(r.new_edges.size(), layers);
    EXPECT_EQ(paper.faces.size(), before.faces.size() + layers);
    // Every new crease lies on the cut in 3D and in the crease pattern at y = 0.2 or its mirror.
    for (int e : r.new_edges)
      for (int v : paper.edges[e].vertices)
        EXPECT_NEAR(paper.vertices[v].folded.y(), 0.2, 1e-12);
    expectValid(paper);
  }
}

TEST(Crease, WedgeFromAnEye)
{
  Paper paper = Paper::square(1.0);
  CreaseRequest request = line(p3(0.5, 0.0), p3(0.5, 1.0));
  request.eye = p3(0.5, 0.5, 3.0);
  const Expected<CreaseResult> r = crease(paper, request);
  ASSERT_TRUE(r.ok()) << r.message();
  EXPECT_EQ(paper.faces.size(), 2u);
  for (int v : paper.edges[r->new_edges[0]].vertices)
    EXPECT_NEAR(paper.vertices[v].crease_pattern.x(), 0.5, 1e-12);
  expectValid(paper);
  // A wedge from an oblique eye: the crease goes where the rays meet the sheet.
  Paper oblique = Paper::square(1.0);
  CreaseRequest slanted = line(p3(0.3, 0.0, 0.0), p3(0.3, 1.0, 0.0));
  slanted.eye = p3(-1.0, 0.5, 2.0);
  ASSERT_TRUE(crease(oblique, slanted).ok());
  EXPECT_EQ(oblique.faces.size(), 2u);
  // A wedge that ends inside the sheet cuts no face completely.
  CreaseRequest short_line = line(p3(0.3, 0.2), p3(0.3, 0.8));
  short_line.eye = p3(0.3, 0.5, 3.0);
  expectRejected(paper, short_line, "completely");
  CreaseRequest eye_on_line = line(p3(0.2, 0.2), p3(0.8, 0.8));
  eye_on_line.eye = p3(1.0, 1.0, 0.0);
  expectRejected(paper, eye_on_line, "eye");
}

TEST(Crease, TheWedgeCutsStackedLayersAsTheEyeSeesThem)
{
  Paper paper = stackOfLayers(1);
  CreaseRequest request = line(p3(0.25, -0.1), p3(0.25, 1.1));
  request.eye = p3(0.25, 0.5, 5.0);
  const Expected<CreaseResult> r = crease(paper, request);
  ASSERT_TRUE(r.ok()) << r.message();
  EXPECT_EQ(r->split_faces.size(), 2u);
  expectValid(paper);
}

TEST(Crease, BadInputChangesNothing)
{
  Paper paper = Paper::square(1.0);
  creaseLine(paper, p3(0.5, -0.1), p3(0.5, 1.1));
  expectRejected(paper, line(p3(2, 2), p3(3, 3)), "misses the paper");
  expectRejected(paper, line(p3(0.2, 0.2), p3(0.2, 0.2)), "zero length");
  expectRejected(paper, line(p3(std::nan(""), 0), p3(1, 1)), "not a finite point");
  expectRejected(paper, line(p3(0, 0), p3(INFINITY, 1)), "not a finite point");
  expectRejected(paper, line(p3(0.2, 0.2), p3(0.3, 0.3)), "completely");  // ends inside a face
  expectRejected(paper, line(p3(0.2, 0.2, 0), p3(0.2, 0.2, 1)), "perpendicular");
  CreaseRequest eye_nan = line(p3(0, 0), p3(1, 1));
  eye_nan.eye = p3(0, NAN, 1);
  expectRejected(paper, eye_nan, "not a finite point");
}

TEST(Crease, SnapsEndsBeforeCutting)
{
  Paper paper = Paper::square(1.0);
  CreaseRequest request = line(p3(0.01, 0.015), p3(0.99, 0.985));
  request.snap = true;
  const Expected<CreaseResult> r = crease(paper, request);
  ASSERT_TRUE(r.ok()) << r.message();
  EXPECT_EQ(r->start_snap.kind, SnapKind::Vertex);
  EXPECT_EQ(r->end_snap.kind, SnapKind::Vertex);
  EXPECT_TRUE(r->new_vertices.empty());  // exactly corner to corner
  expectValid(paper);
}

TEST(Crease, EndsFarOutsideThePaperAreRefusedAsSuch)
{
  // Ends at 1e308 used to overflow the cut's geometry into NaN and be refused as running
  // "along an existing edge"; any point a thousand sheets away is refused for what it is,
  // before any geometry, as is a point that is not finite at all.
  Paper paper = Paper::square(1.0);
  creaseLine(paper, p3(0.5, -0.1), p3(0.5, 1.1));
  for (double far : { 1e308, -1e308, 1e20, 2000.0 })
  {
    expectRejected(paper, line(p3(far, 0.5), p3(0.5, 0.5)), "start lies far outside the paper");
    expectRejected(paper, line(p3(0.25, 0.5), p3(0.75, far)), "end lies far outside the paper");
    expectRejected(paper, line(p3(far, far, far), p3(-far, -far, -far)), "start lies far outside the paper");
    CreaseRequest far_eye = line(p3(0.25, -0.1), p3(0.25, 1.1));
    far_eye.eye = p3(0.25, 0.5, far);
    expectRejected(paper, far_eye, "eye point lies far outside the paper");
  }
  for (double bad : { NAN, INFINITY, -INFINITY })
  {
    expectRejected(paper, line(p3(bad, 0.5), p3(0.5, 0.5)), "start is not a finite point");
    expectRejected(paper, line(p3(0.25, 0.5), p3(0.75, 0.5, bad)), "end is not a finite point");
    CreaseRequest bad_eye = line(p3(0.25, -0.1), p3(0.25, 1.1));
    bad_eye.eye = p3(0.25, bad, 3);
    expectRejected(paper, bad_eye, "eye point is not a finite point");
  }
  // A long line that still lies within reach creases as usual.
  creaseLine(paper, p3(0.25, -500), p3(0.25, 500));
  expectValid(paper);
}

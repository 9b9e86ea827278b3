// The planar graph segments draw (core/planar_graph.h): points merged, segments split where they
// meet, and faces traced with their winding.
#include <gtest/gtest.h>

#include <algorithm>
#include <set>
#include <vector>

#include "virtual_origami/core/planar_geometry.h"
#include "virtual_origami/core/planar_graph.h"

using namespace virtual_origami::core;

namespace
{
/// The unit square and its diagonal from (0, 0) to (1, 1).
const std::vector<Vec2> kSquare{ { 0, 0 }, { 1, 0 }, { 1, 1 }, { 0, 1 } };
const std::vector<std::array<int, 2>> kSquareWithDiagonal{ { 0, 1 }, { 1, 2 }, { 2, 3 }, { 3, 0 }, { 0, 2 } };
}  // namespace

TEST(SnappedPoints, MergesPointsWithinTheToleranceOnly)
{
  SnappedPoints points(1e-3);
  const int a = points.snap(Vec2(0, 0));
  EXPECT_EQ(points.snap(Vec2(5e-4, -5e-4)), a);
  EXPECT_EQ(points.snap(Vec2(1e-3, 0)), a);  // on the tolerance: the same point
  const int b = points.snap(Vec2(1.5e-3, 0));
  EXPECT_NE(b, a);
  // Within the tolerance of both: the nearer one, across the grid's cell boundaries.
  EXPECT_EQ(points.snap(Vec2(0.6e-3, 0)), a);
  EXPECT_EQ(points.snap(Vec2(0.9e-3, 0)), b);
  EXPECT_EQ(points.snap(Vec2(1.5e-3, 0.9e-3)), b);
  EXPECT_EQ(points.points().size(), 2u);
  EXPECT_EQ(points.points()[a], Vec2(0, 0));  // the first point stays where it was
}

TEST(PointsAlongSegments, CrossingSegmentsShareTheirCrossing)
{
  SnappedPoints points(1e-9);
  std::vector<SnappedSegment> segments{ { Vec2(0, 0), Vec2(2, 2), -1, -1 }, { Vec2(0, 2), Vec2(2, 0), -1, -1 } };
  for (SnappedSegment& s : segments)
  {
    s.ia = points.snap(s.a);
    s.ib = points.snap(s.b);
  }
  const std::vector<std::vector<int>> along = pointsAlongSegments(segments, points, 1e-9);
  ASSERT_EQ(along.size(), 2u);
  ASSERT_EQ(along[0].size(), 3u);
  ASSERT_EQ(along[1].size(), 3u);
  EXPECT_EQ(along[0].front(), segments[0].ia);
  EXPECT_EQ(along[0].back(), segments[0].ib);
  EXPECT_EQ(along[0][1], along[1][1]);
  EXPECT_TRUE(points.points()[along[0][1]].isApprox(Vec2(1, 1)));
}

TEST(PointsAlongSegments, AnEndOnAnotherSegmentSplitsItAndOverlapsShareTheirPoints)
{
  SnappedPoints points(1e-9);
  // A T: the stem ends on the bar's middle; and a second bar lying over half the first.
  std::vector<SnappedSegment> segments{ { Vec2(0, 0), Vec2(4, 0), -1, -1 },
                                        { Vec2(2, 0), Vec2(2, 3), -1, -1 },
                                        { Vec2(3, 0), Vec2(1, 0), -1, -1 } };
  for (SnappedSegment& s : segments)
  {
    s.ia = points.snap(s.a);
    s.ib = points.snap(s.b);
  }
  const std::vector<std::vector<int>> along = pointsAlongSegments(segments, points, 1e-9);
  const auto at = [&](double x) { return points.snap(Vec2(x, 0)); };
  EXPECT_EQ(along[0], (std::vector<int>{ at(0), at(1), at(2), at(3), at(4) }));
  EXPECT_EQ(along[1], (std::vector<int>{ at(2), segments[1].ib }));
  EXPECT_EQ(along[2], (std::vector<int>{ at(3), at(2), at(1) }));  // from its own a to its own b
}

TEST(TraceHalfEdgeCycles, EveryHalfEdgeOnceBoundedFacesCounterClockwise)
{
  const std::vector<std::vector<int>> cycles = traceHalfEdgeCycles(kSquare, kSquareWithDiagonal);
  ASSERT_EQ(cycles.size(), 3u);  // two triangles and the outer face
  std::multiset<int> seen;
  int clockwise = 0;
  for (const std::vector<int>& cycle : cycles)
  {
    seen.insert(cycle.begin(), cycle.end());
    std::vector<int> corners;
    for (size_t k = 0; k < cycle.size(); ++k)
    {
      const int h = cycle[k], next = cycle[(k + 1) % cycle.size()];
      EXPECT_EQ(kSquareWithDiagonal[h / 2][1 - h % 2], kSquareWithDiagonal[next / 2][next % 2]) << "each half-edge "
                                                                                                   "ends where the "
                                                                                                   "next starts";
      corners.push_back(kSquareWithDiagonal[h / 2][h % 2]);
    }
    const double area = signedArea(cornersOf(kSquare, corners));
    if (area < 0)
    {
      ++clockwise;
      EXPECT_EQ(area, -1.0);  // the outer face: the whole square, clockwise
    }
    else
      EXPECT_EQ(area, 0.5);
  }
  EXPECT_EQ(clockwise, 1);
  EXPECT_EQ(seen.size(), 2 * kSquareWithDiagonal.size());
  for (int h = 0; h < 2 * static_cast<int>(kSquareWithDiagonal.size()); ++h)
    EXPECT_EQ(seen.count(h), 1u) << "half-edge " << h;
}

TEST(BoundedFaces, DropsTheOuterFaceAndKeepsCornersWithTheirHalfEdges)
{
  const std::vector<TracedFace> faces = boundedFaces(kSquare, kSquareWithDiagonal, 1e-12);
  ASSERT_EQ(faces.size(), 2u);
  std::set<std::set<int>> corner_sets;
  for (const TracedFace& face : faces)
  {
    ASSERT_EQ(face.vertices.size(), face.half_edges.size());
    for (size_t k = 0; k < face.vertices.size(); ++k)
      EXPECT_EQ(kSquareWithDiagonal[face.half_edges[k] / 2][face.half_edges[k] % 2], face.vertices[k]);
    EXPECT_EQ(signedArea(cornersOf(kSquare, face.vertices)), 0.5);
    corner_sets.insert(std::set<int>(face.vertices.begin(), face.vertices.end()));
  }
  EXPECT_EQ(corner_sets, (std::set<std::set<int>>{ { 0, 1, 2 }, { 0, 2, 3 } }));
  // Faces no larger than the least area are left out too.
  EXPECT_TRUE(boundedFaces(kSquare, kSquareWithDiagonal, 0.5).empty());
}

TEST(BoundedFaces, ADanglingEdgeIsWalkedBothWaysInsideItsFace)
{
  // The square with an edge from corner 0 to its centre, ending there: the face passes
  // corner 0 twice (readers refuse such a face by that sign).
  std::vector<Vec2> points = kSquare;
  points.emplace_back(0.5, 0.5);
  const std::vector<std::array<int, 2>> edges{ { 0, 1 }, { 1, 2 }, { 2, 3 }, { 3, 0 }, { 0, 4 } };
  const std::vector<TracedFace> faces = boundedFaces(points, edges, 1e-12);
  ASSERT_EQ(faces.size(), 1u);
  EXPECT_EQ(faces[0].vertices.size(), 6u);
  EXPECT_EQ(std::count(faces[0].vertices.begin(), faces[0].vertices.end(), 0), 2);
  EXPECT_EQ(signedArea(cornersOf(points, faces[0].vertices)), 1.0);
}

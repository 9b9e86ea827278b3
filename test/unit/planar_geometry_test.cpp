// The plane's small helpers (core/planar_geometry.h) on cases whose answers are known exactly.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "virtual_origami/core/planar_geometry.h"

using namespace virtual_origami::core;

TEST(PlanarGeometry, Cross2IsPositiveCounterClockwise)
{
  EXPECT_EQ(cross2(Vec2(1, 0), Vec2(0, 1)), 1.0);
  EXPECT_EQ(cross2(Vec2(0, 1), Vec2(1, 0)), -1.0);
  EXPECT_EQ(cross2(Vec2(2, 3), Vec2(4, 6)), 0.0);  // parallel
  EXPECT_EQ(cross2(Vec2(2, 0), Vec2(1, 3)), 6.0);  // twice the triangle's area
}

TEST(PlanarGeometry, SignedAreaFollowsTheWinding)
{
  const std::vector<Vec2> square{ { 0, 0 }, { 2, 0 }, { 2, 3 }, { 0, 3 } };
  EXPECT_EQ(signedArea(square), 6.0);
  EXPECT_EQ(signedArea(std::vector<Vec2>(square.rbegin(), square.rend())), -6.0);
  // The indexed form reads the corners through the cycle.
  EXPECT_EQ(signedArea(square, { 0, 1, 2, 3 }), 6.0);
  EXPECT_EQ(signedArea(square, { 0, 3, 2, 1 }), -6.0);
  EXPECT_EQ(signedArea(square, { 0, 1, 2 }), 3.0);
  EXPECT_EQ(signedArea(std::vector<Vec2>{}), 0.0);
}

TEST(PlanarGeometry, AngleBetweenIsUnsignedAndExactAtTheEnds)
{
  EXPECT_DOUBLE_EQ(angleBetween(Vec2(1, 0), Vec2(0, 1)), M_PI / 2);
  EXPECT_DOUBLE_EQ(angleBetween(Vec2(1, 0), Vec2(0, -1)), M_PI / 2);
  EXPECT_DOUBLE_EQ(angleBetween(Vec2(1, 1), Vec2(-1, -1)), M_PI);
  EXPECT_EQ(angleBetween(Vec2(3, 0), Vec2(1, 0)), 0.0);
  // A tiny angle keeps its digits, where acos of the cosine would round it to 0.
  EXPECT_NEAR(angleBetween(Vec2(1, 0), Vec2(1, 1e-9)), 1e-9, 1e-20);
}

TEST(PlanarGeometry, PointSegmentDistanceClampsToTheEnds)
{
  const Vec2 a(0, 0), b(4, 0);
  EXPECT_EQ(pointSegmentDistance(Vec2(2, 3), a, b), 3.0);   // above the middle
  EXPECT_EQ(pointSegmentDistance(Vec2(-3, 4), a, b), 5.0);  // beyond a
  EXPECT_EQ(pointSegmentDistance(Vec2(7, 4), a, b), 5.0);   // beyond b
  EXPECT_EQ(pointSegmentDistance(Vec2(1, 0), a, b), 0.0);
  // A segment without length is its point.
  EXPECT_EQ(pointSegmentDistance(Vec2(3, 4), a, a), 5.0);
}

TEST(PlanarGeometry, SegmentDistanceIsZeroWhenTheyCross)
{
  EXPECT_EQ(segmentDistance(Vec2(0, 0), Vec2(2, 2), Vec2(0, 2), Vec2(2, 0)), 0.0);
  EXPECT_EQ(segmentDistance(Vec2(0, 0), Vec2(2, 0), Vec2(0, 1), Vec2(2, 1)), 1.0);  // parallel
  EXPECT_EQ(segmentDistance(Vec2(0, 0), Vec2(2, 0), Vec2(5, 4), Vec2(5, 9)), 5.0);  // end to end
  // A T: the end of one on the other.
  EXPECT_EQ(segmentDistance(Vec2(0, 0), Vec2(2, 0), Vec2(1, 0), Vec2(1, 3)), 0.0);
}

TEST(PlanarGeometry, BoundingDiagonal)
{
  EXPECT_EQ(boundingDiagonal({ { 1, 1 }, { 4, 2 }, { 2, 5 } }), 5.0);
  EXPECT_EQ(boundingDiagonal({ { 1, 1 } }), 0.0);
}

// Convex pieces of a simple polygon (core/convex_partition.h): every piece convex, the pieces
// tiling the polygon, and no more pieces than the shape needs where that is plain.
#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "virtual_origami/core/convex_partition.h"
#include "virtual_origami/core/planar_geometry.h"

using namespace virtual_origami::core;

namespace
{
/// Each piece convex and counter-clockwise, their areas adding up to the polygon's, and one
/// diagonal fewer than pieces (a tree of pieces).
void expectConvexTiling(const std::vector<Vec2>& polygon, const ConvexPieces& split)
{
  ASSERT_FALSE(split.pieces.empty());
  EXPECT_EQ(split.diagonals.size() + 1, split.pieces.size());
  double area = 0;
  for (const std::vector<int>& piece : split.pieces)
  {
    const std::vector<Vec2> corners = cornersOf(polygon, piece);
    const size_t n = corners.size();
    ASSERT_GE(n, 3u);
    for (size_t i = 0; i < n; ++i)
      EXPECT_GE(cross2(corners[(i + 1) % n] - corners[i], corners[(i + 2) % n] - corners[(i + 1) % n]), 0.0);
    area += signedArea(corners);
  }
  EXPECT_NEAR(area, signedArea(polygon), 1e-12);
}
}  // namespace

TEST(ConvexPieces, ConvexPolygonStaysWhole)
{
  const std::vector<Vec2> hexagon{ { 2, 0 }, { 1, 1.7 }, { -1, 1.7 }, { -2, 0 }, { -1, -1.7 }, { 1, -1.7 } };
  const ConvexPieces split = convexPieces(hexagon, 1e-13);
  ASSERT_EQ(split.pieces.size(), 1u);
  EXPECT_TRUE(split.diagonals.empty());
  expectConvexTiling(hexagon, split);
}

TEST(ConvexPieces, AnLShapeIsCutAtItsReflexCornerOnly)
{
  // Corner 3, (1, 1), is the only reflex one: every diagonal kept is needed there.
  const std::vector<Vec2> l{ { 0, 0 }, { 2, 0 }, { 2, 1 }, { 1, 1 }, { 1, 2 }, { 0, 2 } };
  const ConvexPieces split = convexPieces(l, 1e-13);
  expectConvexTiling(l, split);
  EXPECT_EQ(split.pieces.size(), 2u);
  for (const auto& [u, v] : split.diagonals)
    EXPECT_TRUE(u == 3 || v == 3) << "a diagonal " << u << "-" << v << " away from the reflex corner";
}

TEST(ConvexPieces, ACombNeedsNoMoreThanTwicePerReflexCornerAndOne)
{
  // Three teeth, four reflex corners: Hertel–Mehlhorn leaves at most 2r + 1 pieces.
  const std::vector<Vec2> comb{ { 0, 0 }, { 5, 0 }, { 5, 2 }, { 4, 2 }, { 4, 1 }, { 3, 1 },
                                { 3, 2 }, { 2, 2 }, { 2, 1 }, { 1, 1 }, { 1, 2 }, { 0, 2 } };
  const ConvexPieces split = convexPieces(comb, 1e-13);
  expectConvexTiling(comb, split);
  EXPECT_LE(split.pieces.size(), 9u);
  EXPECT_GE(split.pieces.size(), 3u);  // no fewer than the teeth
}

TEST(ConvexPieces, StartingAtTurnsACycle)
{
  EXPECT_EQ(startingAt({ 4, 7, 1, 9 }, 1), (std::vector<int>{ 1, 9, 4, 7 }));
  EXPECT_EQ(startingAt({ 4, 7, 1, 9 }, 4), (std::vector<int>{ 4, 7, 1, 9 }));
}

#include <gtest/gtest.h>

#include <cmath>

#include "test_models.h"
#include "virtual_origami/core/flat_fold.h"
#include "virtual_origami/core/layers.h"
#include "virtual_origami/core/metrics.h"

using namespace virtual_origami::core;
using namespace virtual_origami::core::test;

namespace
{
const Vec2 kCentre(0.5, 0.5);

Vec3 foldedAt(const Paper& paper, const Vec2& crease_pattern_point)
{
  const int v = paper.vertexAt(crease_pattern_point);
  EXPECT_GE(v, 0);
  return v >= 0 ? paper.vertices[v].folded : Vec3::Constant(NAN);
}
}  // namespace

TEST(FlatFold, OneCreaseFoldsLikeARotation)
{
  Paper paper = Paper::square(1.0);
  creaseLine(paper, p3(0, 0), p3(1, 1));
  Paper turned = paper;
  RotateRequest request;
  request.click = p3(0.2, 0.8);
  request.angle = M_PI;
  ASSERT_TRUE(rotate(turned, request).ok());

  const Expected<FlatFoldResult> folded = flatFold(paper, { { { v2(0, 0), v2(1, 1), M_PI } }, v2(0.9, 0.1) });
  ASSERT_TRUE(folded.ok()) << folded.message();
  EXPECT_EQ(folded->moved_faces.size(), 1u);
  EXPECT_EQ(folded->changed_edges.size(), 1u);
  EXPECT_LT((foldedAt(paper, v2(0, 1)) - p3(1, 0)).norm(), 1e-12);  // the corner folded onto its mirror image
  for (size_t v = 0; v < paper.vertices.size(); ++v)
    EXPECT_LT((paper.vertices[v].folded - turned.vertices[v].folded).norm(), 1e-12);
  EXPECT_EQ(layerCount(paper, p3(0.7, 0.2)), 2);
  expectValid(paper);
}

TEST(FlatFold, AFoldThatDoesNotCloseIsRefusedAndLeavesThePaper)
{
  Paper paper = creasedSquare();
  const Paper before = paper;
  // One crease alone through the centre: the centre would tear.
  const Expected<FlatFoldResult> torn = flatFold(paper, { { { v2(0.5, 0), kCentre, M_PI } }, v2(0.9, 0.1) });
  EXPECT_FALSE(torn.ok());
  EXPECT_NE(torn.message().find("does not close"), std::string::npos) << torn.message();
  EXPECT_TRUE(paper == before);

  EXPECT_FALSE(flatFold(paper, { { { v2(0.1, 0.2), v2(0.2, 0.4), M_PI } }, v2(0.9, 0.1) }).ok());  // no crease there
  EXPECT_FALSE(flatFold(paper, { { { v2(0, 0), v2(1, 1), 4.0 } }, v2(0.9, 0.1) }).ok());            // past 180°
  EXPECT_FALSE(flatFold(paper, { { { v2(0, 0), v2(1, 1), M_PI } }, v2(2, 2) }).ok());               // fixed point off the sheet
  EXPECT_FALSE(flatFold(paper, { { { v2(0, 0), v2(1, 1), NAN } }, v2(0.9, 0.1) }).ok());
  EXPECT_TRUE(paper == before);
}

// Square base, first half: the sheet folded in half on both diagonals is a triangle of four
// layers; squashing its top flap opens the flap's quadrant flat into a square beside the
// flap that is still a triangle.
TEST(FlatFold, SquashFoldOpensTheFlapIntoASquare)
{
  Paper paper = creasedSquare();
  const Vec2 fixed(0.9, 0.3);  // in the quadrant x > .5, y < .5, on the lower-right side of the diagonal
  ASSERT_TRUE(flatFold(paper, { { { v2(0, 0), v2(1, 1), M_PI } }, fixed }).ok());
  // The second fold turns the two layers the same way: valley in the lower layer, mountain in the
  // upper one, which faces down.
  ASSERT_TRUE(flatFold(paper, { { { v2(1, 0), kCentre, M_PI }, { kCentre, v2(0, 1), -M_PI } }, fixed }).ok());
  EXPECT_EQ(layerCount(paper, p3(0.9, 0.3)), 4);
  EXPECT_EQ(layerCount(paper, p3(0.9, 0.7)), 4);
  EXPECT_EQ(layerCount(paper, p3(0.6, 0.2)), 0);  // outside the triangle (.5,.5), (1,0), (1,1)

  const Expected<FlatFoldResult> squashed = flatFold(paper, { { { v2(0, 0), kCentre, 0.0 },        // the flap's spine opens
                                                                { v2(1, 0), kCentre, 0.0 },        // its hinge in one layer
                                                                { v2(0.5, 0), kCentre, M_PI },     // its sides fold
                                                                { v2(0, 0.5), kCentre, M_PI } },
                                                              fixed });
  ASSERT_TRUE(squashed.ok()) << squashed.message();
  expectValid(paper);
  EXPECT_LT(edgeStrain(paper).max, 1e-12);
  // The flap's quadrant [0, .5]² now lies flat on the square [.5, 1] × [0, .5].
  for (const Vec2& corner : { v2(0, 0), v2(0.5, 0), v2(0, 0.5), kCentre })
  {
    const Vec3 p = foldedAt(paper, corner);
    EXPECT_NEAR(p.z(), 0.0, 1e-12);
    EXPECT_TRUE(p.x() > 0.5 - 1e-12 && p.x() < 1 + 1e-12 && p.y() > -1e-12 && p.y() < 0.5 + 1e-12)
        << corner.transpose() << " -> " << p.transpose();
  }
  // Layers: the square's half beyond the old triangle is the opened flap's two layers alone;
  // its half on the triangle holds those two over the two layers under the flap; the
  // triangle (.5,.5), (1,.5), (1,1) keeps the other flap's two. Areas sum to the sheet's.
  const int beyond = layerCount(paper, p3(0.6, 0.3));
  const int over = layerCount(paper, p3(0.9, 0.2));
  const int other = layerCount(paper, p3(0.9, 0.7));
  EXPECT_EQ(beyond, 2);
  EXPECT_EQ(over, 4);
  EXPECT_EQ(other, 2);
  EXPECT_EQ((beyond + over + other) * 0.125, 1.0);
}

// An inside reverse fold of a two-layer point: the sheet folded on its diagonal, the tip at
// (0, 0) reversed along x = 0.3 through both layers. The tip lands mirrored across the line,
// the spine's piece in the tip turns from valley to mountain, the new creases fold valley (each
// layer's own side: the layers face opposite ways), the vertex where they meet the spine keeps
// Maekawa's |M − V| = 2, and the tip's two layers lie between the body's.
TEST(FlatFold, InsideReverseFoldMirrorsTheTipAndFlipsItsSpine)
{
  Paper paper = Paper::square(1.0);
  creaseLine(paper, p3(0, 0), p3(1, 1));
  const Vec2 fixed(0.9, 0.1);
  ASSERT_TRUE(flatFold(paper, { { { v2(0, 0), v2(1, 1), M_PI } }, fixed }).ok());
  creaseLine(paper, p3(0.3, -0.1), p3(0.3, 0.4));  // through both layers
  ASSERT_EQ(paper.faces.size(), 4u);

  const Expected<FlatFoldResult> reversed = flatFold(paper, { { { v2(0, 0), v2(0.3, 0.3), -M_PI },
                                                                { v2(0.3, 0), v2(0.3, 0.3), M_PI },
                                                                { v2(0, 0.3), v2(0.3, 0.3), M_PI } },
                                                              fixed });
  ASSERT_TRUE(reversed.ok()) << reversed.message();
  expectValid(paper);
  EXPECT_LT((foldedAt(paper, v2(0, 0)) - p3(0.6, 0)).norm(), 1e-12);
  EXPECT_LT((foldedAt(paper, v2(0, 0.3)) - p3(0.3, 0)).norm(), 1e-12);  // the back layer's edge point joins the front's
  EXPECT_EQ(reversed->moved_faces.size(), 2u);                           // the tip, both layers
  int mountains = 0, valleys = 0;
  const int joint = paper.vertexAt(v2(0.3, 0.3));
  for (const Edge& e : paper.edges)
    if (e.isCrease() && (e.vertices[0] == joint || e.vertices[1] == joint))
      (e.fold_angle < 0 ? mountains : valleys) += 1;
  EXPECT_EQ(mountains, 1);
  EXPECT_EQ(valleys, 3);
  const std::vector<int> levels = stackLevels(paper);
  const int body_low = std::min(levels[faceContaining(paper, v2(0.8, 0.1))], levels[faceContaining(paper, v2(0.1, 0.8))]);
  const int body_high = std::max(levels[faceContaining(paper, v2(0.8, 0.1))], levels[faceContaining(paper, v2(0.1, 0.8))]);
  for (const Vec2& tip : { v2(0.2, 0.1), v2(0.1, 0.2) })
  {
    EXPECT_GT(levels[faceContaining(paper, tip)], body_low);
    EXPECT_LT(levels[faceContaining(paper, tip)], body_high);
  }
  // Between x = .3 and .6 the tip adds its two layers to the body's two.
  EXPECT_EQ(layerCount(paper, p3(0.5, 0.05)), 4);
  EXPECT_EQ(layerCount(paper, p3(0.8, 0.1)), 2);
}

// Paper cannot pass through paper: the sheet folded in half (the right half on top, face down)
// and creased through both layers at a quarter; a quarter of the bottom layer turned a right
// angle up would go through the top layer's quarter lying on it, and one of the top layer
// turned down through the bottom's. Each the other way is a fold.
TEST(FlatFold, ALayerTurnedThroughTheLayerOnItIsRefusedAndTheOtherWayFolds)
{
  Paper paper = Paper::square(1.0);
  creaseLine(paper, p3(0.5, 0), p3(0.5, 1));
  RotateRequest half;
  half.click = p3(0.75, 0.5);
  half.angle = M_PI;  // valley: the right half over onto the left, face down
  ASSERT_TRUE(rotate(paper, half).ok());
  creaseLine(paper, p3(0.25, -0.1), p3(0.25, 1.1));
  ASSERT_EQ(layerCount(paper, p3(0.1, 0.5)), 2);
  const Paper before = paper;

  // The bottom layer's quarter (the crease pattern's [0, 0.25]) up, a valley, through the top.
  Paper up = paper;
  const Expected<FlatFoldResult> through = flatFold(up, { { { v2(0.25, 0), v2(0.25, 1), M_PI / 2 } }, v2(0.4, 0.5) });
  ASSERT_FALSE(through.ok());
  EXPECT_NE(through.message().find("paper cannot go through paper"), std::string::npos) << through.message();
  EXPECT_TRUE(up == before);
  // Down, a mountain: away from the top layer.
  Paper down = paper;
  const Expected<FlatFoldResult> away = flatFold(down, { { { v2(0.25, 0), v2(0.25, 1), -M_PI / 2 } }, v2(0.4, 0.5) });
  ASSERT_TRUE(away.ok()) << away.message();
  EXPECT_LT(foldedAt(down, v2(0, 0)).z(), -0.2);

  // The top layer's quarter (the crease pattern's [0.75, 1], face down): a valley turns it
  // towards its front, down through the bottom layer; a mountain up, away from it.
  Paper top_down = paper;
  ASSERT_FALSE(flatFold(top_down, { { { v2(0.75, 0), v2(0.75, 1), M_PI / 2 } }, v2(0.6, 0.5) }).ok());
  EXPECT_TRUE(top_down == before);
  Paper top_up = paper;
  const Expected<FlatFoldResult> lifted =
      flatFold(top_up, { { { v2(0.75, 0), v2(0.75, 1), -M_PI / 2 } }, v2(0.6, 0.5) });
  ASSERT_TRUE(lifted.ok()) << lifted.message();
  EXPECT_GT(foldedAt(top_up, v2(1, 0)).z(), 0.2);
}

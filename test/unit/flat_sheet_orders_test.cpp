// Paper continues across a crease left unfolded (flat_sheet_orders.h): a layer order in which
// such a sheet changes sides of another layer is named a clash, and a flat fold picks an order
// without one (flat_fold.h). On the crane and the flapping bird (their reference scripts), the
// two wings' layers lie wholly on their own sides of each other, and a wing turned towards the
// body is refused.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "model_reference.h"
#include "test_models.h"
#include "virtual_origami/core/face_orders.h"
#include "virtual_origami/core/flat_fold.h"
#include "virtual_origami/core/flat_sheet_orders.h"
#include "virtual_origami/core/layer_pick.h"
#include "virtual_origami/core/layers.h"

using namespace virtual_origami::core;
using namespace virtual_origami::core::test;

namespace
{
constexpr double kTolerance = 1e-7;

/// Whether any clash's message holds `text`.
bool clashSays(const std::vector<SheetOrderClash>& clashes, const std::string& text)
{
  for (const SheetOrderClash& clash : clashes)
    if (clash.message.find(text) != std::string::npos)
      return true;
  return false;
}

/// Where `other` lies from `face` along +z by the recorded order: +1 above, −1 below.
int aboveAlongZ(const Paper& paper, int face, int other)
{
  return faceOrder(paper, face, other) * (paper.faceNormal(face).z() > 0 ? 1 : -1);
}

/// Records `other` above (+1) or below (−1) `face` along +z.
void putAlongZ(Paper& paper, int face, int other, int above)
{
  setFaceOrder(paper, face, other, above * (paper.faceNormal(face).z() > 0 ? 1 : -1));
}
}  // namespace

// The sheet folded in half, the right half over the left, with the left half creased across at
// y = 0.5 (left flat) under it: the right half, one face, lies over both faces of that crease.
// Below one and above the other, it would go through the sheet along the crease.
TEST(FlatSheetOrders, ALayerAnUnfoldedCreaseRunsThroughLiesOnOneSideOfBothItsFaces)
{
  Paper paper = Paper::square(1.0);
  creaseLine(paper, p3(0.5, -0.1), p3(0.5, 1.1));
  creaseLine(paper, p3(-0.1, 0.5), p3(0.5, 0.5));
  ASSERT_TRUE(flatFold(paper, { { { v2(0.5, 0), v2(0.5, 1), M_PI } }, v2(0.25, 0.25) }).ok());
  const int lower = faceContaining(paper, v2(0.25, 0.25)), upper = faceContaining(paper, v2(0.25, 0.75));
  const int half = faceContaining(paper, v2(0.75, 0.5));
  ASSERT_EQ(faceContaining(paper, v2(0.75, 0.25)), half);  // one face, the crease does not reach it
  EXPECT_TRUE(sheetOrderClashes(paper, kTolerance).empty());
  EXPECT_EQ(aboveAlongZ(paper, lower, half), 1);
  EXPECT_EQ(aboveAlongZ(paper, upper, half), 1);

  putAlongZ(paper, upper, half, -1);
  const std::vector<SheetOrderClash> clashes = sheetOrderClashes(paper, kTolerance);
  ASSERT_EQ(clashes.size(), 1u);
  // The faces by where they lie on the sheet (their centroids: the right half's is its middle,
  // though it has five corners, the crease's end on its side among them).
  EXPECT_TRUE(clashSays(clashes, "face " + std::to_string(half) + " (about (0.75, 0.5) on the sheet)"))
      << clashes[0].message;
  EXPECT_TRUE(clashSays(clashes, "face " + std::to_string(lower) + " (about (0.25, 0.25) on the sheet)"));
  EXPECT_TRUE(clashSays(clashes, "one flat sheet across crease"));
  EXPECT_TRUE(clashSays(clashes, "(0, 0.5)–(0.5, 0.5)"));
  EXPECT_TRUE(clashSays(clashes, "it lies above one of the two faces and below the other"));
}

// Creased across at y = 0.5 through both halves, the sheet folded in half: two sheets, each flat
// across its half of the crease, lie on each other along one folded line. The right one above on
// one side of the line and below on the other would go through the left one.
TEST(FlatSheetOrders, TwoSheetsFlatAcrossOneLineKeepOneOrderOnBothSides)
{
  Paper paper = Paper::square(1.0);
  creaseLine(paper, p3(0.5, -0.1), p3(0.5, 1.1));
  creaseLine(paper, p3(-0.1, 0.5), p3(1.1, 0.5));
  ASSERT_TRUE(
      flatFold(paper, { { { v2(0.5, 0), v2(0.5, 0.5), M_PI }, { v2(0.5, 0.5), v2(0.5, 1), M_PI } }, v2(0.25, 0.25) })
          .ok());
  const int left_low = faceContaining(paper, v2(0.25, 0.25)), left_high = faceContaining(paper, v2(0.25, 0.75));
  const int right_low = faceContaining(paper, v2(0.75, 0.25)), right_high = faceContaining(paper, v2(0.75, 0.75));
  EXPECT_TRUE(sheetOrderClashes(paper, kTolerance).empty());

  putAlongZ(paper, left_high, right_high, -aboveAlongZ(paper, left_high, right_high));
  const std::vector<SheetOrderClash> clashes = sheetOrderClashes(paper, kTolerance);
  ASSERT_FALSE(clashes.empty());
  EXPECT_TRUE(clashSays(clashes, "pass through each other: one lies above the other on one side of the crease"));
  for (const int face : { left_low, left_high, right_low, right_high })
    EXPECT_TRUE(clashSays(clashes, "face " + std::to_string(face) + " ")) << face;
}

// Creased at x = 0.25, 0.5 and 0.75: the strip left of 0.25 folded over (valley) and the right
// half folded over it (valley), its crease at 0.75 left flat. That crease lands on the line of
// the fold at 0.25, so the right half's sheet, flat across it, cannot lie between the two faces
// of that fold: it lies over both. A flat fold picks that order; put between, it is a clash.
TEST(FlatSheetOrders, ASheetFlatAcrossTheLineOfAFoldDoesNotLieBetweenTheFoldsFaces)
{
  Paper paper = Paper::square(1.0);
  for (const double x : { 0.25, 0.5, 0.75 })
    creaseLine(paper, p3(x, -0.1), p3(x, 1.1));
  const Expected<FlatFoldResult> folded =
      flatFold(paper, { { { v2(0.25, 0), v2(0.25, 1), M_PI }, { v2(0.5, 0), v2(0.5, 1), M_PI } }, v2(0.4, 0.5) });
  ASSERT_TRUE(folded.ok()) << folded.message();
  const int base = faceContaining(paper, v2(0.4, 0.5)), strip = faceContaining(paper, v2(0.1, 0.5));
  const int sheet = faceContaining(paper, v2(0.6, 0.5));
  ASSERT_TRUE(facesStacked(paper, base, strip, kTolerance));
  ASSERT_TRUE(facesStacked(paper, strip, sheet, kTolerance));
  EXPECT_TRUE(sheetOrderClashes(paper, kTolerance).empty());
  EXPECT_EQ(aboveAlongZ(paper, base, strip), 1);
  EXPECT_EQ(aboveAlongZ(paper, strip, sheet), 1) << "the right half lies over the folded strip";

  putAlongZ(paper, strip, sheet, -1);  // between the strip and the face it is folded on
  const std::vector<SheetOrderClash> clashes = sheetOrderClashes(paper, kTolerance);
  ASSERT_FALSE(clashes.empty());
  EXPECT_TRUE(clashSays(clashes, "face " + std::to_string(sheet) + " (about (0.62, 0.5) on the sheet), in "))
      << clashes[0].message;
  EXPECT_TRUE(clashSays(clashes, "folded on each other at crease"));
  EXPECT_TRUE(clashSays(clashes, "it would go through that fold"));
}

// Issue 39: the crane's and the flapping bird's wings. Before them (step 19), at the wing tips,
// every layer of the wing of corner (0, 0) lies above every layer of the wing of corner (1, 1),
// on both sides of the wings' middle (the diagonal, left flat): each wing's layers turn together.
// No state on the way has a sheet that changes sides across an unfolded crease. The front wing
// turned towards the body, through the layers under it, is refused; away from it, it folds.
TEST(FlatSheetOrders, TheWingsOfTheCraneAndTheFlappingBirdLieEachWhollyOnItsOwnSide)
{
  for (const std::string file : { "crane_reference.json", "flapping_bird_reference.json" })
  {
    SCOPED_TRACE(file);
    const Expected<FoldSequence> script = modelReference(file);
    ASSERT_TRUE(script.ok()) << script.message();
    const Expected<std::vector<Paper>> states = modelStates(*script);
    ASSERT_TRUE(states.ok()) << states.message();
    for (size_t i = 0; i < states->size(); ++i)
      EXPECT_TRUE(sheetOrderClashes((*states)[i], kTolerance).empty()) << "after step " << i;

    const Paper& before = (*states)[19];
    for (const Vec2& cp : { v2(0.1, 0.12), v2(0.12, 0.1), v2(0.05, 0.2), v2(0.2, 0.05) })
    {
      const int face = faceContaining(before, cp);
      ASSERT_GE(face, 0);
      Vec3 at = Vec3::Zero();
      for (int v : before.faces[face].vertices)
        at += before.vertices[v].folded;
      at /= static_cast<double>(before.faces[face].vertices.size());
      const std::vector<int> stack = facesUnder(before, at + Vec3(0, 0, 1), Vec3(0, 0, -1));
      bool back_wing_seen = false;
      int front = 0, back = 0;
      for (const int g : stack)
      {
        Vec2 centroid = Vec2::Zero();
        for (int v : before.faces[g].vertices)
          centroid += before.vertices[v].crease_pattern;
        centroid /= static_cast<double>(before.faces[g].vertices.size());
        // The wings' faces lie within 0.4 of their corners on the sheet; others (the tail's, the
        // neck's) do not count.
        const bool front_wing = centroid.norm() < 0.4, back_wing = (centroid - v2(1, 1)).norm() < 0.4;
        if (!front_wing && !back_wing)
          continue;
        if (front_wing)
        {
          ++front;
          EXPECT_FALSE(back_wing_seen) << "face " << g << " of the front wing lies under the back wing's";
        }
        else
        {
          ++back;
          back_wing_seen = true;
        }
      }
      EXPECT_GE(front, 2);
      EXPECT_GE(back, 2);
    }

    // The front wing's hinge turned the other way: towards the body, through the layers under it.
    const FlatFoldRequest& wing = script->steps[19].operation.flat_fold;
    FlatFoldRequest inwards = wing;
    for (CreaseLineAngle& line : inwards.creases)
      line.angle = -line.angle;
    Paper through = before;
    const Expected<FlatFoldResult> refused = flatFold(through, inwards);
    ASSERT_FALSE(refused.ok());
    EXPECT_NE(refused.message().find("paper cannot go through paper"), std::string::npos) << refused.message();
    EXPECT_TRUE(through == before);
    Paper away = before;
    EXPECT_TRUE(flatFold(away, wing).ok());
  }
}

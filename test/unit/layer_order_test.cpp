// The layer order of flat-folded states: solved from the creases and the rules no paper breaks,
// recorded by every flat fold, checked against rotations' orders and the single-vertex theory.
#include <gtest/gtest.h>

#include <cmath>

#include "single_vertex.h"
#include "test_models.h"
#include "virtual_origami/core/face_orders.h"
#include "virtual_origami/core/flat_fold.h"
#include "virtual_origami/core/flat_vertices.h"
#include "virtual_origami/core/kinematics.h"
#include "virtual_origami/core/layer_order.h"
#include "virtual_origami/core/tessellations.h"

using namespace virtual_origami::core;
using namespace virtual_origami::core::test;

namespace
{
/// `paper` folded to `angles` by kinematics from face 0 (no check of the vertices), or nothing
/// when the fold does not close.
std::optional<Paper> foldedTo(const Paper& paper, const std::vector<double>& angles)
{
  const Expected<std::vector<Vec3>> placed = foldedPositionsFromAngles(paper, angles, 0, facePose(paper, 0), 1e-9);
  if (!placed)
    return std::nullopt;
  Paper folded = paper;
  for (size_t v = 0; v < folded.vertices.size(); ++v)
    folded.vertices[v].folded = (*placed)[v];
  for (size_t e = 0; e < folded.edges.size(); ++e)
    folded.edges[e].fold_angle = angles[e];
  return folded;
}

/// Every pair of stacked faces has an order and the orders obey the rules.
void expectCompleteOrder(const Paper& paper)
{
  EXPECT_EQ(layerOrderViolation(paper, paper.face_orders), "");
}
}  // namespace

// Two independent judges of a single vertex agree on every assignment: the local theorems
// (Maekawa, Kawasaki, big-little-big) and the search for a stacking of the folded faces.
TEST(LayerOrder, AStackingExistsExactlyWhenTheVertexTheoremsHold)
{
  for (const std::vector<double>& degrees :
       { std::vector<double>{ 0, 70, 180, 290 }, std::vector<double>{ 0, 45, 90, 135, 180, 225, 270, 315 },
         std::vector<double>{ 0, 40, 90, 150, 220, 300 } })
  {
    const Paper paper = singleVertex(degrees);
    const int degree = static_cast<int>(degrees.size());
    int stacked = 0;
    for (int mask = 0; mask < (1 << degree); ++mask)
    {
      std::vector<int> signs;
      for (int i = 0; i < degree; ++i)
        signs.push_back((mask >> i) & 1 ? 1 : -1);
      const std::vector<double> angles = spokeAngles(paper, signs);
      const std::optional<Paper> folded = foldedTo(paper, angles);
      ASSERT_TRUE(folded) << "a Kawasaki vertex closes whatever its signs";
      const bool theorems = checkFlatVertices(paper, angles).ok();
      const Expected<LayerOrder> order = solveLayerOrder(*folded);
      EXPECT_EQ(order.ok(), theorems) << degree << " creases, mask " << mask << ": "
                                      << (order ? std::string("an order found") : order.message());
      if (order)
      {
        ASSERT_TRUE(order->complete);
        Paper ordered = *folded;
        ordered.face_orders = order->orders;
        expectCompleteOrder(ordered);
        ++stacked;
      }
    }
    EXPECT_GT(stacked, 0);
  }
}

// A flat fold records the order a rotation by the same half turn records: the flap on the side
// its valley or mountain says.
TEST(LayerOrder, AFlatFoldInHalfRecordsTheOrderOfTheSameHalfTurn)
{
  for (const double angle : { M_PI, -M_PI })
  {
    Paper paper = Paper::square(1.0);
    creaseLine(paper, p3(0.5, -0.1), p3(0.5, 1.1));
    Paper turned = paper;
    RotateRequest request;
    request.click = p3(0.8, 0.5);
    request.angle = angle;
    ASSERT_TRUE(rotate(turned, request).ok());
    ASSERT_EQ(turned.face_orders.size(), 1u);

    ASSERT_TRUE(flatFold(paper, { { { v2(0.5, 0), v2(0.5, 1), angle } }, v2(0.2, 0.5) }).ok());
    ASSERT_EQ(paper.face_orders.size(), 1u);
    const int fixed = faceContaining(paper, v2(0.2, 0.5)), flap = faceContaining(paper, v2(0.8, 0.5));
    EXPECT_EQ(faceOrder(paper, fixed, flap), angle > 0 ? 1 : -1);
    EXPECT_EQ(faceOrder(paper, fixed, flap), faceOrder(turned, fixed, flap));
  }
}

// Half turns (rotate) record orders; those orders obey the rules, and the search that keeps
// them finds an order for every stacked pair.
TEST(LayerOrder, TheOrdersOfAStackFoldedByTurnsObeyTheRules)
{
  const Paper paper = stackOfLayers(3);
  expectCompleteOrder(paper);
  LayerOrderOptions options;
  options.kept = paper.face_orders;
  const Expected<LayerOrder> order = solveLayerOrder(paper, options);
  ASSERT_TRUE(order.ok()) << order.message();
  EXPECT_EQ(order->stacked_pairs, 28);  // 8 layers, every two on each other
  Paper solved = paper;
  solved.face_orders = order->orders;
  for (const FaceOrder& o : paper.face_orders)
    EXPECT_EQ(faceOrder(solved, o.face, o.other), o.above);
}

// The creased square's eight creases folded flat at once (five valleys, three mountains) put its
// eight triangles on one (each crease reflects the next 45° sector onto the last): the order of
// the eight layers is recorded. Every crease valley is refused (Maekawa), the paper untouched.
TEST(LayerOrder, EightCreasesFoldedFlatAtOnceRecordEightLayersAndAllValleysAreRefused)
{
  Paper paper = creasedSquare();
  const Vec2 centre(0.5, 0.5);
  const std::vector<Vec2> ends = { v2(1, 0.5), v2(1, 1), v2(0.5, 1), v2(0, 1),
                                   v2(0, 0.5), v2(0, 0), v2(0.5, 0), v2(1, 0) };
  FlatFoldRequest all_valley;
  all_valley.fixed_point = v2(0.9, 0.6);
  for (const Vec2& end : ends)
    all_valley.creases.push_back({ centre, end, M_PI });
  const Paper before = paper;
  const Expected<FlatFoldResult> refused = flatFold(paper, all_valley);
  ASSERT_FALSE(refused.ok());
  EXPECT_NE(refused.message().find("Maekawa"), std::string::npos) << refused.message();
  EXPECT_TRUE(paper == before);

  FlatFoldRequest square_base = all_valley;
  for (size_t i = 0; i < ends.size(); i += 2)  // the midline halves mountain but one, the diagonals valley
    square_base.creases[i].angle = i == 0 ? M_PI : -M_PI;
  const Expected<FlatFoldResult> folded = flatFold(paper, square_base);
  ASSERT_TRUE(folded.ok()) << folded.message();
  expectValid(paper);
  EXPECT_EQ(paper.face_orders.size(), 28u);  // eight layers over one triangle, every two stacked
  expectCompleteOrder(paper);
}

// Re-marking a folded crease the other way swings its flap round to the other side: the faces'
// places are the same, the layer order is not, and the fold is not refused as moving nothing.
TEST(LayerOrder, ReMarkingAFoldedCreaseTurnsItsFlapToTheOtherSide)
{
  Paper paper = Paper::square(1.0);
  creaseLine(paper, p3(0.5, -0.1), p3(0.5, 1.1));
  ASSERT_TRUE(flatFold(paper, { { { v2(0.5, 0), v2(0.5, 1), M_PI } }, v2(0.2, 0.5) }).ok());
  const int fixed = faceContaining(paper, v2(0.2, 0.5)), flap = faceContaining(paper, v2(0.8, 0.5));
  ASSERT_EQ(faceOrder(paper, fixed, flap), 1);
  const Paper valley = paper;
  const Expected<FlatFoldResult> remarked = flatFold(paper, { { { v2(0.5, 0), v2(0.5, 1), -M_PI } }, v2(0.2, 0.5) });
  ASSERT_TRUE(remarked.ok()) << remarked.message();
  EXPECT_EQ(remarked->moved_faces, std::vector<int>{ flap });
  EXPECT_EQ(faceOrder(paper, fixed, flap), -1);
  for (size_t v = 0; v < paper.vertices.size(); ++v)
    EXPECT_LT((paper.vertices[v].folded - valley.vertices[v].folded).norm(), 1e-12);
  EXPECT_LT(paper.edges[paper.findEdge(paper.vertexAt(v2(0.5, 0)), paper.vertexAt(v2(0.5, 1)))].fold_angle, 0);
}

// Two flaps folded in from either side overlap over the middle, and a crease across the sheet is
// left unfolded: each flap is one flat sheet across it, so the flap on top on one side of it is on
// top on the other (tortilla–tortilla, LayerOrderOptions::unfolded_sheets). Either flap may be the
// top one; an order kept for one side decides the other, one kept each way is refused naming the
// faces and where they are on the sheet, and a recorded order that flips across the crease breaks
// the layer checks.
TEST(LayerOrder, FlapsFlatAcrossAnUnfoldedCreaseKeepOneOrderOnBothSidesOfIt)
{
  Paper paper = Paper::square(1.0);
  creaseLine(paper, p3(0.3, -0.1), p3(0.3, 1.1));
  creaseLine(paper, p3(0.7, -0.1), p3(0.7, 1.1));
  creaseLine(paper, p3(-0.1, 0.5), p3(1.1, 0.5));
  // The flaps x < 0.3 and x > 0.7 folded over: x in [0.3, 0.6] and [0.4, 0.7], overlapping on [0.4, 0.6].
  const Expected<FlatFoldResult> folded =
      flatFold(paper, { { { v2(0.3, 0), v2(0.3, 1), M_PI }, { v2(0.7, 0), v2(0.7, 1), M_PI } }, v2(0.5, 0.25) });
  ASSERT_TRUE(folded.ok()) << folded.message();
  const int left_top = faceContaining(paper, v2(0.1, 0.75)), left_bottom = faceContaining(paper, v2(0.1, 0.25));
  const int right_top = faceContaining(paper, v2(0.9, 0.75)), right_bottom = faceContaining(paper, v2(0.9, 0.25));
  LayerOrderOptions free;
  free.unfolded_sheets = true;
  const Expected<LayerOrder> some = solveLayerOrder(paper, free);
  ASSERT_TRUE(some.ok()) << some.message();
  paper.face_orders = some->orders;
  ASSERT_NE(faceOrder(paper, left_top, right_top), 0);
  EXPECT_EQ(faceOrder(paper, left_bottom, right_bottom), faceOrder(paper, left_top, right_top));
  EXPECT_EQ(layerOrderViolation(paper, paper.face_orders, 1e-7, true), "");

  for (const int above : { 1, -1 })
  {
    LayerOrderOptions options;
    options.unfolded_sheets = true;
    options.kept = { { left_top, right_top, above } };
    const Expected<LayerOrder> order = solveLayerOrder(paper, options);
    ASSERT_TRUE(order.ok()) << order.message();
    Paper ordered = paper;
    ordered.face_orders = order->orders;
    EXPECT_EQ(faceOrder(ordered, left_bottom, right_bottom), above);
    EXPECT_EQ(faceOrder(ordered, left_top, right_top), above);
  }

  LayerOrderOptions crossed;
  crossed.unfolded_sheets = true;
  crossed.kept = { { left_top, right_top, 1 }, { left_bottom, right_bottom, -1 } };
  const Expected<LayerOrder> refused = solveLayerOrder(paper, crossed);
  ASSERT_FALSE(refused.ok());
  EXPECT_NE(refused.message().find("one flat sheet across crease"), std::string::npos) << refused.message();
  EXPECT_NE(refused.message().find("face " + std::to_string(left_top) + " (about (0.15, 0.75) on the sheet)"),
            std::string::npos)
      << refused.message();

  Paper flipped = paper;
  setFaceOrder(flipped, left_bottom, right_bottom, -faceOrder(paper, left_bottom, right_bottom));
  const std::string violation = layerOrderViolation(flipped, flipped.face_orders, 1e-7, true);
  EXPECT_NE(violation.find("would pass through each other"), std::string::npos) << violation;
  EXPECT_NE(violation.find("(0.85, 0.25) on the sheet"), std::string::npos) << violation;
}

// A flap that is one face lies over a sheet split by an unfolded crease the flap crosses: it lies
// above both halves or below both, never between.
TEST(LayerOrder, AFaceAcrossAnUnfoldedCreaseOfAnotherSheetLiesOnOneSideOfBothItsHalves)
{
  Paper paper = Paper::square(1.0);
  creaseLine(paper, p3(0.3, -0.1), p3(0.3, 1.1));
  creaseLine(paper, p3(0.7, -0.1), p3(0.7, 1.1));
  creaseLine(paper, p3(-0.1, 0.5), p3(0.7, 0.5));  // ends on x = 0.7: the right flap is one face
  ASSERT_TRUE(
      flatFold(paper, { { { v2(0.3, 0), v2(0.3, 1), M_PI }, { v2(0.7, 0), v2(0.7, 1), M_PI } }, v2(0.5, 0.25) }).ok());
  const int left_top = faceContaining(paper, v2(0.1, 0.75)), left_bottom = faceContaining(paper, v2(0.1, 0.25));
  const int right = faceContaining(paper, v2(0.9, 0.5));
  for (const int above : { 1, -1 })
  {
    LayerOrderOptions options;
    options.unfolded_sheets = true;
    options.kept = { { left_top, right, above } };
    const Expected<LayerOrder> order = solveLayerOrder(paper, options);
    ASSERT_TRUE(order.ok()) << order.message();
    Paper ordered = paper;
    ordered.face_orders = order->orders;
    EXPECT_EQ(faceOrder(ordered, left_bottom, right), above);
  }
  LayerOrderOptions between;
  between.unfolded_sheets = true;
  between.kept = { { left_top, right, 1 }, { left_bottom, right, -1 } };
  const Expected<LayerOrder> refused = solveLayerOrder(paper, between);
  ASSERT_FALSE(refused.ok());
  EXPECT_NE(
      refused.message().find("face " + std::to_string(right) + " (about (0.85, 0.5) on the sheet) would pass through"),
      std::string::npos)
      << refused.message();
}

// Stacks are looked for on papers of any size, and a stack too large to order is answered at
// once: a Miura-ori of 4,900 faces part folded has no stack at all (it was answered "a paper of
// 4900 faces is more than the 4000 whose stacks are looked for", so a fold by assignment of it
// said its flat layers were left unordered), and folded flat it lies in one stack of millions of
// pairs, said to be more than the bound.
TEST(LayerOrder, AnySizeOfPaperIsSearchedForStacksAndOneTooLargeIsSaidSo)
{
  LayerOrderOptions options;
  options.max_faces = 1000;
  options.max_pairs = 20000;
  options.unfolded_sheets = true;

  const Expected<Tessellation> part = miuraTessellationFolded(70, 70, 1.0, 1.0, 70.0 * M_PI / 180.0, 1.0);
  ASSERT_TRUE(part) << part.message();
  ASSERT_EQ(part->paper.faces.size(), 4900u);
  options.tolerance = 1e-5 * part->paper.scale();
  const Expected<LayerOrder> none = solveLayerOrder(part->paper, options);
  ASSERT_TRUE(none) << none.message();
  EXPECT_TRUE(none->complete) << none->incomplete;
  EXPECT_EQ(none->stacked_pairs, 0);

  const Expected<Tessellation> pattern = miuraTessellation(70, 70, 1.0, 1.0, 70.0 * M_PI / 180.0);
  ASSERT_TRUE(pattern) << pattern.message();
  const std::optional<Paper> flat = foldedTo(pattern->paper, pattern->target_fold_angle);
  ASSERT_TRUE(flat);
  const Expected<LayerOrder> too_large = solveLayerOrder(*flat, options);
  ASSERT_TRUE(too_large) << too_large.message();
  EXPECT_FALSE(too_large->complete);
  EXPECT_TRUE(too_large->orders.empty());
  EXPECT_NE(too_large->incomplete.find("more than the 20000 overlapping pairs of faces"), std::string::npos)
      << too_large->incomplete;
}

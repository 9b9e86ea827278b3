// The traditional frog base (test/data/frog_base_reference.json): the square base, the squash lines
// creased through all layers, and each of the four flaps squashed by one drag (compound_fold.h) —
// the first on its outer layer, the others on their inner layer, one of them under another
// flap's layers — then the petal folds' creases through all layers and each squashed flap petal
// folded by one drag, against the script to 1e-6; no state's sheets passing through each other
// (flat_sheet_orders.h); the kite of the squashes and the frog base against their closed forms;
// docs/INTERACTION.md's walkthrough ("## Fold a frog base") against the script.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "model_reference.h"
#include "reference_fold_checks.h"
#include "virtual_origami/core/chosen_creases.h"
#include "virtual_origami/core/flat_sheet_orders.h"
#include "virtual_origami/core/layer_order.h"
#include "virtual_origami/core/layer_pick.h"
#include "walkthrough_checks.h"

using namespace virtual_origami;
using namespace virtual_origami::core;
using namespace virtual_origami::core::test;

namespace
{
const FoldSequence& script()
{
  static const Expected<FoldSequence> sequence = modelReference("frog_base_reference.json");
  EXPECT_TRUE(sequence.ok()) << sequence.message();
  return *sequence;
}

const std::vector<Paper>& frog()
{
  static const Expected<std::vector<Paper>> states = modelStates(script());
  EXPECT_TRUE(states.ok()) << states.message();
  return *states;
}

/// Where the flap at `cp` lies in the stack before step `step`, seen from above (1: on top; the
/// number of layers there: at the bottom).
std::pair<int, int> layerOf(int step, const Vec2& cp)
{
  const Paper& before = frog()[step - 1];
  const int face = faceContaining(before, cp);
  const std::vector<int> under = facesUnder(before, facePose(before, face) * Vec3(cp.x(), cp.y(), 0), Vec3(0, 0, -1));
  const auto it = std::find(under.begin(), under.end(), face);
  return { it == under.end() ? -1 : static_cast<int>(it - under.begin()) + 1, static_cast<int>(under.size()) };
}

const double kTan = std::tan(M_PI / 8);  // the squash lines halve the 45° at the closed point
constexpr int kSquashed = 14;            // the steps up to the fourth squash fold

/// `cp` turned a quarter turn about the centre of the sheet `turns` times (the four flaps alike).
Vec2 quarterTurned(Vec2 cp, int turns)
{
  for (int k = 0; k < turns; ++k)
    cp = Vec2(1 - cp.y(), cp.x());
  return cp;
}

/// Every crease of `paper` flat (0 or ±180°).
void expectFlat(const Paper& paper)
{
  for (const Edge& e : paper.edges)
  {
    if (e.isCrease())
    {
      EXPECT_TRUE(std::abs(e.fold_angle) < 1e-9 || std::abs(std::abs(e.fold_angle) - M_PI) < 1e-9) << e.fold_angle;
    }
  }
}

/// Every vertex of `paper` within the kite from `c` to `b` whose side points lie `side_along`
/// along and `side_across` across: no layer sticks out.
void expectWithinTheKite(const Paper& paper, const Vec3& c, const Vec3& b, double side_along, double side_across)
{
  const Vec3 axis = (b - c).normalized();
  const double length = (b - c).norm();
  for (const Vertex& v : paper.vertices)
  {
    const Vec3 d = v.folded - c;
    const double along = d.dot(axis), across = (d - along * axis).norm();
    EXPECT_GE(along, -1e-9);
    EXPECT_LE(along, length + 1e-9);
    // The kite's half width at `along`: widening from C to the side points, narrowing to B.
    const double half_width =
        along <= side_along ? side_across * along / side_along : side_across * (length - along) / (length - side_along);
    EXPECT_LE(across, half_width + 1e-9) << v.crease_pattern.transpose();
  }
}
}  // namespace

TEST(FrogBase, DraggingEachFlapOpenAcrossTheCentreLineSquashesIt)
{
  // The front left flap, on top.
  EXPECT_EQ(layerOf(11, Vec2(0.4, 0.1)).first, 1);
  expectTheScriptsFold(script(), frog(), 11, Vec2(0.4, 0.1), CompoundKind::Squash);
  // The back left flap: its inner layer, on top where the first squash uncovered it.
  EXPECT_EQ(layerOf(12, Vec2(0.9, 0.4)).first, 1);
  expectTheScriptsFold(script(), frog(), 12, Vec2(0.9, 0.4), CompoundKind::Squash);
  // The front right flap: its inner layer (the outer one is held at the centre line by the first
  // squash), picked one layer down.
  EXPECT_EQ(layerOf(13, Vec2(0.1, 0.6)).first, 2);
  expectTheScriptsFold(script(), frog(), 13, Vec2(0.1, 0.6), CompoundKind::Squash);
  // The back right flap: its inner layer, on top where the third squash uncovered it.
  EXPECT_EQ(layerOf(14, Vec2(0.4, 0.9)).first, 1);
  expectTheScriptsFold(script(), frog(), 14, Vec2(0.4, 0.9), CompoundKind::Squash);
}

TEST(FrogBase, TheFourSquashesLayTheFlapsOnTheKiteAboutTheCentreLine)
{
  const Paper& base = frog()[kSquashed];
  expectFlat(base);
  // The closed point C, the four corners at the open point B half a diagonal away; every
  // flap's folded edge (the midlines' ends) on the centre line CB half a side from C; the
  // squash lines' ends at the kite's side points, tan(22.5°) / 2 from the corners.
  const Vec3 c = foldedAt(base, Vec2(0.5, 0.5)), b = foldedAt(base, Vec2(0, 0));
  for (const Vec2& corner : { Vec2(1, 0), Vec2(1, 1), Vec2(0, 1) })
    EXPECT_LE((foldedAt(base, corner) - b).norm(), 1e-9);
  EXPECT_NEAR((b - c).norm(), std::sqrt(0.5), 1e-9);
  const Vec3 axis = (b - c).normalized();
  for (const Vec2& end : { Vec2(0.5, 0), Vec2(1, 0.5), Vec2(0.5, 1), Vec2(0, 0.5) })
    EXPECT_LE((foldedAt(base, end) - (c + 0.5 * axis)).norm(), 1e-9) << end.transpose();
  std::vector<Vec3> sides;
  for (const Vec2& end :
       { Vec2(0.5 - 0.5 * kTan, 0), Vec2(0.5 + 0.5 * kTan, 0), Vec2(1, 0.5 - 0.5 * kTan), Vec2(1, 0.5 + 0.5 * kTan),
         Vec2(0.5 + 0.5 * kTan, 1), Vec2(0.5 - 0.5 * kTan, 1), Vec2(0, 0.5 + 0.5 * kTan), Vec2(0, 0.5 - 0.5 * kTan) })
  {
    const Vec3 p = foldedAt(base, end);
    EXPECT_NEAR((p - b).norm(), 0.5 - 0.5 * kTan, 1e-9) << end.transpose();
    EXPECT_NEAR((p - c).norm(), 0.5 / std::cos(M_PI / 8), 1e-9) << end.transpose();
    sides.push_back(p);
  }
  // Two side points, one either side of the centre line, four of the squash lines' ends at each.
  const Vec3 normal = base.faceNormal(0);
  int left = 0;
  for (const Vec3& p : sides)
    left += axis.cross(p - c).dot(normal) > 0;
  EXPECT_EQ(left, 4);
  // Every vertex within the kite C, side, B, side: no layer sticks out.
  const double side_along = (sides[0] - c).dot(axis);
  expectWithinTheKite(base, c, b, side_along, ((sides[0] - c) - side_along * axis).norm());
}

TEST(FrogBase, LiftingEachSquashedFlapsRawEdgeUpOverTheLineThroughItsSidePointsPetalFoldsIt)
{
  // Pressed on the squashed flap's top layer below the line through its side points, beside the
  // centre line, and dragged up to where the fold puts that point; the flaps alike a quarter turn
  // apart on the sheet (the front left flap, then the back left, front right and back right
  // ones, each pressed on its own layer). The back right flap's kite lies on top and wraps the
  // others' layers on one side of the centre line: its petal fold comes last.
  const std::pair<int, Vec2> petals[] = { { 20, Vec2(0.47, 0.06) },
                                          { 21, quarterTurned(Vec2(0.47, 0.06), 1) },
                                          { 22, quarterTurned(Vec2(0.53, 0.06), 3) },
                                          { 23, quarterTurned(Vec2(0.47, 0.06), 2) } };
  for (const auto& [step, cp] : petals)
    expectTheScriptsFold(script(), frog(), step, cp, CompoundKind::Petal);
  EXPECT_EQ(layerOf(23, petals[3].second).first, 1);
}

TEST(FrogBase, TheFourPetalFoldsMakeTheFrogBase)
{
  // The kite of the squashes, C the closed point, B the open one half a diagonal away; the
  // petal folds' hinge crosses it halfway from C to B, between the side points (where the
  // lower edges' creases, halving the 45° at B, meet its edges).
  const Paper& base = frog().back();
  ASSERT_EQ(frog().size(), script().steps.size() + 1);
  expectFlat(base);
  const Vec3 c = foldedAt(base, Vec2(0.5, 0.5)), b = foldedAt(base, Vec2(0, 0));
  for (const Vec2& corner : { Vec2(1, 0), Vec2(1, 1), Vec2(0, 1) })
    EXPECT_LE((foldedAt(base, corner) - b).norm(), 1e-9) << "every corner at the open point";
  EXPECT_NEAR((b - c).norm(), std::sqrt(0.5), 1e-9);
  const Vec3 axis = (b - c).normalized();
  const double hinge = std::sqrt(0.5) / 2, side = hinge * kTan;
  for (int k = 0; k < 4; ++k)
  {
    SCOPED_TRACE("flap " + std::to_string(k));
    // Each flap's point, its raw edge's middle (half a side from C before), turned up over the
    // hinge onto the centre line: 2 * hinge - 1/2 = (sqrt(2) - 1) / 2 from C.
    EXPECT_LE((foldedAt(base, quarterTurned(Vec2(0.5, 0), k)) - (c + (2 * hinge - 0.5) * axis)).norm(), 1e-9);
    // The sides collapsed in: the squash lines' ends (the kite's side points before) on the
    // centre line, their distance from B (1/2 - tan(22.5°)/2) laid along it from B.
    for (const Vec2& end : { Vec2(0.5 - 0.5 * kTan, 0), Vec2(0.5 + 0.5 * kTan, 0) })
      EXPECT_LE((foldedAt(base, quarterTurned(end, k)) - (b - (0.5 - 0.5 * kTan) * axis)).norm(), 1e-9)
          << end.transpose();
    // The side points stay: on the hinge, tan(22.5°) of it either side of the centre line.
    for (const Vec2& q : { Vec2(hinge, 0.5 - hinge), Vec2(1 - hinge, 0.5 - hinge) })
    {
      const Vec3 d = foldedAt(base, quarterTurned(q, k)) - c;
      EXPECT_NEAR(d.dot(axis), hinge, 1e-9) << q.transpose();
      EXPECT_NEAR((d - d.dot(axis) * axis).norm(), side, 1e-9) << q.transpose();
    }
  }
  // Nothing sticks out of the kite; its widest, at the side points, is what the squashes made.
  expectWithinTheKite(base, c, b, 0.5, 0.5 * kTan);
}

TEST(FrogBase, EveryStepKeepsEachSheetOnOneSideOfEveryLayer)
{
  // flatFold refuses a fold whose layers pass through each other (flat_sheet_orders.h): every
  // state of the script, the creases through all layers' too, has none of those clashes, the
  // square base (step 8's midlines valleys, as step 7's) and the frog base included; and its
  // recorded orders obey layer_order.h's rules with faces joined by an unfolded crease held to be
  // one sheet (before, the squash folds 12-14 left two pairs of sheets in one order on one side of
  // the centre line and in the other order on the other).
  ASSERT_EQ(frog().size(), script().steps.size() + 1);
  for (size_t i = 1; i < frog().size(); ++i)
  {
    EXPECT_TRUE(sheetOrderClashes(frog()[i], 1e-7).empty()) << "after step " << i;
    EXPECT_EQ(layerOrderViolation(frog()[i], frog()[i].face_orders, 1e-7, true), "") << "after step " << i;
  }
}

TEST(FrogBase, TheWalkthroughNamesTheScriptsFoldsAndItsGesturesAddUp)
{
  const virtual_origami::test::Walkthrough walkthrough = virtual_origami::test::readWalkthrough("## Fold a frog base");
  virtual_origami::test::expectTheWalkthroughFoldsTheScript(walkthrough, script(), frog());
}

TEST(FrogBase, AFlapLetGoOnTheSideItWasPressedFromFoldsOverOnItsSquashLineInstead)
{
  // The front left flap pressed as for its squash, let go where folding the flap's edge over the
  // squash line puts the point (mirrored over that line only): no squash, a plain fold of the
  // flap's two layers on their squash lines, nothing else changed.
  const Paper& before = frog()[10];
  const Vec2 cp(0.4, 0.1);
  const int face = faceContaining(before, cp);
  ASSERT_GE(face, 0);
  const Vec3 press = facePose(before, face) * Vec3(cp.x(), cp.y(), 0);
  const Vec3 c = foldedAt(before, Vec2(0.5, 0.5)), p = foldedAt(before, Vec2(0.5 + 0.5 * kTan, 0));
  const Vec3 d = (p - c).normalized();
  const Vec3 foot = c + (press - c).dot(d) * d;
  Expected<CompoundFolds> folds = CompoundFolds::at(before, face, press);
  ASSERT_TRUE(folds.ok()) << folds.message();
  const auto chosen = folds->nearestResolved(2 * foot - press);
  ASSERT_TRUE(chosen.has_value());
  EXPECT_LT(chosen->first.miss, 1e-9);
  ASSERT_EQ(chosen->second.request.creases.size(), 2u);
  for (const CreaseLineAngle& line : chosen->second.request.creases)
  {
    EXPECT_NEAR(std::abs(line.angle), M_PI, 1e-12);
    const Vec2 away = (line.start - Vec2(0.5, 0.5)).norm() > 1e-9 ? line.start : line.end;
    EXPECT_NEAR(away.y(), 0.0, 1e-9) << "a squash line of the flap's layers";
    EXPECT_NEAR(std::abs(away.x() - 0.5), 0.5 * kTan, 1e-9);
  }
}

TEST(FrogBase, EachFoldAPressFindsAtTheClosedPointLandsThePressedPointWhereItsFoldPutsIt)
{
  // Where 16 creases meet, the press finds its folds by moving the parts of the paper each one's
  // creases part (compound_fold.cpp): each landing is where the flat fold of its creases takes
  // the pressed point, the face that stays bit for bit (the first 150 of them, which fold flat).
  const Paper& before = frog()[10];
  const Vec2 cp(0.4, 0.1);
  const int face = faceContaining(before, cp);
  ASSERT_GE(face, 0);
  const Vec3 press = facePose(before, face) * Vec3(cp.x(), cp.y(), 0);
  Expected<CompoundFolds> folds = CompoundFolds::at(before, face, press);
  ASSERT_TRUE(folds.ok()) << folds.message();
  ASSERT_GT(folds->outcomes().size(), 150u);
  int resolved = 0;
  for (size_t i = 0; i < 150; ++i)
  {
    const Expected<CompoundFolds::Resolved> fold = folds->resolve(i);
    if (!fold)
      continue;
    ++resolved;
    Paper folded = before;
    ASSERT_TRUE(flatFold(folded, fold->request).ok());
    const Eigen::Isometry3d motion = facePose(folded, face) * facePose(before, face).inverse();
    EXPECT_LE((motion * press - folds->outcomes()[i].landing).norm(), 1e-9) << "outcome " << i;
    for (int v : before.faces[folds->fixedFace()].vertices)
      EXPECT_EQ(folded.vertices[v].folded, before.vertices[v].folded);
  }
  EXPECT_GT(resolved, 10);
}

TEST(FrogBase, TheShippedSequenceFoldsTheScriptsPaperStepByStep)
{
  // sequences/frog_base.json, what the mouse issues (the rostest frog_base_by_mouse checks that), folds
  // without ROS through the same papers as the script, to 1e-6 after a rigid fit.
  const Expected<FoldSequence> shipped = shippedSequence("frog_base.json");
  ASSERT_TRUE(shipped.ok()) << shipped.message();
  const Expected<std::vector<Paper>> states = modelStates(*shipped);
  ASSERT_TRUE(states.ok()) << states.message();
  ASSERT_EQ(states->size(), frog().size());
  for (size_t i = 1; i < states->size(); ++i)
    EXPECT_LE(rigidFitDistance((*states)[i], frog()[i]), 1e-6) << "after step " << i;
}

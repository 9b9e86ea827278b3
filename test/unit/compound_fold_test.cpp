// Folds by one drag (compound_fold.h) on the crane's states (crane_reference.h): a flap pressed
// and dragged to where the reference folding puts the pressed point infers the reference's fold
// — the same creases, the same directions, the same paper to 1e-6 — on the triangle (the squash
// folds), the square base (the petal folds) and the bird base (the inside reverse folds).
#include <gtest/gtest.h>

#include <cmath>

#include "flap_drags.h"
#include "virtual_origami/core/geometry.h"

using namespace virtual_origami::core;
using namespace virtual_origami::core::test;

namespace
{
const std::vector<Paper>& crane()
{
  static const Expected<std::vector<Paper>> states = craneStates();
  EXPECT_TRUE(states.ok()) << states.message();
  return *states;
}

/// The reference's angle for the crease `line` (a crease edge), or NaN when it names none.
double referenceAngle(const FlatFoldRequest& reference, const CreaseLineAngle& line)
{
  const auto on = [](const Vec2& p, const CreaseLineAngle& l) {
    return pointSegmentDistance(Vec3(p.x(), p.y(), 0), Vec3(l.start.x(), l.start.y(), 0),
                                Vec3(l.end.x(), l.end.y(), 0)) < 1e-9;
  };
  for (const CreaseLineAngle& r : reference.creases)
    if (on(line.start, r) && on(line.end, r))
      return r.angle;
  return NAN;
}

/// Drags the flap at `cp` in step `step` to where the reference puts it and checks the fold it
/// infers against the reference's.
void expectTheReferenceFold(int step, const Vec2& cp, CompoundKind kind)
{
  SCOPED_TRACE("step " + std::to_string(step));
  const std::vector<Paper>& states = crane();
  const Paper& before = states[step - 1];
  const FlapDrag drag = flapDrag(states, step, cp);
  ASSERT_GE(drag.face, 0);
  Expected<CompoundFolds> folds = CompoundFolds::at(before, drag.face, drag.press);
  ASSERT_TRUE(folds.ok()) << folds.message();
  const auto chosen = folds->nearestResolved(drag.target);
  ASSERT_TRUE(chosen.has_value());
  const auto& [choice, fold] = *chosen;
  EXPECT_LT(choice.miss, 1e-9);
  EXPECT_NEAR(choice.fraction, 1.0, 1e-9);
  EXPECT_EQ(fold.kind, kind) << compoundKindName(fold.kind);
  // The reference's creases, each with the reference's direction, and no other.
  const Expected<FoldSequence> script = craneReference();
  ASSERT_TRUE(script.ok());
  const FlatFoldRequest& reference = script->steps[step - 1].operation.flat_fold;
  size_t reference_edges = 0;
  for (const CreaseLineAngle& line : reference.creases)
    for (const Edge& e : before.edges)
    {
      const CreaseLineAngle edge{ before.vertices[e.vertices[0]].crease_pattern,
                                  before.vertices[e.vertices[1]].crease_pattern, 0.0 };
      reference_edges += e.isCrease() && !std::isnan(referenceAngle(FlatFoldRequest{ { line }, {} }, edge));
    }
  EXPECT_EQ(fold.request.creases.size(), reference_edges);
  for (const CreaseLineAngle& line : fold.request.creases)
    EXPECT_EQ(line.angle, referenceAngle(reference, line))
        << "(" << line.start.transpose() << ")–(" << line.end.transpose() << ")";
  // The paper it folds: the reference's, the face that stays in place.
  Paper folded = before;
  const Expected<FlatFoldResult> result = flatFold(folded, fold.request);
  ASSERT_TRUE(result.ok()) << result.message();
  EXPECT_LE(largestOffset(folded, drag.after), 1e-6);
  EXPECT_FALSE(folded.face_orders.empty());  // the layers stacked
}
}  // namespace

TEST(CompoundFold, DraggingTheTopFlapOfTheTriangleOpenAndDownSquashesIt)
{
  expectTheReferenceFold(7, Vec2(1.0 / 3, 1.0 / 6), CompoundKind::Squash);
}

TEST(CompoundFold, DraggingTheBottomFlapSquashesItUnderneathWithMountains)
{
  // Pressed on the bottom layer there (picked by Next layer down): the flap stays underneath.
  expectTheReferenceFold(8, Vec2(5.0 / 6, 2.0 / 3), CompoundKind::Squash);
}

TEST(CompoundFold, LiftingTheSquareBasesLowerPointOverTheLineThroughItsSidePointsPetalFolds)
{
  expectTheReferenceFold(12, Vec2(0.18688672392660702, 0.2845177968644246), CompoundKind::Petal);
  expectTheReferenceFold(13, Vec2(0.813113276073393, 0.7154822031355753), CompoundKind::Petal);
}

TEST(CompoundFold, DraggingABirdBaseFlapsTipUpAndOutReverseFoldsItInside)
{
  expectTheReferenceFold(15, Vec2(0.6911, 0.0589), CompoundKind::InsideReverse);  // the neck
  expectTheReferenceFold(17, Vec2(0.0589, 0.6911), CompoundKind::InsideReverse);  // the tail
  expectTheReferenceFold(19, Vec2(0.9917, 0.06), CompoundKind::InsideReverse);    // the head
}

TEST(CompoundFold, AnInsideReverseFoldHasTheOutsideOneAlongTheSameCreases)
{
  const FlapDrag drag = flapDrag(crane(), 15, Vec2(0.6911, 0.0589));
  Expected<CompoundFolds> folds = CompoundFolds::at(crane()[14], drag.face, drag.press);
  ASSERT_TRUE(folds.ok());
  const auto chosen = folds->nearestResolved(drag.target);
  ASSERT_TRUE(chosen.has_value());
  ASSERT_EQ(chosen->second.kind, CompoundKind::InsideReverse);
  ASSERT_TRUE(chosen->second.outside.has_value());
  const FlatFoldRequest& inside = chosen->second.request;
  const FlatFoldRequest& outside = *chosen->second.outside;
  // The inside one turns the flap's spine inside out as well (its fold from the line to the tip,
  // (0.65, 0.35)–(1, 0)); the outside one folds the same creases on the line, the spine as it
  // was: the tip turned round the layers, none of it between them.
  ASSERT_EQ(inside.creases.size(), outside.creases.size() + 1);
  const CreaseLineAngle& spine = inside.creases.back();
  EXPECT_LT((spine.start - Vec2(1, 0)).norm(), 1e-9);
  EXPECT_LT((spine.end - Vec2(1 - std::sqrt(0.125), std::sqrt(0.125))).norm(), 1e-9);
  for (size_t k = 0; k < outside.creases.size(); ++k)
  {
    EXPECT_EQ(outside.creases[k].start, inside.creases[k].start);
    EXPECT_EQ(outside.creases[k].end, inside.creases[k].end);
  }
  // The same places, the layers stacked otherwise.
  Paper in = crane()[14], out = crane()[14];
  ASSERT_TRUE(flatFold(in, inside).ok());
  ASSERT_TRUE(flatFold(out, outside).ok());
  EXPECT_LE(largestOffset(in, out), 1e-9);
  EXPECT_NE(in.face_orders, out.face_orders);
}

TEST(CompoundFold, ThePointersWayAlongTheDragIsTheFractionPreviewed)
{
  const FlapDrag drag = flapDrag(crane(), 15, Vec2(0.6911, 0.0589));
  Expected<CompoundFolds> folds = CompoundFolds::at(crane()[14], drag.face, drag.press);
  ASSERT_TRUE(folds.ok());
  const auto full = folds->nearest(drag.target);
  ASSERT_TRUE(full.has_value());
  const Vec3 halfway = drag.press + 0.5 * (drag.target - drag.press);
  const auto half = folds->nearest(halfway);
  ASSERT_TRUE(half.has_value());
  EXPECT_EQ(half->outcome, full->outcome);
  EXPECT_NEAR(half->fraction, 0.5, 1e-9);
  EXPECT_NEAR(half->miss, 0.5 * (drag.target - drag.press).norm(), 1e-9);
  const auto back = folds->nearest(drag.press - (drag.target - drag.press));  // away from every fold
  ASSERT_TRUE(back.has_value());
  EXPECT_EQ(back->fraction, 0.0);
}

TEST(CompoundFold, EveryOutcomeLandsThePressedPointWhereItsFoldPutsIt)
{
  // Each outcome's landing is where the fold it resolves to takes the pressed point.
  const FlapDrag drag = flapDrag(crane(), 7, Vec2(1.0 / 3, 1.0 / 6));
  Expected<CompoundFolds> folds = CompoundFolds::at(crane()[6], drag.face, drag.press);
  ASSERT_TRUE(folds.ok());
  ASSERT_GT(folds->outcomes().size(), 1u);
  int resolved = 0;
  for (size_t i = 0; i < folds->outcomes().size(); ++i)
  {
    const Expected<CompoundFolds::Resolved> fold = folds->resolve(i);
    if (!fold)
      continue;
    ++resolved;
    Paper folded = crane()[6];
    ASSERT_TRUE(flatFold(folded, fold->request).ok());
    const Eigen::Isometry3d motion = facePose(folded, drag.face) * facePose(crane()[6], drag.face).inverse();
    EXPECT_LE((motion * drag.press - folds->outcomes()[i].landing).norm(), 1e-9) << "outcome " << i;
    EXPECT_GT(largestOffset(folded, crane()[6]), 0.1);  // it folds
    // The face that stays stays, bit for bit.
    for (int v : crane()[6].faces[folds->fixedFace()].vertices)
      EXPECT_EQ(folded.vertices[v].folded, crane()[6].vertices[v].folded);
  }
  EXPECT_GT(resolved, 1);
}

TEST(CompoundFold, PaperThatDoesNotLieFlatOrAPressOffThePaperIsRefused)
{
  const Paper& wings = crane()[20];  // a flap at a right angle
  const Expected<CompoundFolds> standing = CompoundFolds::at(wings, 0, wings.faceCentroid(0));
  ASSERT_FALSE(standing.ok());
  EXPECT_NE(standing.message().find("does not lie flat"), std::string::npos) << standing.message();
  EXPECT_FALSE(CompoundFolds::at(crane()[6], -1, Vec3::Zero()).ok());
  EXPECT_FALSE(CompoundFolds::at(crane()[6], 0, Vec3(NAN, 0, 0)).ok());
  EXPECT_FALSE(CompoundFolds::at(crane()[6], 0, crane()[6].faceCentroid(0), Vec3::Zero()).ok());
  EXPECT_FALSE(CompoundFolds::at(crane()[6], static_cast<int>(crane()[6].faces.size()), Vec3::Zero()).ok());
  // A sheet without creases folds no flap.
  const Paper flat = Paper::square(1.0);
  const Expected<CompoundFolds> none = CompoundFolds::at(flat, 0, Vec3(0.5, 0.5, 0));
  ASSERT_TRUE(none.ok());
  EXPECT_TRUE(none->outcomes().empty());
  EXPECT_FALSE(none->nearest(Vec3(0.2, 0.2, 0)).has_value());
}

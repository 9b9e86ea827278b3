// The traditional flapping bird (test/data/flapping_bird_reference.json): the bird base, the
// lower flaps reverse folded up without thinning (the neck and the tail), the head, and the
// wings lowered to a right angle. Its reverse folds made by one drag each (compound_fold.h)
// against the script to 1e-6, its wings against their closed form, and docs/INTERACTION.md's
// walkthrough ("## Fold a flapping bird") against the script.
#include <gtest/gtest.h>

#include <cmath>

#include "model_reference.h"
#include "reference_fold_checks.h"
#include "virtual_origami/core/chosen_creases.h"
#include "virtual_origami/core/layer_pick.h"
#include "walkthrough_checks.h"

using namespace virtual_origami;
using namespace virtual_origami::core;
using namespace virtual_origami::core::test;

namespace
{
const FoldSequence& script()
{
  static const Expected<FoldSequence> sequence = modelReference("flapping_bird_reference.json");
  EXPECT_TRUE(sequence.ok()) << sequence.message();
  return *sequence;
}

const std::vector<Paper>& bird()
{
  static const Expected<std::vector<Paper>> states = modelStates(script());
  EXPECT_TRUE(states.ok()) << states.message();
  return *states;
}
}  // namespace

TEST(FlappingBird, TheScriptFoldsFlatUpToTheWings)
{
  ASSERT_EQ(bird().size(), script().steps.size() + 1);
  for (size_t i = 1; i + 2 < bird().size(); ++i)
    for (const Edge& e : bird()[i].edges)
    {
      if (e.isCrease())
      {
        EXPECT_TRUE(std::abs(e.fold_angle) < 1e-9 || std::abs(std::abs(e.fold_angle) - M_PI) < 1e-9)
            << "after step " << i << ": a crease at " << e.fold_angle;
      }
    }
}

TEST(FlappingBird, DraggingTheBirdBasesLowerFlapsUpAndOutReverseFoldsThemInside)
{
  expectTheScriptsFold(script(), bird(), 15, Vec2(0.6911, 0.0589), CompoundKind::InsideReverse);  // the neck
  expectTheScriptsFold(script(), bird(), 17, Vec2(0.0589, 0.6911), CompoundKind::InsideReverse);  // the tail
  expectTheScriptsFold(script(), bird(), 19, Vec2(0.9917, 0.06), CompoundKind::InsideReverse);    // the head
}

TEST(FlappingBird, EachWingIsLoweredToARightAngleOnItsOwnSide)
{
  // Before the wings: the wing of corner (0, 0) lies on top (nearest the eye above), the wing of
  // corner (1, 1) under it, both tips at one point half the sheet's side from the hinge's middle.
  const Paper& flat = bird()[19];
  const Vec3 tip = foldedAt(flat, Vec2(0, 0)), hinge = foldedAt(flat, Vec2(0.5, 0));
  EXPECT_LE((foldedAt(flat, Vec2(1, 1)) - tip).norm(), 1e-9);
  EXPECT_NEAR((tip - hinge).norm(), 0.5, 1e-9);
  const std::vector<int> under = facesUnder(flat, tip + 0.05 * (hinge - tip), Vec3(0, 0, -1));
  ASSERT_GE(under.size(), 2u);
  EXPECT_LT(creasePatternPoint(flat, under.front()).norm(), 0.5) << "the top layer is the wing of corner (0, 0)";
  // After: each wing stands at a right angle to the body, the top one towards the eye, the
  // bottom one away: the wings spread and do not pass through each other.
  const Paper& spread = bird().back();
  const Vec3 front = foldedAt(spread, Vec2(0, 0)), back = foldedAt(spread, Vec2(1, 1)), base = foldedAt(spread, Vec2(0.5, 0));
  EXPECT_NEAR(front.z() - base.z(), 0.5, 1e-9);
  EXPECT_NEAR(back.z() - base.z(), -0.5, 1e-9);
  EXPECT_NEAR((front - base).head<2>().norm(), 0.0, 1e-9);
  EXPECT_NEAR((back - base).head<2>().norm(), 0.0, 1e-9);
  // The body stays where it lay.
  EXPECT_LE((foldedAt(spread, Vec2(0.5, 0.5)) - foldedAt(flat, Vec2(0.5, 0.5))).norm(), 1e-9);
}

TEST(FlappingBird, TheWalkthroughNamesTheScriptsFoldsAndItsGesturesAddUp)
{
  const virtual_origami::test::Walkthrough walkthrough = virtual_origami::test::readWalkthrough("## Fold a flapping "
                                                                                                "bird");
  virtual_origami::test::expectTheWalkthroughFoldsTheScript(walkthrough, script(), bird());
}

TEST(FlappingBird, TheShippedSequenceFoldsTheScriptsPaperStepByStep)
{
  // sequences/flapping_bird.json, what the mouse issues (the rostest flapping_bird_by_mouse checks that), folds
  // without ROS through the same papers as the script, to 1e-6 after a rigid fit.
  const Expected<FoldSequence> shipped = shippedSequence("flapping_bird.json");
  ASSERT_TRUE(shipped.ok()) << shipped.message();
  const Expected<std::vector<Paper>> states = modelStates(*shipped);
  ASSERT_TRUE(states.ok()) << states.message();
  ASSERT_EQ(states->size(), bird().size());
  for (size_t i = 1; i < states->size(); ++i)
    EXPECT_LE(rigidFitDistance((*states)[i], bird()[i]), 1e-6) << "after step " << i;
}

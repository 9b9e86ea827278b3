// docs/INTERACTION.md's crane walkthrough against the reference script it folds
// (test/data/crane_reference.json): every step in one row, every fold step's marks named in the
// order of the script's creases with the script's signs and the menu entry that folds them
// named — or the flap it drags, where a drag from there to where the script puts that point
// makes the script's fold (compound_fold.h), of the kind named — and the gestures summed as the
// text says. The rostest crane_by_mouse makes the gestures from
// the same text and counts them.
#include <gtest/gtest.h>

#include "crane_reference.h"
#include "walkthrough_checks.h"

using namespace virtual_origami;
using virtual_origami::test::parseCraneWalkthrough;
using virtual_origami::test::Walkthrough;

TEST(CraneWalkthrough, TheTextNamesTheScriptsMarksStepByStep)
{
  const core::Expected<core::FoldSequence> reference = core::test::craneReference();
  ASSERT_TRUE(reference.ok()) << reference.message();
  const core::Expected<std::vector<core::Paper>> states = core::test::craneStates();
  ASSERT_TRUE(states.ok()) << states.message();
  test::expectTheWalkthroughFoldsTheScript(test::readWalkthrough("## Fold a crane"), *reference, *states);
}

TEST(CraneWalkthrough, MarksAreReadOncePerCreaseOrCounted)
{
  const Walkthrough w = parseCraneWalkthrough("intro\n## Fold a crane\n\n2 steps, **9 gestures** by mouse.\n\n| steps "
                                              "| what | gestures | how |\n"
                                              "|---|---|---|---|\n| 1 | crease | 2 | *Crease mode*, a drag |\n"
                                              "| 2 | fold | 7 | *Fold mode*; **2**: the top *mountain*, the edges "
                                              "*valley* ×3, then *unfold* ×2; "
                                              "*Fold flat* |\n\n## Next\n| 3 | not this table | 1 | **3**: *valley* "
                                              "|\n");
  ASSERT_TRUE(w.error.empty()) << w.error;
  EXPECT_EQ(w.steps, 2);
  EXPECT_EQ(w.total_gestures, 9);
  ASSERT_EQ(w.rows.size(), 2u);
  EXPECT_EQ(w.rows[0].first, 1);
  EXPECT_EQ(w.rows[0].last, 1);
  EXPECT_TRUE(w.rows[0].marks.empty());
  EXPECT_EQ(w.rows[1].gestures, 7);
  EXPECT_EQ(w.rows[1].marks.at(2), (std::vector<int>{ -1, 1, 1, 1, 0, 0 }));
  EXPECT_FALSE(parseCraneWalkthrough("## Other\n").error.empty());
}

TEST(CraneWalkthrough, AFlapDragIsReadWithItsPressPointAndKindInsteadOfMarks)
{
  const Walkthrough w = parseCraneWalkthrough("intro\n## Fold a crane\n\n2 steps, **4 gestures**.\n\n| steps | what | "
                                              "gestures | "
                                              "how |\n|---|---|---|---|\n| 1–2 | squash | 4 | *Flap mode*. **1**: "
                                              "press at (0.33, 0.17) and drag: *squash fold*. **2**: *Next layer "
                                              "down*, press at (0.83, -0.5), drag: *inside reverse fold* |\n");
  ASSERT_TRUE(w.error.empty()) << w.error;
  ASSERT_EQ(w.rows.size(), 1u);
  EXPECT_TRUE(w.rows[0].marks.empty());
  ASSERT_EQ(w.rows[0].drags.size(), 2u);
  EXPECT_EQ(w.rows[0].drags.at(1).kind, "squash fold");
  EXPECT_DOUBLE_EQ(w.rows[0].drags.at(1).x, 0.33);
  EXPECT_DOUBLE_EQ(w.rows[0].drags.at(1).y, 0.17);
  EXPECT_EQ(w.rows[0].drags.at(2).kind, "inside reverse fold");
  EXPECT_DOUBLE_EQ(w.rows[0].drags.at(2).y, -0.5);
}

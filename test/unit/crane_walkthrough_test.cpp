// docs/INTERACTION.md's crane walkthrough against the reference script it folds
// (test/data/crane_reference.json): every step in one row, every fold step's marks named in the
// order of the script's creases with the script's signs and the menu entry that folds them
// named — or the flap it drags, where a drag from there to where the script puts that point
// makes the script's fold (compound_fold.h), of the kind named — and the gestures summed as the
// text says. The rostest crane_by_mouse makes the gestures from
// the same text and counts them.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include "crane_reference.h"
#include "crane_walkthrough.h"
#include "flap_drags.h"

using namespace virtual_origami;
using virtual_origami::test::parseCraneWalkthrough;
using virtual_origami::test::Walkthrough;

namespace
{
Walkthrough readWalkthrough()
{
  std::ifstream file(std::string(VO_SOURCE_DIR) + "/docs/INTERACTION.md");
  std::stringstream text;
  text << file.rdbuf();
  return parseCraneWalkthrough(text.str());
}

int signOf(double angle)
{
  return angle > 1e-9 ? 1 : angle < -1e-9 ? -1 : 0;
}

/// The flap pressed where the text says, dragged to where the script puts that point: the fold
/// inferred is of the kind the text names and folds the script's paper (1e-6).
void expectTheDragFolds(int step, const test::FlapDragNamed& named)
{
  static const core::Expected<std::vector<core::Paper>> states = core::test::craneStates();
  ASSERT_TRUE(states.ok()) << states.message();
  const core::Paper& before = (*states)[step - 1];
  const core::Vec2 cp(named.x, named.y);
  const core::test::FlapDrag drag = core::test::flapDrag(*states, step, cp);
  ASSERT_GE(drag.face, 0) << "step " << step << ": no face at (" << named.x << ", " << named.y << ")";
  core::Expected<core::CompoundFolds> folds = core::CompoundFolds::at(before, drag.face, drag.press);
  ASSERT_TRUE(folds.ok()) << folds.message();
  const auto chosen = folds->nearestResolved(drag.target);
  ASSERT_TRUE(chosen.has_value()) << "step " << step << ": the drag folds nothing";
  EXPECT_EQ(core::compoundKindName(chosen->second.kind), named.kind) << "step " << step;
  core::Paper folded = before;
  ASSERT_TRUE(core::flatFold(folded, chosen->second.request).ok());
  EXPECT_LE(core::test::largestOffset(folded, drag.after), 1e-6) << "step " << step << ": not the script's fold";
}
}  // namespace

TEST(CraneWalkthrough, TheTextNamesTheScriptsMarksStepByStep)
{
  const Walkthrough walkthrough = readWalkthrough();
  ASSERT_TRUE(walkthrough.error.empty()) << walkthrough.error;
  const core::Expected<core::FoldSequence> reference = core::test::craneReference();
  ASSERT_TRUE(reference.ok()) << reference.message();
  const int steps = static_cast<int>(reference->steps.size());
  EXPECT_EQ(walkthrough.steps, steps);
  int next = 1, gestures = 0;
  for (const test::WalkthroughRow& row : walkthrough.rows)
  {
    SCOPED_TRACE("row " + std::to_string(row.first) + "–" + std::to_string(row.last));
    EXPECT_EQ(row.first, next) << "the rows take the steps in turn";
    EXPECT_LE(row.first, row.last);
    next = row.last + 1;
    gestures += row.gestures;
    bool flat = false, right_angle = false;
    for (int step = row.first; step <= row.last && step <= steps; ++step)
    {
      const core::Operation& op = reference->steps[step - 1].operation;
      if (op.kind != core::Operation::Kind::FlatFold)
      {
        EXPECT_FALSE(row.marks.count(step)) << "step " << step << " folds on no marks";
        EXPECT_FALSE(row.drags.count(step)) << "step " << step << " drags no flap";
        continue;
      }
      if (row.drags.count(step))
      {
        expectTheDragFolds(step, row.drags.at(step));
        continue;
      }
      ASSERT_TRUE(row.marks.count(step)) << "step " << step << " (" << reference->steps[step - 1].note
                                         << ") names no marks: **" << step << "** and its marks";
      std::vector<int> script;
      for (const core::CreaseLineAngle& line : op.flat_fold.creases)
      {
        script.push_back(signOf(line.angle));
        (std::abs(std::abs(line.angle) - M_PI / 2) < 1e-9 ? right_angle : flat) = true;
      }
      EXPECT_EQ(row.marks.at(step), script) << "step " << step << ": the marks (+1 valley, −1 mountain, 0 unfold) "
                                            << "in the order of the script's creases";
    }
    for (const auto& [step, marks] : row.marks)
      EXPECT_TRUE(step >= row.first && step <= row.last) << "marks of step " << step << " in another row";
    // The menu entry that folds them (rviz's titles).
    if (flat)
    {
      EXPECT_NE(row.how.find("Fold flat"), std::string::npos);
    }
    if (right_angle)
    {
      EXPECT_NE(row.how.find("Fold to a right angle"), std::string::npos);
    }
  }
  EXPECT_EQ(next, steps + 1) << "every step in a row";
  EXPECT_EQ(gestures, walkthrough.total_gestures) << "the rows' gestures add up to the total said";
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

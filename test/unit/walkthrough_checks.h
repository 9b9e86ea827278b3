// A walkthrough of docs/INTERACTION.md (crane_walkthrough.h reads it) against the reference script
// it folds: every step in one row, in turn; every fold step either names the flap it drags — and
// a drag from there to where the script puts that point makes the script's fold, of the kind
// named (compound_fold.h) — or names its marks in the order of the script's creases with the
// script's signs and the menu entry that folds them; the rows' gestures add up to the totals said
// (with rviz's Interact tool, and with the Fold tool: the `tool` column).
// For the models' tests (crane_walkthrough_test, flapping_bird_test, frog_base_test).
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "crane_walkthrough.h"
#include "flap_drags.h"
#include "virtual_origami/core/fold_sequence.h"

namespace virtual_origami::test
{
/// docs/INTERACTION.md's section under `heading`.
inline Walkthrough readWalkthrough(const std::string& heading)
{
  std::ifstream file(std::string(VO_SOURCE_DIR) + "/docs/INTERACTION.md");
  std::stringstream text;
  text << file.rdbuf();
  return parseWalkthrough(text.str(), heading);
}

inline int signOfAngle(double angle)
{
  return angle > 1e-9 ? 1 : angle < -1e-9 ? -1 : 0;
}

/// The flap pressed where the text says, dragged to where the script puts that point: the fold
/// inferred is of the kind the text names and folds the script's paper (1e-6).
inline void expectTheNamedDragFolds(const std::vector<core::Paper>& states, int step, const FlapDragNamed& named)
{
  const core::Paper& before = states[step - 1];
  const core::test::FlapDrag drag = core::test::flapDrag(states, step, core::Vec2(named.x, named.y));
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

inline void expectTheWalkthroughFoldsTheScript(const Walkthrough& walkthrough, const core::FoldSequence& script,
                                               const std::vector<core::Paper>& states)
{
  ASSERT_TRUE(walkthrough.error.empty()) << walkthrough.error;
  const int steps = static_cast<int>(script.steps.size());
  EXPECT_EQ(walkthrough.steps, steps);
  int next = 1, gestures = 0, tool_gestures = 0;
  for (const WalkthroughRow& row : walkthrough.rows)
  {
    SCOPED_TRACE("row " + std::to_string(row.first) + "–" + std::to_string(row.last));
    EXPECT_EQ(row.first, next) << "the rows take the steps in turn";
    EXPECT_LE(row.first, row.last);
    next = row.last + 1;
    gestures += row.gestures;
    tool_gestures += row.tool_gestures;
    EXPECT_GE(row.tool_gestures, 0) << "the row gives the Fold tool's count (the `tool` column)";
    bool flat = false, right_angle = false;
    for (int step = row.first; step <= row.last && step <= steps; ++step)
    {
      const core::Operation& op = script.steps[step - 1].operation;
      if (op.kind != core::Operation::Kind::FlatFold)
      {
        EXPECT_FALSE(row.marks.count(step)) << "step " << step << " folds on no marks";
        EXPECT_FALSE(row.drags.count(step)) << "step " << step << " drags no flap";
        continue;
      }
      if (row.drags.count(step))
      {
        expectTheNamedDragFolds(states, step, row.drags.at(step));
        continue;
      }
      ASSERT_TRUE(row.marks.count(step)) << "step " << step << " (" << script.steps[step - 1].note
                                         << ") names no marks: **" << step << "** and its marks";
      std::vector<int> signs;
      for (const core::CreaseLineAngle& line : op.flat_fold.creases)
      {
        signs.push_back(signOfAngle(line.angle));
        (std::abs(std::abs(line.angle) - M_PI / 2) < 1e-9 ? right_angle : flat) = true;
      }
      EXPECT_EQ(row.marks.at(step), signs) << "step " << step << ": the marks (+1 valley, −1 mountain, 0 unfold) "
                                           << "in the order of the script's creases";
    }
    for (const auto& [step, marks] : row.marks)
      EXPECT_TRUE(step >= row.first && step <= row.last) << "marks of step " << step << " in another row";
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
  EXPECT_EQ(tool_gestures, walkthrough.total_tool_gestures) << "and so do the Fold tool's";
}

}  // namespace virtual_origami::test

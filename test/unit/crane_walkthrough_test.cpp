// docs/INTERACTION.md's crane walkthrough against the reference script it folds
// (test/data/crane_reference.json): every step in one row, every fold step's marks named in the
// order of the script's creases with the script's signs, the menu entry that folds them named,
// and the gestures summed as the text says. The rostest crane_by_mouse makes the gestures from
// the same text and counts them.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include "crane_reference.h"
#include "crane_walkthrough.h"

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

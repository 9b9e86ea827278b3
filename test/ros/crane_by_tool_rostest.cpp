// rostest crane_by_tool: the traditional crane folded through the Fold tool's interface (the
// rviz tool virtual_origami/Fold: ToolEvent on `tool_events`), step by step against the crane the
// reference script folds (test/data/crane_reference.json), as docs/INTERACTION.md's walkthrough
// "Fold a crane" says, counted against its `tool` column (model_by_mouse.h): number keys choose
// the modes, the wheel walks the layers down and up, Enter folds flat; the sheet marker's menu
// only for *Snap the line*, *Keep the face here* (beside creases) and *Fold to a right angle*.
#include "model_by_mouse.h"

using namespace virtual_origami;

namespace
{
class CraneByTool : public test::ModelByMouse
{
public:
  CraneByTool() : ModelByMouse(test::MouseDriver::Tool)
  {}
};
}  // namespace

TEST_F(CraneByTool, TheCraneFoldsThroughTheFoldToolInAtMostAHundredGesturesAsTheWalkthroughSays)
{
  // The tool makes the same operations as the sheet marker: the shipped crane's.
  foldAsTheLaunchSays("## Fold a crane");
  if (HasFatalFailure())
    return;
  EXPECT_LE(gestures(), 100) << "issue 39: the crane in at most 100 gestures";
  // The menu only for what the tool has no key for.
  for (const auto& [title, times] : menuChoices())
  {
    std::printf("menu: %s %d times\n", title.c_str(), times);
    EXPECT_TRUE(title == "Snap the line" || title == "Keep the face here" || title == "Fold to a right angle")
        << title << " has a key or a gesture of the Fold tool";
  }
}

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "crane_by_tool_rostest");
  ros::NodeHandle nh;
  return RUN_ALL_TESTS();
}

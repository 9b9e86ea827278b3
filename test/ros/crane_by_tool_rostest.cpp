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
  std::string path, shipped_path, walkthrough_path;
  ASSERT_TRUE(ros::param::get("~reference", path));
  ASSERT_TRUE(ros::param::get("~shipped", shipped_path));
  ASSERT_TRUE(ros::param::get("~walkthrough", walkthrough_path));
  foldAsTheWalkthroughSays(path, walkthrough_path, "## Fold a crane");
  if (HasFatalFailure())
    return;
  EXPECT_LE(gestures(), 100) << "issue 39: the crane in at most 100 gestures";
  // The tool makes the same operations as the sheet marker: the shipped crane's.
  const std::vector<core::Operation> issued = issuedOperations();
  const core::Expected<core::FoldSequence> shipped = core::parseFoldSequence(test::readFile(shipped_path));
  ASSERT_TRUE(shipped.ok()) << shipped.message();
  EXPECT_TRUE(test::sameOperations(*shipped, issued))
      << shipped_path << " is not what the tool issued; the tool's sequence:\n"
      << test::sequenceJson(issued, reference());
  RecordProperty("gestures", gestures());
}

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "crane_by_tool_rostest");
  ros::NodeHandle nh;
  return RUN_ALL_TESTS();
}

// rostest frog_base_by_mouse: The traditional frog base (the square base, the squash lines creased through all layers,
// each flap squashed by one drag, two of them on the bottom layer and one under another flap's layer; the petal folds'
// creases through all layers, each squashed flap petal folded by one drag, two of them a few layers down) folded
// through the interaction node alone, as the rviz tool virtual_origami/Fold drives it (ToolEvents;
// `~driver: markers` drives it as rviz's Interact tool does instead), step by step against the paper the reference
// script folds, as docs/INTERACTION.md's walkthrough "Fold a frog base" says (model_by_mouse.h): every step to 1e-6
// after a rigid fit, every row's gestures and the total as the text counts them; the shipped sequence is what the
// gestures issued.
#include <gtest/gtest.h>

#include "model_by_mouse.h"

using namespace virtual_origami;

namespace
{
test::MouseDriver driverAsked()
{
  std::string driver = "tool";
  ros::param::get("~driver", driver);
  return driver == "markers" ? test::MouseDriver::Markers : test::MouseDriver::Tool;
}

class FrogBaseByMouse : public test::ModelByMouse
{
public:
  FrogBaseByMouse() : ModelByMouse(driverAsked())
  {}
};
}  // namespace

TEST_F(FrogBaseByMouse, TheModelFoldsByTheFoldToolAsTheWalkthroughSaysAndTheScriptFoldsIt)
{
  std::string path, shipped_path, walkthrough_path;
  ASSERT_TRUE(ros::param::get("~reference", path));
  ASSERT_TRUE(ros::param::get("~shipped", shipped_path));
  ASSERT_TRUE(ros::param::get("~walkthrough", walkthrough_path));
  foldAsTheWalkthroughSays(path, walkthrough_path, "## Fold a frog base");
  if (HasFatalFailure())
    return;
  // The shipped frog base (sequences/frog_base.json) is written in the operations the gestures issued.
  const std::vector<core::Operation> issued = issuedOperations();
  const core::Expected<core::FoldSequence> shipped = core::parseFoldSequence(test::readFile(shipped_path));
  ASSERT_TRUE(shipped.ok()) << shipped.message();
  EXPECT_TRUE(test::sameOperations(*shipped, issued))
      << shipped_path << " is not what the gestures issued; their sequence:\n"
      << test::sequenceJson(issued, reference());
  RecordProperty("gestures", gestures());
}

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "frog_base_by_mouse_rostest");
  ros::NodeHandle nh;
  return RUN_ALL_TESTS();
}

// rostest crane_by_mouse: the traditional crane folded through the interaction node alone,
// driven exactly as rviz drives it (InteractiveMarkerFeedback on the server's feedback topic:
// presses, drags, releases, menu selections; no service calls), step by step against the crane
// the reference script folds (test/data/crane_reference.json: creases, turns and flat folds), as
// docs/INTERACTION.md's walkthrough "Fold a crane" says (model_by_mouse.h). The test plans each
// gesture as a person looks before clicking: where a crease or a face lies on the folded model,
// and which layer the interaction says it picked.
#include "model_by_mouse.h"

using namespace virtual_origami;

namespace
{
class CraneByMouse : public test::ModelByMouse
{
public:
  CraneByMouse() : ModelByMouse(test::MouseDriver::Markers)
  {}
};
}  // namespace

TEST_F(CraneByMouse, TheCraneFoldsByMouseAloneAsTheWalkthroughSaysAndTheScriptFoldsIt)
{
  std::string path, shipped_path, walkthrough_path;
  ASSERT_TRUE(ros::param::get("~reference", path));
  ASSERT_TRUE(ros::param::get("~shipped", shipped_path));
  ASSERT_TRUE(ros::param::get("~walkthrough", walkthrough_path));
  foldAsTheWalkthroughSays(path, walkthrough_path, "## Fold a crane");
  if (HasFatalFailure())
    return;
  // The shipped crane (sequences/crane.json) is written in the operations the mouse issued.
  const std::vector<core::Operation> issued = issuedOperations();
  const core::Expected<core::FoldSequence> shipped = core::parseFoldSequence(test::readFile(shipped_path));
  ASSERT_TRUE(shipped.ok()) << shipped.message();
  EXPECT_TRUE(test::sameOperations(*shipped, issued))
      << shipped_path << " is not what the mouse issued; the mouse's sequence:\n"
      << test::sequenceJson(issued, reference());
  RecordProperty("gestures", gestures());
}

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "crane_by_mouse_rostest");
  ros::NodeHandle nh;
  return RUN_ALL_TESTS();
}

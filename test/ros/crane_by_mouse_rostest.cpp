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
  foldAsTheLaunchSays("## Fold a crane");
}

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "crane_by_mouse_rostest");
  ros::NodeHandle nh;
  return RUN_ALL_TESTS();
}

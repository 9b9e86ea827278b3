// rostest flapping_bird_by_mouse: The traditional flapping bird (the bird base, the neck and tail reverse folded up
// without thinning, the head, the wings lowered to a right angle) folded through the interaction node alone, as the
// rviz tool virtual_origami/Fold drives it (ToolEvents; `~driver: markers` drives it as rviz's Interact tool does
// instead), step by step against the paper the reference script folds, as docs/INTERACTION.md's walkthrough "Fold a
// flapping bird" says (model_by_mouse.h): every step to 1e-6 after a rigid fit, every row's gestures and the total as
// the text counts them; the shipped sequence is what the gestures issued.
#include <gtest/gtest.h>

#include "model_by_mouse.h"

using namespace virtual_origami;

namespace
{
class FlappingBirdByMouse : public test::ModelByMouse
{
public:
  FlappingBirdByMouse() : ModelByMouse(test::driverAsked())
  {}
};
}  // namespace

TEST_F(FlappingBirdByMouse, TheModelFoldsByTheFoldToolAsTheWalkthroughSaysAndTheScriptFoldsIt)
{
  foldAsTheLaunchSays("## Fold a flapping bird");
}

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "flapping_bird_by_mouse_rostest");
  ros::NodeHandle nh;
  return RUN_ALL_TESTS();
}

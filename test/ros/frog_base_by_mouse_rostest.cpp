// rostest frog_base_by_mouse: The traditional frog base (the square base, the squash lines creased through all layers,
// each flap squashed by one drag, three of them by their inner layer, one of those under another flap's layer; the
// petal folds' creases through all layers, each squashed flap petal folded by one drag, three of them a few layers
// down, the back right flap's last; no step passing paper through paper) folded
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
class FrogBaseByMouse : public test::ModelByMouse
{
public:
  FrogBaseByMouse() : ModelByMouse(test::driverAsked())
  {}
};
}  // namespace

TEST_F(FrogBaseByMouse, TheModelFoldsByTheFoldToolAsTheWalkthroughSaysAndTheScriptFoldsIt)
{
  foldAsTheLaunchSays("## Fold a frog base");
}

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "frog_base_by_mouse_rostest");
  ros::NodeHandle nh;
  return RUN_ALL_TESTS();
}

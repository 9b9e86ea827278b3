// gripper_example against the running paper_model: the sheet ends folded in half.
#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>
#include <ros/ros.h>

#include "gripper_checks.h"
#include "ros_test_client.h"

namespace virtual_origami::test
{
namespace
{
constexpr double kSolverTolerance = 1e-10;  // spring_solver's default strain tolerance (cfg/SpringSolver.cfg)

TEST(Gripper, FoldsTheSheetInHalfAndLetsGo)
{
  PaperClient client;
  int pulls = 0;
  ros::Subscriber ops = client.nh().subscribe<Operation>("operations", 1000, [&](const Operation::ConstPtr& op) {
    if (op->type == "pull")
      ++pulls;
  });
  // The example lets go (no pins left) only once the sheet has followed it to the end.
  ASSERT_TRUE(waitFor([&] { return foldedAndReleased(client.state()); }, 90.0)) << "the sheet was not folded and "
                                                                                   "released";
  const PaperState state = client.state();
  EXPECT_GT(pulls, 0) << "the paper never followed the gripper frame";
  std::printf("gripper: %d pulls\n", pulls);
  expectFoldedInHalf(state, kSolverTolerance, "gripper");
}
}  // namespace
}  // namespace virtual_origami::test

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "gripper_rostest");
  ros::NodeHandle nh;
  return RUN_ALL_TESTS();
}

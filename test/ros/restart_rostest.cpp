// rostest: kill -9 the solver or the model mid-sequence; roslaunch respawns them.
#include <gtest/gtest.h>

#include <string>

#include "ros_test_client.h"

using namespace virtual_origami;
using virtual_origami::test::PaperClient;
using virtual_origami::test::crash;
using virtual_origami::test::waitFor;

namespace
{
/// A degree-4 vertex at the centre: a full crease x = 0.5 and one half crease on each side.
/// Turning a face about a half crease moves every other face through the solver.
void makeDegreeFourVertex(PaperClient& client)
{
  ASSERT_TRUE(client.crease(0.5, -0.1, 0.5, 1.1).response.success);
  ASSERT_TRUE(client.crease(0.5, 0.5, 1.0, 0.8).response.success);
  ASSERT_TRUE(client.crease(0.5, 0.5, 0.0, 0.9).response.success);
}
}  // namespace

TEST(Restart, FoldingGoesOnWhenTheSolverDies)
{
  PaperClient client;
  ASSERT_TRUE(client.trigger("reset").response.success);
  makeDegreeFourVertex(client);
  const Rotate first = client.rotate(-1, -1, 0.9, 0.9, 0.3);
  ASSERT_TRUE(first.response.success) << first.response.message;
  crash("spring_solver");
  // The very next fold waits for the solver to come back instead of failing.
  const Rotate second = client.rotate(first.response.face, first.response.axis_edge, 0, 0, 0.3);
  ASSERT_TRUE(second.response.success) << second.response.message;
  EXPECT_EQ(second.response.revision, first.response.revision + 1);
  const PaperState state = client.stateAt(second.response.revision);
  EXPECT_NEAR(state.edges[second.response.axis_edge].fold_angle, 0.6, 1e-6);
}

TEST(Restart, TheModelComesBackWithItsHistory)
{
  PaperClient client;
  ASSERT_TRUE(client.trigger("reset").response.success);
  ASSERT_TRUE(client.crease(0, 0, 1, 1).response.success);
  const Rotate folded = client.rotate(-1, -1, 0.2, 0.8, M_PI);
  ASSERT_TRUE(folded.response.success) << folded.response.message;
  ASSERT_TRUE(client.trigger("undo").response.success);
  const PaperState before_fold = client.stateAt(folded.response.revision + 1);
  ASSERT_TRUE(client.trigger("redo").response.success);
  const PaperState last = client.stateAt(folded.response.revision + 2);

  crash("paper_model");
  // The new process publishes the same state under the same revision...
  const PaperState& back = client.stateAt(last.revision);
  EXPECT_EQ(back.vertices_folded, last.vertices_folded);
  EXPECT_EQ(back.edges, last.edges);
  // ...and undo still reaches back into the history made before the crash.
  const std_srvs::Trigger undone = client.trigger("undo");
  ASSERT_TRUE(undone.response.success) << undone.response.message;
  const PaperState& after = client.stateAt(last.revision + 1);
  EXPECT_EQ(after.vertices_folded, before_fold.vertices_folded);
  EXPECT_EQ(after.faces.size(), 2u);  // unfolded, still creased
  ASSERT_TRUE(client.trigger("undo").response.success);
  EXPECT_EQ(client.stateAt(last.revision + 2).faces.size(), 1u);  // back to the reset sheet
}

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "restart_rostest");
  ros::NodeHandle keep_alive;
  return RUN_ALL_TESTS();
}

// rostest: a folding recorded through the services replays into a fresh model exactly, and
// the recording survives kill -9 of the recorder.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>

#include "ros_test_client.h"
#include "virtual_origami/ros/recording.h"
#include "virtual_origami/ros/replay.h"

using namespace virtual_origami;
using virtual_origami::test::PaperClient;
using virtual_origami::test::crash;
using virtual_origami::test::waitFor;


TEST(RecordReplay, AReplayEndsInTheRecordedState)
{
  const std::string bag = ros::NodeHandle("~").param<std::string>("bag", "");
  ASSERT_FALSE(bag.empty());
  PaperClient recorded("/origami"), replayed("/replayed");
  // The recorder has the latched starting state once the bag exists.
  ASSERT_TRUE(waitFor([&] { return std::filesystem::exists(bag); }, 30.0));

  // Flat folds, a fold the solver carries (a degree-4 vertex), undo/redo and a squash.
  ASSERT_TRUE(recorded.crease(0.5, -0.1, 0.5, 1.1).response.success);
  ASSERT_TRUE(recorded.crease(0.5, 0.5, 1.0, 0.8).response.success);
  ASSERT_TRUE(recorded.crease(0.5, 0.5, 0.0, 0.9).response.success);
  const Rotate solved = recorded.rotate(-1, -1, 0.9, 0.9, 0.4);
  ASSERT_TRUE(solved.response.success) << solved.response.message;
  ASSERT_TRUE(recorded.trigger("undo").response.success);
  ASSERT_TRUE(recorded.trigger("redo").response.success);
  ASSERT_TRUE(recorded.trigger("undo").response.success);
  ASSERT_TRUE(recorded.crease(-0.1, 0.25, 1.1, 0.25).response.success);
  const Rotate folded = recorded.rotate(-1, -1, 0.3, 0.1, M_PI);
  ASSERT_TRUE(folded.response.success) << folded.response.message;
  ASSERT_TRUE(recorded.trigger("squash").response.success);
  const uint64_t last = folded.response.revision + 1;
  const PaperState expected = recorded.stateAt(last);

  // Killed as a crash would: what it wrote stays readable, every operation in it.
  ros::WallDuration(1.0).sleep();
  crash("recorder", false);
  const core::Expected<Recording> recording = readRecording(bag);
  ASSERT_TRUE(recording.ok()) << recording.message();
  ASSERT_EQ(recording->operations.size(), 10u);
  EXPECT_EQ(recording->operations.back().type, "squash");
  EXPECT_EQ(recording->operations.back().revision, last);
  ASSERT_TRUE(recording->initial_state.has_value());

  OperationClient client("/replayed");
  ASSERT_TRUE(client.waitForServices(30.0));
  ReplayOptions options;
  options.speed = 0;  // no pauses, no animation
  const core::Status done = replay(*recording, client, options);
  ASSERT_TRUE(done.ok()) << done.message();

  // Same topology, same positions (the replay starts from a loaded copy of the first state).
  ASSERT_TRUE(waitFor([&] { return replayed.state().edges.size() == expected.edges.size() &&
                                   replayed.state().faces.size() == expected.faces.size(); }));
  const PaperState& got = replayed.state();
  EXPECT_EQ(got.faces, expected.faces);
  ASSERT_EQ(got.edges.size(), expected.edges.size());
  for (size_t e = 0; e < got.edges.size(); ++e)
  {
    EXPECT_EQ(got.edges[e].v0, expected.edges[e].v0);
    EXPECT_EQ(got.edges[e].v1, expected.edges[e].v1);
    EXPECT_EQ(got.edges[e].assignment, expected.edges[e].assignment);
    EXPECT_NEAR(got.edges[e].fold_angle, expected.edges[e].fold_angle, 1e-9);
  }
  ASSERT_EQ(got.vertices_folded.size(), expected.vertices_folded.size());
  for (size_t v = 0; v < got.vertices_folded.size(); ++v)
  {
    EXPECT_NEAR(got.vertices_folded[v].x, expected.vertices_folded[v].x, 1e-9);
    EXPECT_NEAR(got.vertices_folded[v].y, expected.vertices_folded[v].y, 1e-9);
    EXPECT_NEAR(got.vertices_folded[v].z, expected.vertices_folded[v].z, 1e-9);
  }
  std::filesystem::remove(bag);
}

TEST(RecordReplay, ABrokenBagIsReportedNotReplayed)
{
  const std::string path = "/tmp/virtual_origami_broken_" + std::to_string(::getpid()) + ".bag";
  { std::FILE* f = std::fopen(path.c_str(), "w"); std::fputs("#ROSBAG V2.0\nnot a bag", f); std::fclose(f); }
  const core::Expected<Recording> broken = readRecording(path);
  EXPECT_FALSE(broken.ok());
  EXPECT_NE(broken.message().find(path), std::string::npos) << broken.message();
  EXPECT_FALSE(readRecording("/no/such.bag").ok());
  std::remove(path.c_str());
}

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "record_replay_rostest");
  ros::NodeHandle keep_alive;
  return RUN_ALL_TESTS();
}

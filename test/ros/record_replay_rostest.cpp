// rostest: a folding recorded through the services replays into a fresh model exactly, and
// the recording survives kill -9 of the recorder.
#include <gtest/gtest.h>

#include <algorithm>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <future>
#include <vector>

#include <virtual_origami/DragVertex.h>
#include <virtual_origami/FlatFold.h>
#include <virtual_origami/KeepBend.h>
#include <virtual_origami/PinVertex.h>

#include "../unit/bent_strips.h"
#include "ros_test_client.h"
#include "virtual_origami/ros/recording.h"
#include "virtual_origami/ros/replay.h"

using namespace virtual_origami;
using virtual_origami::test::PaperClient;
using virtual_origami::test::crash;
using virtual_origami::test::point;
using virtual_origami::test::vertexAt;
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
  // Part way, so that the squash presses something (a squash of flat paper is refused).
  const Rotate folded = recorded.rotate(-1, -1, 0.3, 0.1, 2.0);
  ASSERT_TRUE(folded.response.success) << folded.response.message;
  const std_srvs::Trigger squashed = recorded.trigger("squash");
  ASSERT_TRUE(squashed.response.success) << squashed.response.message;

  // Then afresh: a fold on a chosen crease (previewed half way first), pins, a vertex dragged
  // (previewed first), a rotation of the picked layers only.
  ASSERT_TRUE(recorded.trigger("reset").response.success);
  ASSERT_TRUE(recorded.crease(0, 0, 1, 1).response.success);
  FlatFold::Request fold;
  fold.starts = { point(0, 0) };
  fold.ends = { point(1, 1) };
  fold.angles = { M_PI };
  fold.fixed = point(0.9, 0.1);
  fold.commit = false;
  fold.fraction = 0.5;
  const FlatFold previewed = recorded.call<FlatFold>("flat_fold", fold);
  ASSERT_TRUE(previewed.response.success) << previewed.response.message;
  fold.commit = true;
  const FlatFold flat = recorded.call<FlatFold>("flat_fold", fold);
  ASSERT_TRUE(flat.response.success) << flat.response.message;
  const PaperState halved = recorded.stateAt(flat.response.revision);
  // The half that stays is pinned: its three corners.
  for (const auto& [x, y] : { std::pair<double, double>{ 0, 0 }, { 1, 0 }, { 1, 1 } })
  {
    PinVertex::Request pin;
    pin.vertex = vertexAt(halved, x, y);
    ASSERT_GE(pin.vertex, 0);
    ASSERT_TRUE(recorded.call<PinVertex>("pin", pin).response.success);
  }
  // The corner (0, 1), folded onto (1, 0), dragged back up to a right angle.
  DragVertex::Request drag;
  drag.vertex = vertexAt(halved, 0, 1);
  drag.position = point(0.5, 0.5, std::sqrt(0.5));
  drag.commit = false;
  const DragVertex preview_drag = recorded.call<DragVertex>("drag_vertex", drag);
  ASSERT_TRUE(preview_drag.response.success) << preview_drag.response.message;
  EXPECT_EQ(preview_drag.response.revision, flat.response.revision);
  drag.commit = true;
  const DragVertex dragged = recorded.call<DragVertex>("drag_vertex", drag);
  ASSERT_TRUE(dragged.response.success) << dragged.response.message;
  EXPECT_EQ(dragged.response.revision, flat.response.revision + 1);
  EXPECT_LE(dragged.response.residual, 1e-6);
  EXPECT_LE(dragged.response.max_strain, 1e-6);
  const PaperState upright = recorded.stateAt(dragged.response.revision);
  EXPECT_NEAR(upright.vertices_folded[drag.vertex].z, std::sqrt(0.5), 1e-6);
  Rotate::Request turn;
  turn.face = -1;
  turn.axis_edge = -1;
  for (size_t e = 0; e < upright.edges.size(); ++e)
    if (upright.edges[e].face_left >= 0 && upright.edges[e].face_right >= 0)
      turn.axis_edge = static_cast<int>(e);
  ASSERT_GE(turn.axis_edge, 0);
  for (size_t f = 0; f < upright.faces.size(); ++f)  // the flap: the face with the corner (0, 1)
    for (const auto v : upright.faces[f].vertices)
      if (static_cast<int>(v) == drag.vertex)
        turn.face = static_cast<int>(f);
  ASSERT_GE(turn.face, 0);
  turn.angle = -0.25;
  turn.commit = true;
  turn.picked_layers_only = true;
  const Rotate turned = recorded.call<Rotate>("rotate", turn);
  ASSERT_TRUE(turned.response.success) << turned.response.message;
  const uint64_t last = turned.response.revision;
  const PaperState expected = recorded.stateAt(last);

  // Killed as a crash would: what it wrote stays readable, every operation in it.
  ros::WallDuration(1.0).sleep();
  crash("recorder", false);
  const core::Expected<Recording> recording = readRecording(bag);
  ASSERT_TRUE(recording.ok()) << recording.message();
  // 10 before the reset; then reset, crease, flat_fold, three pins, drag_vertex, rotate (the
  // previews are not recorded).
  ASSERT_EQ(recording->operations.size(), 18u);
  EXPECT_EQ(recording->operations[9].type, "squash");
  const Operation& flat_op = recording->operations[12];
  EXPECT_EQ(flat_op.type, "flat_fold");
  ASSERT_EQ(flat_op.crease_angles.size(), 1u);
  EXPECT_EQ(flat_op.crease_angles[0], M_PI);
  EXPECT_EQ(flat_op.fixed.x, 0.9);
  const Operation& drag_op = recording->operations[16];
  EXPECT_EQ(drag_op.type, "drag_vertex");
  EXPECT_EQ(drag_op.vertex, drag.vertex);
  EXPECT_EQ(drag_op.position.z, std::sqrt(0.5));
  EXPECT_EQ(recording->operations.back().type, "rotate");
  EXPECT_TRUE(recording->operations.back().picked_layers_only);
  EXPECT_EQ(recording->operations.back().revision, last);
  // Where the turn's vertices ended, which the replay takes instead of solving again.
  EXPECT_EQ(recording->operations.back().folded, expected.vertices_folded);
  ASSERT_TRUE(recording->initial_state.has_value());

  OperationClient client("/replayed");
  ASSERT_TRUE(client.waitForServices(30.0));
  ReplayOptions options;
  options.speed = 0;  // no pauses, no animation
  const core::Status done = replay(*recording, client, options);
  ASSERT_TRUE(done.ok()) << done.message();

  // Same topology, same positions (the replay starts from a loaded copy of the first state).
  // The replay's last state may still be on its way (the topology is the same for its last
  // operations): wait for the positions, then check everything.
  ASSERT_TRUE(waitFor([&] { return replayed.state().edges.size() == expected.edges.size() &&
                                   replayed.state().faces.size() == expected.faces.size(); }));
  waitFor([&] {
    const PaperState& s = replayed.state();
    if (s.vertices_folded.size() != expected.vertices_folded.size())
      return false;
    for (size_t v = 0; v < s.vertices_folded.size(); ++v)
      if (std::abs(s.vertices_folded[v].x - expected.vertices_folded[v].x) > 1e-9 ||
          std::abs(s.vertices_folded[v].y - expected.vertices_folded[v].y) > 1e-9 ||
          std::abs(s.vertices_folded[v].z - expected.vertices_folded[v].z) > 1e-9)
        return false;
    return true;
  });
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

// Found by the round-3 probe: two creases stamped 1e9 s apart replayed at speed 1 never ended
// (no message), and a bag refused half way left the paper half replayed.
TEST(RecordReplay, GapsAreCappedAndAFailureRollsBack)
{
  PaperClient replayed("/replayed");
  OperationClient client("/replayed");
  ASSERT_TRUE(client.waitForServices(30.0));
  const auto crease = [](double x, double stamp) {
    Operation op;
    op.type = "crease";
    op.start.x = op.end.x = x;
    op.start.y = -0.1;
    op.end.y = 1.1;
    op.header.stamp = ros::Time(stamp);
    return op;
  };
  Recording gap;
  gap.operations = { crease(0.3, 1.0), crease(0.6, 1.0 + 1e9) };
  ReplayOptions options;
  options.speed = 1.0;  // as recorded, but for the gap
  options.max_gap = 0.5;
  std::vector<size_t> progress;
  options.progress = [&](size_t done, size_t total) {
    EXPECT_EQ(total, 2u);
    progress.push_back(done);
  };
  auto replaying = std::async(std::launch::async, [&] { return replay(gap, client, options); });
  ASSERT_EQ(replaying.wait_for(std::chrono::seconds(60)), std::future_status::ready);
  const core::Status done = replaying.get();
  ASSERT_TRUE(done) << done.message();
  EXPECT_EQ(progress, (std::vector<size_t>{ 1, 2 }));
  ASSERT_TRUE(waitFor([&] { return replayed.state().faces.size() == 3u; }));
  const PaperState before = replayed.state();

  // Refused on its third operation (a face that does not exist): rolled back.
  Recording broken;
  broken.operations = { crease(0.2, 0.0), crease(0.8, 0.0), crease(0.5, 0.0) };
  broken.operations[2].type = "rotate";
  broken.operations[2].face = broken.operations[2].axis_edge = 100000;
  broken.operations[2].angle = 1.0;
  options.speed = 0;
  options.progress = {};
  const core::Status failed = replay(broken, client, options);
  ASSERT_FALSE(failed);
  EXPECT_NE(failed.message().find("operation 3 of 3"), std::string::npos) << failed.message();
  EXPECT_NE(failed.message().find("as it was before the replay"), std::string::npos) << failed.message();
  // The same counts pass by on the way (the broken bag's two creases make three faces too): the
  // paper is back when its vertices are where they were.
  // The crease pattern's points in any order (a load may number them its own way).
  const auto samePattern = [](const PaperState& a, const PaperState& b) {
    const auto points = [](const PaperState& s) {
      std::vector<std::pair<double, double>> p;
      for (const auto& v : s.vertices_crease_pattern)
        p.emplace_back(std::round(v.x * 1e6), std::round(v.y * 1e6));
      std::sort(p.begin(), p.end());
      return p;
    };
    return points(a) == points(b);
  };
  ASSERT_TRUE(waitFor([&] {
    const PaperState& now = replayed.state();
    return now.revision > before.revision && now.faces.size() == before.faces.size() &&
           now.edges.size() == before.edges.size() && samePattern(now, before);
  })) << "the paper was not rolled back: "
      << replayed.state().faces.size() << " faces";

  // An operation of a type no model knows: refused before anything is applied.
  const uint64_t revision = replayed.state().revision;
  Recording unknown;
  unknown.operations = { crease(0.5, 0.0), crease(0.5, 0.0) };
  unknown.operations[1].type = "fold_everything";
  const core::Status refused = replay(unknown, client, options);
  ASSERT_FALSE(refused);
  EXPECT_NE(refused.message().find("nothing was replayed"), std::string::npos) << refused.message();
  ros::WallDuration(0.3).sleep();
  ros::spinOnce();
  EXPECT_EQ(replayed.state().revision, revision);
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

// Issue 38 item 1: a bend kept is recorded in a bag (its `operations` message carries the sheet,
// written by the recorder's DurableBagWriter) and a replay of the bag lands on the kept state
// bit for bit.
TEST(RecordReplay, AKeptBendIsRecordedInABagAndReplayedExactly)
{
  PaperClient recorded("/origami"), replayed("/replayed");
  std::vector<Operation> operations;
  ros::Subscriber operations_sub = recorded.nh().subscribe<Operation>(
      "operations", 10, [&](const Operation::ConstPtr& op) { operations.push_back(*op); });
  ASSERT_TRUE(waitFor([&] { return operations_sub.getNumPublishers() > 0; }, 30));
  ASSERT_TRUE(recorded.trigger("reset").response.success);
  ASSERT_TRUE(waitFor([&] { return !operations.empty() && recorded.state().faces.size() == 1u; }, 10));
  const PaperState flat = recorded.state();
  operations.clear();

  const core::BentSheet sheet = core::test::stripsBentFrom(0.0, 8, 0.2);
  KeepBend::Request keep;
  for (const core::Vec2& p : sheet.points)
    keep.points.push_back(point(p.x(), p.y()));
  for (const auto& t : sheet.triangles)
    keep.triangles.insert(keep.triangles.end(), t.begin(), t.end());
  for (const core::Vec3& p : sheet.positions)
    keep.positions.push_back(point(p.x(), p.y(), p.z()));
  const KeepBend kept = recorded.call<KeepBend>("keep_bend", keep);
  ASSERT_TRUE(kept.response.success) << kept.response.message;
  EXPECT_EQ(kept.response.triangles_kept, 128);
  EXPECT_NEAR(kept.response.largest_bend, 0.2, 1e-12);
  const PaperState expected = recorded.stateAt(kept.response.revision);
  ASSERT_TRUE(waitFor([&] { return !operations.empty(); }, 10));
  ASSERT_EQ(operations.back().type, "keep_bend");

  // The bag as the recorder writes it: the state the operation started from, then the operation.
  const std::string bag = (std::filesystem::temp_directory_path() /
                           ("virtual_origami_kept_bend_" + std::to_string(::getpid()) + ".bag"))
                              .string();
  DurableBagWriter writer(bag);
  ASSERT_TRUE(writer.write("/origami/state", flat).ok());
  ASSERT_TRUE(writer.write("/origami/operations", operations.back()).ok());
  const core::Expected<Recording> recording = readRecording(bag);
  std::filesystem::remove(bag);
  ASSERT_TRUE(recording.ok()) << recording.message();
  ASSERT_EQ(recording->operations.size(), 1u);
  EXPECT_EQ(recording->operations[0].bend_points.size(), sheet.points.size());
  EXPECT_EQ(recording->operations[0].bend_triangles.size(), 3 * sheet.triangles.size());

  OperationClient client("/replayed");
  ASSERT_TRUE(client.waitForServices(30.0));
  ReplayOptions options;
  options.speed = 0;
  const core::Status done = replay(*recording, client, options);
  ASSERT_TRUE(done.ok()) << done.message();
  ASSERT_TRUE(waitFor([&] { return replayed.state().faces.size() == expected.faces.size(); }, 10));
  const PaperState& got = replayed.state();
  EXPECT_EQ(got.faces, expected.faces);
  EXPECT_EQ(got.vertices_folded, expected.vertices_folded);
  EXPECT_EQ(got.vertices_crease_pattern, expected.vertices_crease_pattern);
  ASSERT_EQ(got.edges.size(), expected.edges.size());
  for (size_t e = 0; e < got.edges.size(); ++e)
  {
    EXPECT_EQ(got.edges[e].fold_angle, expected.edges[e].fold_angle) << "edge " << e;
    EXPECT_EQ(got.edges[e].split, expected.edges[e].split) << "edge " << e;
    EXPECT_EQ(got.edges[e].target_angle, expected.edges[e].target_angle) << "edge " << e;
  }
}

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "record_replay_rostest");
  ros::NodeHandle keep_alive;
  return RUN_ALL_TESTS();
}

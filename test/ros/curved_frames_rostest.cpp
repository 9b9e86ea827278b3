// rostest: curved_mesh_solver's anytime frames (issue 37). Three corners of the square pinned,
// the fourth dragged on `curved_drag` as the interaction drags it: every sheet shown for a move
// holds the pins and the dragged vertex exactly where they are; the pointer standing still, the
// sheet settles to the solve's tolerance; a bend kept while the frames still move is committed
// balanced (the node settles it first); a vertex pinned on a moving tf frame is followed in
// frames the same way.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>

#include <std_srvs/Trigger.h>
#include <tf2_ros/transform_broadcaster.h>
#include <visualization_msgs/MarkerArray.h>
#include <virtual_origami/PinVertex.h>
#include <virtual_origami/VertexTarget.h>

#include "curved_sheet.h"
#include "ros_test_client.h"
#include "virtual_origami/curved/curved_solver.h"
#include "virtual_origami/ros/conversions.h"
#include "virtual_origami/ros/curved_mesh_solver_node.h"

namespace virtual_origami::test
{
namespace
{
using visualization_msgs::Marker;


class CurvedFrames : public ::testing::Test
{
protected:
  void SetUp() override
  {
    sheet_sub_ = client_.nh().subscribe<visualization_msgs::MarkerArray>(
        "curved_mesh", 1000, [this](const visualization_msgs::MarkerArray::ConstPtr& a) {
          for (const Marker& m : a->markers)
            if (m.ns == "curved_mesh")
              sheets_.push_back(m);
        });
    drag_pub_ = client_.nh().advertise<VertexTarget>("curved_drag", 10);
    ASSERT_TRUE(waitFor([&] { return drag_pub_.getNumSubscribers() >= 2; }, 30)) << "nobody listens to curved_drag";
    const PaperState& state = client_.state();
    // Three corners held where they lie (a state with them pinned already keeps them).
    for (const auto& [x, y] : { std::pair{ 1.0, 0.0 }, { 1.0, 1.0 }, { 0.0, 1.0 } })
    {
      PinVertex::Request pin;
      pin.vertex = vertexAt(state, x, y);
      if (std::none_of(state.pins.begin(), state.pins.end(), [&](const Pin& p) { return p.vertex == pin.vertex; }))
      {
        ASSERT_TRUE(client_.call<PinVertex>("pin", pin).response.success);
      }
    }
    ASSERT_TRUE(waitFor([&] { return client_.state().pins.size() == 3; }, 10));
    state_ = client_.state();
    const core::Expected<core::Paper> paper = fromMessage(state_);
    ASSERT_TRUE(paper) << paper.message();
    paper_ = *paper;
    core::Expected<core::CurvedMesh> mesh = meshCurvedSheet(paper_, config_);
    ASSERT_TRUE(mesh) << mesh.message();
    mesh_ = std::move(*mesh);
    corner_ = vertexAt(state_, 0, 0);
    for (const Pin& p : state_.pins)
      pins_.push_back({ mesh_.vertex_nodes[p.vertex], toVec3(state_.vertices_folded[p.vertex]) });
    // The state's own sheet shown (flat) before the drag.
    ASSERT_TRUE(waitFor([&] { return !sheets_.empty() && sheets_.back().header.stamp == state_.header.stamp; }, 30));
  }

  /// The corner in towards the middle and up, t in [0, 1].
  static core::Vec3 lifted(double t)
  {
    return core::Vec3(0.15 * t, 0.15 * t, 0.25 * t);
  }

  /// Drags the corner in `moves` moves at 30 Hz; the stamp of each move and where it went.
  std::map<ros::Time, core::Vec3> drag(int moves)
  {
    std::map<ros::Time, core::Vec3> sent;
    for (int k = 1; k <= moves; ++k)
    {
      VertexTarget target;
      target.header.frame_id = state_.header.frame_id;
      target.header.stamp = ros::Time::now();
      target.vertex = corner_;
      target.position = toPoint(lifted(static_cast<double>(k) / moves));
      drag_pub_.publish(target);
      sent[target.header.stamp] = lifted(static_cast<double>(k) / moves);
      ros::WallDuration(1.0 / 30).sleep();
      ros::spinOnce();
    }
    return sent;
  }

  void letGo()
  {
    VertexTarget go;
    go.header.frame_id = state_.header.frame_id;
    go.header.stamp = ros::Time::now();
    go.vertex = -1;
    drag_pub_.publish(go);
  }

  /// The largest force of `x` with the state's pins and the corner at `corner`, over stretch ×
  /// spacing (as the solver's tolerance).
  double force(const core::Positions& x, const core::Vec3& corner)
  {
    const core::CurvedFollowOptions options = *curvedFollowOptions(config_);
    core::CurvedSolver solver(mesh_, paper_, options.material, options.contact, options.solve, options.surroundings);
    std::vector<core::CurvedPin> pins = pins_;
    pins.push_back({ mesh_.vertex_nodes[corner_], corner });
    return solver.maxForce(x, pins);
  }

  PaperClient client_;
  ros::Subscriber sheet_sub_;
  ros::Publisher drag_pub_;
  std::vector<Marker> sheets_;
  CurvedMeshSolverConfig config_ = CurvedMeshSolverConfig::__getDefault__();
  PaperState state_;
  core::Paper paper_;
  core::CurvedMesh mesh_;
  int corner_ = -1;
  std::vector<core::CurvedPin> pins_;
};

TEST_F(CurvedFrames, EachMoveIsShownWithThePinsExactAndTheStillSheetSettlesToTheTolerance)
{
  const size_t before = sheets_.size();
  const std::map<ros::Time, core::Vec3> sent = drag(15);
  const ros::Time last = sent.rbegin()->first;
  // Standing still: the last sheet stamped with the last move is balanced to the tolerance.
  std::optional<core::Positions> settled;
  ASSERT_TRUE(waitFor([&] {
    if (sheets_.back().header.stamp != last)
      return false;
    settled = nodePositions(sheets_.back(), mesh_);
    return settled && force(*settled, sent.at(last)) <= config_.tolerance;
  }, 30)) << "the sheet does not settle: force " << (settled ? force(*settled, sent.at(last)) : NAN);
  // Every sheet shown for a move: the pins and the dragged corner exactly where they were.
  int frames = 0;
  for (size_t k = before; k < sheets_.size(); ++k)
  {
    const auto move = sent.find(sheets_[k].header.stamp);
    if (move == sent.end())
      continue;
    const std::optional<core::Positions> x = nodePositions(sheets_[k], mesh_);
    ASSERT_TRUE(x) << "a sheet shown is not of the state's mesh";
    EXPECT_EQ(core::Vec3(x->col(mesh_.vertex_nodes[corner_])), move->second);
    for (const core::CurvedPin& pin : pins_)
      EXPECT_EQ(core::Vec3(x->col(pin.node)), pin.position);
    EXPECT_TRUE(x->allFinite());
    frames += move->first != last ? 1 : 0;
  }
  EXPECT_GT(frames, 0) << "no sheet was shown while the corner moved";
  std::printf("curved_frames: %d of 14 moves before the last shown, the settled sheet at force %.3g\n", frames,
              force(*settled, sent.at(last)));
  letGo();
  EXPECT_TRUE(waitFor([&] { return sheets_.back().header.stamp == state_.header.stamp; }, 30))
      << "the sheet does not spring back to the state's";
}

TEST_F(CurvedFrames, ABendKeptWhileTheFramesMoveIsCommittedBalanced)
{
  const std::map<ros::Time, core::Vec3> sent = drag(15);
  const ros::Time last = sent.rbegin()->first;
  ASSERT_TRUE(waitFor([&] { return sheets_.back().header.stamp == last; }, 30)) << "the last move is not shown";
  // At once, before the pointer has stood still long enough to settle the frames.
  const std_srvs::Trigger kept = client_.trigger("curved_mesh_solver/keep_bend");
  ASSERT_TRUE(kept.response.success) << kept.response.message;
  const PaperState& after = client_.stateAt(state_.revision + 1);
  // The committed sheet: every mesh node a vertex of the kept paper at its crease-pattern point.
  core::Positions x = core::Positions::Zero(3, static_cast<Eigen::Index>(mesh_.nodes.size()));
  for (size_t n = 0; n < mesh_.nodes.size(); ++n)
  {
    const int v = vertexAt(after, mesh_.nodes[n].crease_pattern.x(), mesh_.nodes[n].crease_pattern.y());
    ASSERT_GE(v, 0) << "node " << n << " is not a vertex of the kept paper";
    x.col(static_cast<Eigen::Index>(n)) = toVec3(after.vertices_folded[v]);
  }
  EXPECT_EQ(core::Vec3(x.col(mesh_.vertex_nodes[corner_])), sent.at(last));
  EXPECT_LE(force(x, sent.at(last)), config_.tolerance) << "the kept sheet is not the balance";
  std::printf("curved_frames: kept at force %.3g\n", force(x, sent.at(last)));
  ASSERT_TRUE(client_.trigger("undo").response.success);
  letGo();
}
TEST_F(CurvedFrames, APinOnAMovingTfFrameIsFollowedInFramesAndSettles)
{
  tf2_ros::TransformBroadcaster tf;
  const auto place = [&](const core::Vec3& p) {
    geometry_msgs::TransformStamped t;
    t.header.stamp = ros::Time::now();
    t.header.frame_id = state_.header.frame_id;
    t.child_frame_id = "curved_frames_hand";
    t.transform.translation.x = p.x();
    t.transform.translation.y = p.y();
    t.transform.translation.z = p.z();
    t.transform.rotation.w = 1;
    tf.sendTransform(t);
    return t.header.stamp;
  };
  // The hand at the corner, then the corner pinned on it.
  for (int k = 0; k < 10; ++k)
  {
    place(lifted(0.0));
    ros::WallDuration(0.05).sleep();
  }
  PinVertex::Request pin;
  pin.vertex = corner_;
  pin.frame_id = "curved_frames_hand";
  const PinVertex::Response pinned = client_.call<PinVertex>("pin", pin).response;
  ASSERT_TRUE(pinned.success) << pinned.message;
  ASSERT_TRUE(waitFor([&] { return client_.state().pins.size() == 4; }, 10));
  const size_t before = sheets_.size();
  std::map<ros::Time, core::Vec3> sent;
  const int moves = 15;
  for (int k = 1; k <= moves; ++k)
  {
    const core::Vec3 to = lifted(static_cast<double>(k) / moves);
    sent[place(to)] = to;
    ros::WallDuration(1.0 / 30).sleep();
    ros::spinOnce();
  }
  // The hand stands still (tf keeps its last place): the sheet settles with the corner there.
  std::optional<core::Positions> settled;
  ASSERT_TRUE(waitFor(
      [&] {
        settled = nodePositions(sheets_.back(), mesh_);
        return settled && core::Vec3(settled->col(mesh_.vertex_nodes[corner_])) == lifted(1.0) &&
               force(*settled, lifted(1.0)) <= config_.tolerance;
      },
      8))
      << "the sheet does not settle on the hand's last place";
  int frames = 0;
  for (size_t k = before; k < sheets_.size(); ++k)
    if (const auto move = sent.find(sheets_[k].header.stamp); move != sent.end())
    {
      const std::optional<core::Positions> x = nodePositions(sheets_[k], mesh_);
      ASSERT_TRUE(x);
      EXPECT_EQ(core::Vec3(x->col(mesh_.vertex_nodes[corner_])), move->second);
      for (const core::CurvedPin& p : pins_)
        EXPECT_EQ(core::Vec3(x->col(p.node)), p.position);
      ++frames;
    }
  EXPECT_GT(frames, 1) << "no sheet was shown while the hand moved";
  std::printf("curved_frames: %d sheets stamped with the hand's %d places, settled at force %.3g\n", frames, moves,
              force(*settled, lifted(1.0)));
  pin.release = true;
  EXPECT_TRUE(client_.call<PinVertex>("pin", pin).response.success);
}
}  // namespace
}  // namespace virtual_origami::test

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "curved_frames_rostest");
  ros::NodeHandle nh;
  return RUN_ALL_TESTS();
}

// rostest: curved_mesh_solver with `layers` (issue 38, item 2; docs/CURVED.md "A barrier on that
// start"). The crane of sequences/crane.json is folded through the paper's services, one wing tip
// pinned where it lies, the other dragged on `curved_drag` (as the interaction's Drag mode drags)
// 0.004 of the side away along the tips' line. The sheet shown when the drag stands still has the
// tip where the mouse left it, no layer passed through another, and the body's layers opened.
// The same with both tips pinned on tf frames that move apart, as a robot's grippers would pull
// (curved_layers_frames.test runs that one).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <optional>
#include <sstream>

#include <tf2_ros/transform_broadcaster.h>
#include <visualization_msgs/MarkerArray.h>
#include <virtual_origami/PinVertex.h>
#include <virtual_origami/VertexTarget.h>

#include "curved_sheet.h"
#include "ros_test_client.h"
#include "virtual_origami/core/fold_sequence.h"
#include "virtual_origami/curved/contact.h"
#include "virtual_origami/curved/curved_follow.h"
#include "virtual_origami/curved/layered_start.h"
#include "virtual_origami/ros/conversions.h"
#include "virtual_origami/ros/curved_mesh_solver_node.h"
#include "virtual_origami/ros/operation_client.h"

namespace virtual_origami::test
{
using visualization_msgs::Marker;

namespace
{
/// The crane of the test's `sequence`, folded through the paper's services.
void foldCrane()
{
  std::string path;
  ASSERT_TRUE(ros::NodeHandle("~").getParam("sequence", path));
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  const core::Expected<core::FoldSequence> sequence = core::parseFoldSequence(text.str());
  ASSERT_TRUE(sequence) << sequence.message();
  OperationClient operations("/origami");
  ASSERT_TRUE(operations.waitForServices(30));
  for (const core::FoldStep& step : sequence->steps)
    for (int k = 0; k < step.repeat; ++k)
    {
      const core::Status applied = operations.apply(toMessage(step.operation));
      ASSERT_TRUE(applied) << step.note << ": " << applied.message();
    }
}

/// Every sheet curved_mesh_solver shows on `curved_mesh`, into `sheets`.
ros::Subscriber recordSheets(ros::NodeHandle& nh, std::vector<Marker>& sheets)
{
  return nh.subscribe<visualization_msgs::MarkerArray>("curved_mesh", 1000,
                                                       [&sheets](const visualization_msgs::MarkerArray::ConstPtr& a) {
                                                         for (const Marker& m : a->markers)
                                                           if (m.ns == "curved_mesh")
                                                             sheets.push_back(m);
                                                       });
}

/// The sheet curved_mesh_solver makes of `paper` with this launch's parameters.
core::Expected<core::CurvedMesh> launchedMesh(const core::Paper& paper)
{
  CurvedMeshSolverConfig config = CurvedMeshSolverConfig::__getDefault__();
  ros::NodeHandle solver_params("/origami/curved_mesh_solver");
  if (!solver_params.getParam("layers", config.layers) || !config.layers)
    return core::Expected<core::CurvedMesh>::failure("curved_mesh_solver is not launched with layers");
  solver_params.getParam("spacing", config.spacing);
  return meshCurvedSheet(paper, config);
}
}  // namespace

TEST(CurvedLayers, AFoldedCraneDraggedByAWingTipOpensItsBodyWithNoLayerPassingAnother)
{
  PaperClient client;
  std::vector<Marker> sheets;
  const ros::Subscriber sheet_sub = recordSheets(client.nh(), sheets);
  ros::Publisher drag_pub = client.nh().advertise<VertexTarget>("curved_drag", 10);
  ASSERT_TRUE(waitFor([&] { return drag_pub.getNumSubscribers() >= 1; }, 30)) << "nobody listens to curved_drag";

  // The crane, folded through the services.
  ASSERT_NO_FATAL_FAILURE(foldCrane());
  const int tip0 = vertexAt(client.state(), 0, 0), tip1 = vertexAt(client.state(), 1, 1);
  ASSERT_GE(tip0, 0);
  ASSERT_GE(tip1, 0);
  PinVertex::Request pin;
  pin.vertex = tip0;
  ASSERT_TRUE(client.call<PinVertex>("pin", pin).response.success);
  ASSERT_TRUE(waitFor([&] { return client.state().pins.size() == 1; }, 30));
  const PaperState state = client.state();
  const core::Expected<core::Paper> crane = fromMessage(state);
  ASSERT_TRUE(crane) << crane.message();

  // The sheet as curved_mesh_solver meshes it, with this launch's parameters, shown as the
  // layered start draws it.
  const core::Expected<core::CurvedMesh> mesh = launchedMesh(*crane);
  ASSERT_TRUE(mesh) << mesh.message();
  const core::LayeredStartOptions layers = core::layersFor(*crane, core::CurvedFollowOptions().layer_gap);
  const core::LayeredStart start = core::layeredStart(*mesh, *crane, layers);
  const double gap = layers.gapFor(*crane);
  ASSERT_TRUE(waitFor([&] { return !sheets.empty() && sheets.back().header.stamp == state.header.stamp; }, 60))
      << "the pinned crane is not shown";
  const std::optional<core::Positions> shown = nodePositions(sheets.back(), *mesh);
  ASSERT_TRUE(shown);
  EXPECT_LT((*shown - start.positions).cwiseAbs().maxCoeff(), 1e-12) << "the pinned crane is not shown as drawn";

  // The other tip dragged away along the tips' line in twenty moves at 30 Hz, then held there.
  const core::Vec3 p0 = crane->vertices[tip0].folded, p1 = crane->vertices[tip1].folded;
  const core::Vec3 away = (p1 - p0).normalized();
  const double pull = 0.004 * crane->scale();
  const int node0 = mesh->vertex_nodes[tip0], node1 = mesh->vertex_nodes[tip1];
  VertexTarget drag;
  drag.header.frame_id = state.header.frame_id;
  drag.vertex = tip1;
  for (int k = 1; k <= 20; ++k)
  {
    drag.header.stamp = ros::Time::now();
    drag.position = toPoint(core::Vec3(p1 + pull * k / 20.0 * away));
    drag_pub.publish(drag);
    ros::WallDuration(1.0 / 30).sleep();
    ros::spinOnce();
  }
  const ros::Time last = drag.header.stamp;
  std::optional<core::Positions> x;
  ASSERT_TRUE(waitFor(
      [&] {
        if (sheets.empty() || sheets.back().header.stamp != last)
          return false;
        x = nodePositions(sheets.back(), *mesh);
        return x.has_value();
      },
      240))
      << "no sheet for the drag's last move";
  // The dragged tip where the mouse left it (moved as far as the vertex from where the model has
  // it), the pinned one where it lay.
  EXPECT_LT((x->col(node1) - (start.positions.col(node1) + pull * away)).norm(), 1e-12);
  EXPECT_LT((x->col(node0) - start.positions.col(node0)).norm(), 1e-12);
  // No layer passed through another: no edge through a triangle deeper than a layer's gap that
  // the start had not (where folds' hinges meet at paper vertices).
  EXPECT_LE(core::countPenetrations(*mesh, *x, gap), core::countPenetrations(*mesh, start.positions, gap));
  // The body's stack (its plane's nodes, across the plane), 11 gaps as drawn, opened.
  auto spread = [&](const core::Positions& at) {
    return core::stackThickness(*mesh, *crane, start, start.plane_of[0], at);
  };
  EXPECT_LT(spread(start.positions), 12 * gap);
  EXPECT_GT(spread(*x), 0.5 * pull);
  std::printf("curved_layers: %zu sheets; the body's stack %.2g across (as drawn %.2g)\n", sheets.size(), spread(*x),
              spread(start.positions));
  drag.vertex = -1;
  drag_pub.publish(drag);
}

TEST(CurvedLayers, AFoldedCranePulledByBothWingTipsOnTfFramesOpensItsBody)
{
  PaperClient client;
  std::vector<Marker> sheets;
  const ros::Subscriber sheet_sub = recordSheets(client.nh(), sheets);
  ASSERT_NO_FATAL_FAILURE(foldCrane());
  const PaperState folded = client.state();
  const core::Expected<core::Paper> crane = fromMessage(folded);
  ASSERT_TRUE(crane) << crane.message();
  const int tips[2] = { vertexAt(folded, 0, 0), vertexAt(folded, 1, 1) };
  ASSERT_GE(tips[0], 0);
  ASSERT_GE(tips[1], 0);
  const core::Vec3 at[2] = { crane->vertices[tips[0]].folded, crane->vertices[tips[1]].folded };
  const core::Vec3 away = (at[1] - at[0]).normalized();
  const char* frames[2] = { "curved_layers_grip0", "curved_layers_grip1" };

  // Two grippers on tf, each holding a tip where it lies, then drawing it `pull` away from the
  // other; the frames are sent again at 30 Hz, as a robot's tf is, until the test ends.
  const double pull = 0.002 * crane->scale();
  double drawn = 0;  // how far each gripper has drawn its tip
  tf2_ros::TransformBroadcaster tf;
  ros::WallTime last_sent;
  const auto send = [&] {
    if (ros::WallTime::now() - last_sent < ros::WallDuration(1.0 / 30))
      return;
    last_sent = ros::WallTime::now();
    for (int s = 0; s < 2; ++s)
      tf.sendTransform(frameTransform(folded.header.frame_id, frames[s], at[s] + (s == 0 ? -drawn : drawn) * away));
  };
  const auto waitSending = [&](const std::function<bool()>& done, double seconds) {
    return waitFor([&] { send(); return done(); }, seconds);
  };
  // Sends the frames for `seconds`, as a gripper holding still would.
  const auto holdFor = [&](double seconds) { waitSending([] { return false; }, seconds); };
  holdFor(0.5);  // tf knows the frames before the pins take them
  for (int s = 0; s < 2; ++s)
  {
    PinVertex::Request pin;
    pin.vertex = tips[s];
    pin.frame_id = frames[s];
    const PinVertex::Response pinned = client.call<PinVertex>("pin", pin).response;
    ASSERT_TRUE(pinned.success) << pinned.message;
  }
  ASSERT_TRUE(waitSending([&] { return client.state().pins.size() == 2; }, 30));
  const PaperState pinned = client.state();

  const core::Expected<core::CurvedMesh> mesh = launchedMesh(*crane);
  ASSERT_TRUE(mesh) << mesh.message();
  const core::LayeredStartOptions layers = core::layersFor(*crane, core::CurvedFollowOptions().layer_gap);
  const core::LayeredStart start = core::layeredStart(*mesh, *crane, layers);
  const double gap = layers.gapFor(*crane);
  const int nodes[2] = { mesh->vertex_nodes[tips[0]], mesh->vertex_nodes[tips[1]] };
  // Where the grippers hold the tips' nodes: moved as far as the frames from where the model has
  // the tips.
  const auto held = [&](const core::Positions& x) {
    double off = 0;
    for (int s = 0; s < 2; ++s)
      off = std::max(off, (x.col(nodes[s]) - (start.positions.col(nodes[s]) + (s == 0 ? -drawn : drawn) * away)).norm());
    return off;
  };
  std::optional<core::Positions> x;
  const auto shownHeld = [&] {
    if (sheets.empty())
      return false;
    x = nodePositions(sheets.back(), *mesh);
    return x && held(*x) < 1e-9 * crane->scale();
  };
  ASSERT_TRUE(waitSending(shownHeld, 60)) << "the crane held by its tips is not shown as drawn";

  for (int k = 1; k <= 20; ++k)
  {
    drawn = pull * k / 20.0;
    holdFor(1.0 / 30);
  }
  ASSERT_TRUE(waitSending(shownHeld, 240))
      << "no sheet with the tips where the grippers hold them: the nearest is "
      << (x ? held(*x) : NAN) << " away";
  // The model still the crane as folded (paper_model's `follow_frames` off): the grippers bend
  // the sheet, they do not refold the model.
  EXPECT_EQ(client.state().revision, pinned.revision);
  EXPECT_LE(core::countPenetrations(*mesh, *x, gap), core::countPenetrations(*mesh, start.positions, gap));
  const double spread = core::stackThickness(*mesh, *crane, start, start.plane_of[0], *x);
  EXPECT_GT(spread, 0.5 * pull);
  std::printf("curved_layers: grippers on tf drew the tips %.3g apart; the body's stack %.2g across\n", 2 * pull,
              spread);
}

}  // namespace virtual_origami::test

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "curved_layers_rostest");
  ros::NodeHandle nh;
  return RUN_ALL_TESTS();
}

// gripper_example in the curved mode against paper_model and curved_mesh_solver: while the
// gripper carries the corner of the uncreased sheet, curved_mesh_solver's sheet bends with the
// corner on the gripper frame and the model has no crease; at the end the fold is pressed in
// and the sheet is folded in half, in the model and in the curved mesh.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <optional>

#include <gtest/gtest.h>
#include <ros/ros.h>
#include <tf2_msgs/TFMessage.h>
#include <visualization_msgs/MarkerArray.h>

#include "gripper_checks.h"
#include "curved_sheet.h"
#include "ros_test_client.h"
#include "virtual_origami/curved/curved_metrics.h"
#include "virtual_origami/ros/curved_mesh_solver_node.h"

namespace virtual_origami::test
{
namespace
{
constexpr double kSolverTolerance = 1e-10;  // spring_solver's default strain tolerance (cfg/SpringSolver.cfg)
// Paper barely stretches (bending stiffness a millionth of the stretch, cfg/CurvedMeshSolver.cfg),
// but a triangle mesh bends without stretching only along its edges: curled across them at
// spacing 0.1 its edges stretch by up to about 2.5e-3 at the end of this path
// (test/unit/curved_follow_test.cpp, the same path solved step by step).
constexpr double kMeshStrain = 3e-3;


struct Sheet
{
  PaperState state;  // the newest state when the sheet came
  visualization_msgs::Marker triangles;
};

TEST(GripperCurved, TheSheetBendsBeforeTheCreaseAndEndsFoldedInHalf)
{
  PaperClient client;
  // Every place the gripper frame was broadcast at, by stamp (a tf buffer would interpolate
  // over a message it missed).
  std::map<ros::Time, core::Vec3> gripper_at;
  ros::NodeHandle root;
  ros::Subscriber tf = root.subscribe<tf2_msgs::TFMessage>("/tf", 10000, [&](const tf2_msgs::TFMessage::ConstPtr& m) {
    for (const geometry_msgs::TransformStamped& t : m->transforms)
      if (t.child_frame_id == "gripper" && t.header.frame_id == "paper")
        gripper_at[t.header.stamp] =
            core::Vec3(t.transform.translation.x, t.transform.translation.y, t.transform.translation.z);
  });
  const CurvedMeshSolverConfig config = CurvedMeshSolverConfig::__getDefault__();

  // Every state: while a vertex is on the gripper frame the model has no crease.
  int grasped_states = 0;
  int creased_while_grasped = 0;
  PaperState newest;
  ros::Subscriber states = client.nh().subscribe<PaperState>("state", 100, [&](const PaperState::ConstPtr& s) {
    newest = *s;
    const bool grasped = std::any_of(s->pins.begin(), s->pins.end(), [](const Pin& p) { return !p.frame_id.empty(); });
    if (!grasped)
      return;
    ++grasped_states;
    const bool creased = s->faces.size() != 1 || std::any_of(s->edges.begin(), s->edges.end(), [](const Edge& e) {
                           return e.face_left >= 0 && e.face_right >= 0;
                         });
    creased_while_grasped += creased ? 1 : 0;
  });
  std::vector<Sheet> sheets;
  ros::Subscriber meshes = client.nh().subscribe<visualization_msgs::MarkerArray>(
      "curved_mesh", 1000, [&](const visualization_msgs::MarkerArray::ConstPtr& m) {
        for (const visualization_msgs::Marker& marker : m->markers)
          if (marker.ns == "curved_mesh")
            sheets.push_back({ newest, marker });
      });

  ASSERT_TRUE(waitFor([&] { return foldedAndReleased(client.state()); }, 120.0)) << "the sheet was not folded and "
                                                                                    "released";
  const PaperState final_state = client.state();
  // The sheet of the final state (stamped with it: no frame is followed any more).
  ASSERT_TRUE(waitFor(
      [&] { return !sheets.empty() && sheets.back().triangles.header.stamp == final_state.header.stamp; }, 60.0))
      << "no curved_mesh for the final state";

  EXPECT_GT(grasped_states, 0) << "the corner was never on the gripper frame";
  EXPECT_EQ(creased_while_grasped, 0) << "the model had a crease while the gripper carried the corner";

  // The bending phase: sheets of the uncreased sheet with the corner on the frame, each checked
  // against the gripper frame where it was at the sheet's stamp.
  std::optional<core::CurvedMesh> flat_mesh;
  int checked = 0, deep = 0, at_end = 0;
  double deepest_bend = 0.0, worst_strain = 0.0, worst_corner = 0.0;
  for (const Sheet& sheet : sheets)
  {
    int grasped = -1;
    for (const Pin& p : sheet.state.pins)
      if (p.frame_id == "gripper")
        grasped = p.vertex;
    if (grasped < 0 || sheet.state.faces.size() != 1)
      continue;
    const auto frame = gripper_at.find(sheet.triangles.header.stamp);
    if (frame == gripper_at.end())
      continue;  // a sheet of a state alone, or of a frame message this test did not get
    const core::Expected<core::Paper> paper = fromMessage(sheet.state);
    ASSERT_TRUE(paper) << paper.message();
    if (!flat_mesh)
    {
      core::Expected<core::CurvedMesh> meshed = meshCurvedSheet(*paper, config);
      ASSERT_TRUE(meshed) << meshed.message();
      flat_mesh = std::move(*meshed);
    }
    const std::optional<core::Positions> x = nodePositions(sheet.triangles, *flat_mesh);
    ASSERT_TRUE(x) << "the published sheet is not the mesh of the uncreased sheet";
    const core::Vec3 target = frame->second;
    const double corner_error = (x->col(flat_mesh->vertex_nodes[grasped]) - target).norm();
    // The pinned node is set to the frame's origin: only the messages' rounding separates them.
    EXPECT_LT(corner_error, 1e-12) << "the grasped corner's node is not at the gripper frame";
    for (const Pin& p : sheet.state.pins)
      if (p.frame_id.empty())
      {
        EXPECT_LT((x->col(flat_mesh->vertex_nodes[p.vertex]) - toVec3(sheet.state.vertices_folded[p.vertex])).norm(),
                  1e-12)
            << "a held vertex moved";
      }
    const core::CurvedMetrics metrics = core::measureCurved(*flat_mesh, *paper, *x);
    EXPECT_LT(metrics.strain.max, kMeshStrain);
    EXPECT_EQ(metrics.penetrations, 0);
    // On the table (gripper_curved.test: weight and table on), no node sinks into it by more
    // than a hundredth of the layer thickness.
    EXPECT_GT(x->row(2).minCoeff(), -1e-5) << "the sheet went through the table";
    worst_strain = std::max(worst_strain, metrics.strain.max);
    worst_corner = std::max(worst_corner, corner_error);
    ++checked;
    // Well into the half circle (the corner a quarter of the sheet up), the sheet is curved.
    if (target.z() > 0.25)
    {
      ++deep;
      EXPECT_GT(metrics.max_bend, 0.1) << "the sheet is flat with its corner " << target.z() << " up";
      deepest_bend = std::max(deepest_bend, metrics.max_bend);
    }
    // The end of the path: the corner over the opposite one, where the gripper waits for the
    // sheet before it presses the fold.
    if ((target - core::Vec3::Zero()).norm() < 1e-9)
    {
      ++at_end;
      EXPECT_GT(metrics.max_bend, 0.5) << "the sheet is not curled with its corner on the opposite one";
      std::printf("gripper_curved: at the end of the path, largest dihedral %.3f rad, strain %.3g\n", metrics.max_bend,
                  metrics.strain.max);
    }
  }
  EXPECT_GT(deep, 0) << "no bent sheet with the corner well up (" << checked << " checked)";
  EXPECT_GT(at_end, 0) << "no bent sheet with the corner at the end of the path";
  std::printf("gripper_curved: %d sheets on the frame checked, %d well up, %d at the end, largest dihedral %.3f rad, "
              "corner off its frame %.3g, mesh strain %.3g\n",
              checked, deep, at_end, deepest_bend, worst_corner, worst_strain);

  // The end: the model folded in half, the carried half on top.
  expectFoldedInHalf(final_state, kSolverTolerance, "gripper_curved");

  // The curved mesh shows the folded sheet: two layers over the half that stayed.
  const core::Expected<core::Paper> folded = fromMessage(final_state);
  ASSERT_TRUE(folded) << folded.message();
  core::Expected<core::CurvedMesh> mesh = meshCurvedSheet(*folded, config);
  ASSERT_TRUE(mesh) << mesh.message();
  const std::optional<core::Positions> x = nodePositions(sheets.back().triangles, *mesh);
  ASSERT_TRUE(x) << "the final sheet is not the mesh of the folded state";
  const core::CurvedMetrics metrics = core::measureCurved(*mesh, *folded, *x);
  EXPECT_LT(metrics.strain.max, kMeshStrain);
  EXPECT_EQ(metrics.penetrations, 0);
  // Every node where its half lies folded (x mirrored for the carried half), the carried half
  // above the other. Contact keeps the layers a thickness (1e-3 of the sheet) apart but for
  // where they meet at the fold, so the carried half lies as a thin wedge on the other, a few
  // thicknesses up at its far edge.
  double in_plane = 0.0, height = 0.0, carried_z = 0.0, staying_z = 0.0;
  int carried_nodes = 0, staying_nodes = 0;
  for (size_t n = 0; n < mesh->nodes.size(); ++n)
  {
    const core::Vec2 cp = mesh->nodes[n].crease_pattern;
    const core::Vec3 p = x->col(static_cast<Eigen::Index>(n));
    const bool carried = cp.x() > 0.5 + 1e-9;
    in_plane =
        std::max(in_plane, (core::Vec2(p.x(), p.y()) - core::Vec2(carried ? 1.0 - cp.x() : cp.x(), cp.y())).norm());
    height = std::max(height, std::abs(p.z()));
    if (carried)
    {
      carried_z += p.z();
      ++carried_nodes;
    }
    else if (cp.x() < 0.5 - 1e-9)
    {
      staying_z += p.z();
      ++staying_nodes;
    }
  }
  ASSERT_GT(carried_nodes, 0);
  ASSERT_GT(staying_nodes, 0);
  EXPECT_LT(in_plane, 1e-4) << "the curved mesh does not show the sheet folded in half";
  EXPECT_LT(height, 5e-3) << "the curved mesh's layers are not on each other";
  EXPECT_GT(carried_z / carried_nodes, staying_z / staying_nodes + 1e-3) << "the carried half is not on top";
  EXPECT_LT(metrics.max_bend, 0.1) << "the folded halves are flat";
  std::printf("gripper_curved: final mesh %zu nodes, %.3g from the folded sheet in plane, %.3g high, carried half "
              "%.3g above the other on average, strain %.3g\n",
              mesh->nodes.size(), in_plane, height, carried_z / carried_nodes - staying_z / staying_nodes,
              metrics.strain.max);
}
}  // namespace
}  // namespace virtual_origami::test

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "gripper_curved_rostest");
  ros::NodeHandle nh;
  return RUN_ALL_TESTS();
}

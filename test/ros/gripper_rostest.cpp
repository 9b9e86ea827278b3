// gripper_example against the running paper_model: the sheet ends folded in half.
#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>
#include <ros/ros.h>

#include "ros_test_client.h"
#include "virtual_origami/core/face_orders.h"
#include "virtual_origami/core/metrics.h"
#include "virtual_origami/ros/conversions.h"

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
  const auto folded = [&] {
    const PaperState& s = client.state();
    if (!s.pins.empty() || s.edges.size() < 5)
      return false;
    for (const Edge& e : s.edges)
      if (e.face_left >= 0 && e.face_right >= 0 && std::abs(e.fold_angle) > M_PI / 2)
        return true;
    return false;
  };
  ASSERT_TRUE(waitFor(folded, 90.0)) << "the sheet was not folded and released";
  const PaperState state = client.state();
  EXPECT_GT(pulls, 0) << "the paper never followed the gripper frame";

  ASSERT_EQ(state.faces.size(), 2u);
  int creases = 0;
  for (const Edge& e : state.edges)
    if (e.face_left >= 0 && e.face_right >= 0)
    {
      ++creases;
      EXPECT_NEAR(e.fold_angle, M_PI, M_PI / 180) << "a valley fold of 180 degrees";
    }
  EXPECT_EQ(creases, 1);
  // Two layers: the faces lie on each other, and the layer order says the folded half is on top.
  const core::Expected<core::Paper> paper = fromMessage(state);
  ASSERT_TRUE(paper) << paper.message();
  const core::Vec3 n0 = paper->faceNormal(0), n1 = paper->faceNormal(1);
  EXPECT_NEAR(n0.dot(n1), -1.0, 1e-9) << "the halves face each other";
  EXPECT_NEAR(std::abs(n0.dot(paper->faceCentroid(1) - paper->faceCentroid(0))), 0.0, 1e-9);
  EXPECT_NEAR((paper->faceCentroid(1) - paper->faceCentroid(0)).norm(), 0.0, 1e-9) << "the halves coincide";
  ASSERT_EQ(state.face_orders.size(), 1u);
  const FaceOrder& order = state.face_orders.front();
  // The half the gripper carried (x > 0.5 in the crease pattern) came down from above.
  int carried = -1;
  for (int f = 0; f < 2; ++f)
  {
    double x = 0;
    for (int v : paper->faces[f].vertices)
      x += paper->vertices[v].crease_pattern.x();
    if (x / paper->faces[f].vertices.size() > 0.5)
      carried = f;
  }
  ASSERT_GE(carried, 0);
  const int staying = 1 - carried;
  EXPECT_EQ(order.face == staying ? order.other : order.face, carried);
  EXPECT_EQ(core::faceOrder(*paper, staying, carried), 1) << "the carried half lies on the front of the half that "
                                                             "stayed";
  const double strain = core::edgeStrain(*paper).max;
  EXPECT_LE(strain, kSolverTolerance);
  double fold_angle = 0;
  for (double a : core::measuredFoldAngles(*paper))
    if (std::abs(a) > std::abs(fold_angle))
      fold_angle = a;
  EXPECT_NEAR(fold_angle, M_PI, M_PI / 180) << "measured from the folded positions";
  std::printf("gripper: %d pulls, fold angle %.9f deg measured from the positions, max strain %.3g\n", pulls,
              fold_angle * 180 / M_PI, strain);
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

// rostest: curved_mesh_solver meshes every new state of paper_model and publishes the sheet;
// its spacing is tuned live through dynamic_reconfigure.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>
#include <dynamic_reconfigure/Reconfigure.h>
#include <visualization_msgs/MarkerArray.h>

#include "ros_test_client.h"

using namespace virtual_origami;
using virtual_origami::test::PaperClient;
using virtual_origami::test::waitFor;

namespace
{
class SheetListener
{
public:
  explicit SheetListener(ros::NodeHandle& nh)
  {
    sub_ = nh.subscribe<visualization_msgs::MarkerArray>("curved_mesh", 10, [this](const visualization_msgs::MarkerArray::ConstPtr& m) {
      for (const visualization_msgs::Marker& marker : m->markers)
        if (marker.ns == "curved_mesh")
        {
          triangles_ = marker;
          ++received_;
        }
    });
  }
  /// The next sheet published after this call.
  const visualization_msgs::Marker& next()
  {
    const int before = received_;
    EXPECT_TRUE(waitFor([&] { return received_ > before; }, 30.0)) << "no curved_mesh published";
    return triangles_;
  }
  int received() const { return received_; }
  const visualization_msgs::Marker& last() const { return triangles_; }

private:
  ros::Subscriber sub_;
  visualization_msgs::Marker triangles_;
  int received_ = 0;
};

Eigen::Vector3d at(const geometry_msgs::Point& p) { return { p.x, p.y, p.z }; }

double area3d(const visualization_msgs::Marker& triangles)
{
  double area = 0.0;
  for (size_t i = 0; i + 2 < triangles.points.size(); i += 3)
    area += 0.5 * (at(triangles.points[i + 1]) - at(triangles.points[i]))
                      .cross(at(triangles.points[i + 2]) - at(triangles.points[i]))
                      .norm();
  return area;
}

double highest(const visualization_msgs::Marker& triangles)
{
  double z = -INFINITY;
  for (const geometry_msgs::Point& p : triangles.points)
    z = std::max(z, p.z);
  return z;
}
}  // namespace

TEST(CurvedMeshSolver, FollowsEveryStateAndKeepsTheSheetsArea)
{
  PaperClient client;
  SheetListener sheet(client.nh());
  ASSERT_TRUE(waitFor([&] { return sheet.received() > 0; }, 30.0)) << "no sheet for the initial state";
  // A flat unit square: the mesh covers it exactly, flat.
  EXPECT_EQ(sheet.last().points.size() % 3, 0u);
  EXPECT_GT(sheet.last().points.size(), 3u * 20);
  EXPECT_NEAR(area3d(sheet.last()), 1.0, 1e-9);
  EXPECT_NEAR(highest(sheet.last()), 0.0, 1e-9);

  // Fold a corner triangle up by 90° about the diagonal: the sheet follows, its area kept (the
  // mesh bends only where the paper does), its highest node on the raised corner.
  ASSERT_TRUE(client.crease(0, 0, 1, 1).response.success);
  const Rotate turn = client.rotate(-1, -1, 0.9, 0.1, M_PI / 2);
  ASSERT_TRUE(turn.response.success) << turn.response.message;
  const PaperState& folded = client.stateAt(turn.response.revision);
  double corner = -INFINITY;
  for (const geometry_msgs::Point& p : folded.vertices_folded)
    corner = std::max(corner, p.z);
  ASSERT_GT(corner, 0.5);
  ASSERT_TRUE(waitFor([&] { return sheet.received() > 0 && std::abs(highest(sheet.last()) - corner) < 1e-6; }, 30.0))
      << "the sheet did not follow the fold: highest node at " << highest(sheet.last()) << ", corner at " << corner;
  EXPECT_NEAR(area3d(sheet.last()), 1.0, 1e-6);
}

TEST(CurvedMeshSolver, SpacingIsTunedLive)
{
  PaperClient client;
  SheetListener sheet(client.nh());
  ASSERT_TRUE(waitFor([&] { return sheet.received() > 0; }, 30.0));
  const size_t coarse = sheet.last().points.size();

  dynamic_reconfigure::Reconfigure set;
  dynamic_reconfigure::DoubleParameter spacing;
  spacing.name = "spacing";
  spacing.value = 0.05;
  set.request.config.doubles.push_back(spacing);
  const std::string service = client.nh().resolveName("curved_mesh_solver/set_parameters");
  ASSERT_TRUE(ros::service::waitForService(service, ros::Duration(30)));
  ASSERT_TRUE(callService(service, set));
  // Half the spacing: about four times the triangles.
  const visualization_msgs::Marker& fine = sheet.next();
  EXPECT_GT(fine.points.size(), 3 * coarse);
  EXPECT_NEAR(area3d(fine), 1.0, 1e-6);
}

TEST(CurvedMeshSolver, MesherIsChosenLive)
{
  PaperClient client;
  SheetListener sheet(client.nh());
  ASSERT_TRUE(waitFor([&] { return sheet.received() > 0; }, 30.0));

  dynamic_reconfigure::Reconfigure set;
  dynamic_reconfigure::StrParameter mesher;
  mesher.name = "mesher";
  mesher.value = "cgal";
  set.request.config.strs.push_back(mesher);
  const std::string service = client.nh().resolveName("curved_mesh_solver/set_parameters");
  ASSERT_TRUE(ros::service::waitForService(service, ros::Duration(30)));
  ASSERT_TRUE(callService(service, set));
  bool applied = false;
  for (const dynamic_reconfigure::StrParameter& p : set.response.config.strs)
    applied = applied || (p.name == "mesher" && p.value == "cgal");
  EXPECT_TRUE(applied);
  // CGAL's mesh of the same sheet: it covers the sheet exactly.
  const visualization_msgs::Marker& remeshed = sheet.next();
  EXPECT_EQ(remeshed.points.size() % 3, 0u);
  EXPECT_GT(remeshed.points.size(), 3u * 20);
  EXPECT_NEAR(area3d(remeshed), 1.0, 1e-6);
}

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "curved_rostest");
  ros::NodeHandle keep_alive;
  return RUN_ALL_TESTS();
}

// The seed's view turn, kept usable from any view: the turned camera sees the turning axis at
// an angle the pointer can follow, stays level and above the press, and keeps the press where
// it was in the picture.
#include <gtest/gtest.h>

#include "virtual_origami/core/view_camera.h"

using namespace virtual_origami::core;

namespace
{
/// A level camera at `eye` looking at `target`.
ViewCamera lookingAt(const Vec3& eye, const Vec3& target)
{
  ViewCamera camera;
  const Vec3 forward = (target - eye).normalized();
  camera.axes.col(2) = forward;
  camera.axes.col(0) = forward.cross(Vec3::UnitZ()).normalized();
  camera.axes.col(1) = camera.axes.col(2).cross(camera.axes.col(0));
  camera.eye = eye;
  return camera;
}

void expectUsable(const ViewCamera& before, const ViewCamera& turned, const Vec3& press, const Vec3& axis)
{
  EXPECT_GE(std::abs(turned.rayTo(press).dot(axis.normalized())), 0.6);
  EXPECT_GT(turned.eye.z(), press.z());
  EXPECT_NEAR(turned.axes.col(0).z(), 0.0, 1e-12);  // level: rviz's orbit views have no roll
  EXPECT_TRUE(
      (turned.axes.transpose() * (press - turned.eye)).isApprox(before.axes.transpose() * (press - before.eye)));
}
}  // namespace

TEST(ViewCamera, AViewAlreadySeeingTheAxisIsNotTurned)
{
  const ViewCamera camera = lookingAt(Vec3(0.5, -2.0, 1.5), Vec3(0.5, 0.5, 0));
  EXPECT_FALSE(turnedView(camera, Vec3(0.5, 0.5, 0), Vec3(0.3, 0.5, 0), Vec3(0, 1, 0)).has_value());
}

TEST(ViewCamera, AnEdgeOnRingFromAboveTurnsAboutTheLineFromTheCentreToThePress)
{
  const Vec3 press(0.5, 0.5, 0), centre(0.5, 0.3, 0), axis(1, 0, 0);
  const ViewCamera camera = lookingAt(Vec3(0.5, 0.45, 2.0), press);
  const std::optional<ViewCamera> turned = turnedView(camera, press, centre, axis);
  ASSERT_TRUE(turned.has_value());
  expectUsable(camera, *turned, press, axis);
}

// Low and oblique, the face's centre straight behind the press along the sight line: no turn
// about C–P brings the axis across into view (it only rolls the picture), so the camera orbits
// about the vertical through the press instead.
TEST(ViewCamera, AnEdgeOnRingFromALowObliqueViewStillGetsAView)
{
  const Vec3 press(0.5, 0.5, 0), centre(0.3, 0.5, 0), axis(0, 1, 0);
  const ViewCamera camera = lookingAt(Vec3(-3.0, 0.5, 0.6), press);
  ASSERT_LT(std::abs(camera.rayTo(press).dot(axis)), 0.6);
  const std::optional<ViewCamera> turned = turnedView(camera, press, centre, axis);
  ASSERT_TRUE(turned.has_value());
  expectUsable(camera, *turned, press, axis);
}

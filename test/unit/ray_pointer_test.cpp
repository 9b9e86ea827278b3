// The line of sight through the mouse turned into the gesture model's pointer as rviz reports the
// sheet marker: the point on the pickable copy, the margin, nothing off the paper, and the drag
// plane facing the camera.
#include <gtest/gtest.h>

#include <cmath>

#include "virtual_origami/core/ray_pointer.h"

using namespace virtual_origami::core;

namespace
{
/// An eye at `eye` looking along `forward` (x right, y down, z along the sight).
ViewCamera looking(const Vec3& eye, const Vec3& forward)
{
  ViewCamera c;
  c.eye = eye;
  const Vec3 z = forward.normalized();
  const Vec3 x = (std::abs(z.z()) > 0.9 ? Vec3::UnitX() : z.cross(Vec3::UnitZ())).normalized();
  c.axes.col(0) = x;
  c.axes.col(1) = z.cross(x);
  c.axes.col(2) = z;
  return c;
}

SightRay through(const ViewCamera& camera, const Vec3& point)
{
  return SightRay{ camera, point - camera.eye };
}

const PickableSheet kSheet{ 0.006, 0.1 };
}  // namespace

TEST(RayPointer, TheSightLineMeetsTheSeenFaceLiftTowardsTheEye)
{
  const Paper paper = Paper::square(1.0);
  const ViewCamera camera = looking(Vec3(1.5, -0.8, 1.2), Vec3(-1, 1, -1));
  const Vec3 on_paper(0.3, 0.6, 0.0);
  const std::optional<Vec3> p = sheetPointOnRay(paper, through(camera, on_paper), kSheet);
  ASSERT_TRUE(p);
  EXPECT_NEAR((*p - on_paper).norm(), kSheet.lift, 1e-12);
  EXPECT_NEAR(((*p - on_paper).normalized() - (camera.eye - on_paper).normalized()).norm(), 0.0, 1e-12);
}

TEST(RayPointer, BesideThePaperTheMarginTakesThePointOnTheTableAndFartherOutNothingDoes)
{
  const Paper paper = Paper::square(1.0);
  const ViewCamera camera = looking(Vec3(0.5, 0.5, 2.0), Vec3(0, 0, -1));
  const std::optional<Vec3> margin = sheetPointOnRay(paper, through(camera, Vec3(1.05, 0.5, 0)), kSheet);
  ASSERT_TRUE(margin);
  EXPECT_NEAR(margin->z(), kSheet.lift, 1e-12);  // the margin's plane, under the lifted copy
  EXPECT_NEAR(margin->y(), 0.5, 1e-12);
  EXPECT_FALSE(sheetPointOnRay(paper, through(camera, Vec3(1.2, 0.5, 0)), kSheet));
  // Looking away from the paper, or along the table, or with no direction: nothing.
  EXPECT_FALSE(sheetPointOnRay(paper, SightRay{ camera, Vec3(0, 0, 1) }, kSheet));
  EXPECT_FALSE(sheetPointOnRay(paper, SightRay{ looking(Vec3(0.5, -1, 0.006), Vec3(0, 1, 0)), Vec3(0, 1, 0) }, kSheet));
  EXPECT_FALSE(sheetPointOnRay(paper, SightRay{ camera, Vec3::Zero() }, kSheet));
  EXPECT_FALSE(sheetPointOnRay(paper, SightRay{ camera, Vec3(NAN, 0, -1) }, kSheet));
}

TEST(RayPointer, AFaceBehindTheEyeIsNotSeen)
{
  const Paper paper = Paper::square(1.0);
  // Under the sheet looking down: the sheet is behind the eye, the margin's plane too.
  const ViewCamera camera = looking(Vec3(0.5, 0.5, -0.5), Vec3(0, 0, -1));
  EXPECT_FALSE(sheetPointOnRay(paper, through(camera, Vec3(0.5, 0.5, -1)), kSheet));
}

TEST(RayPointer, ADragMovesTheMarkerOnThePlaneThroughTheGrabFacingTheCamera)
{
  const Paper paper = Paper::square(1.0);
  const ViewCamera camera = looking(Vec3(1.5, -0.8, 1.2), Vec3(-1, 1, -1));
  RayPointer pointer;
  const Pointer pressed = pointer.press(paper, through(camera, Vec3(0.3, 0.6, 0)), kSheet);
  ASSERT_TRUE(pressed.mouse_point);
  ASSERT_TRUE(pointer.holding());
  EXPECT_TRUE(pressed.marker_position.isZero());
  ASSERT_TRUE(pressed.camera);
  const Vec3 grab = *pressed.mouse_point;
  // A point on the plane through the grab facing the camera: the marker moves exactly there.
  const Vec3 on_plane = grab + 0.2 * camera.axes.col(0) - 0.1 * camera.axes.col(1);
  const Pointer moved = pointer.move(through(camera, on_plane));
  EXPECT_TRUE(moved.marker_position.isApprox(on_plane - grab, 1e-12));
  EXPECT_FALSE(moved.mouse_point);  // as rviz's pose updates carry none
  // A sight line along the plane moves nothing further.
  EXPECT_TRUE(pointer.move(SightRay{ camera, camera.axes.col(0) }).marker_position.isApprox(on_plane - grab, 1e-12));
  const Pointer released = pointer.release(paper, through(camera, on_plane), kSheet);
  EXPECT_TRUE(released.marker_position.isApprox(on_plane - grab, 1e-12));
  EXPECT_TRUE(released.mouse_point);
  EXPECT_FALSE(pointer.holding());
  // Nothing held: a move is no move.
  EXPECT_TRUE(pointer.move(through(camera, Vec3(0.9, 0.9, 0))).marker_position.isZero());
}

TEST(RayPointer, APressOffThePaperGrabsNothing)
{
  const Paper paper = Paper::square(1.0);
  const ViewCamera camera = looking(Vec3(0.5, 0.5, 2.0), Vec3(0, 0, -1));
  RayPointer pointer;
  const Pointer pressed = pointer.press(paper, through(camera, Vec3(3, 3, 0)), kSheet);
  EXPECT_FALSE(pressed.mouse_point);
  EXPECT_FALSE(pointer.holding());
}

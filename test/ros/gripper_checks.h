// What both gripper rostests check of the sheet gripper_example leaves: folded in half and
// let go, two stacked layers, the carried half on top.
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "ros_test_client.h"
#include "virtual_origami/core/face_orders.h"
#include "virtual_origami/core/metrics.h"
#include "virtual_origami/ros/conversions.h"

namespace virtual_origami::test
{
/// The example lets go (no pins left) only once the sheet is folded: a crease past 90°.
inline bool foldedAndReleased(const PaperState& s)
{
  if (!s.pins.empty() || s.edges.size() < 5)
    return false;
  for (const Edge& e : s.edges)
    if (e.face_left >= 0 && e.face_right >= 0 && std::abs(e.fold_angle) > M_PI / 2)
      return true;
  return false;
}

/// Two faces joined by one valley crease of 180° (recorded and measured from the positions),
/// lying on each other, the half the gripper carried (x > 0.5 in the crease pattern) on the
/// front of the half that stayed, faces rigid within `strain_tolerance`.
inline void expectFoldedInHalf(const PaperState& state, double strain_tolerance, const char* name)
{
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
  EXPECT_LE(strain, strain_tolerance);
  double fold_angle = 0;
  for (double a : core::measuredFoldAngles(*paper))
    if (std::abs(a) > std::abs(fold_angle))
      fold_angle = a;
  EXPECT_NEAR(fold_angle, M_PI, M_PI / 180) << "measured from the folded positions";
  std::printf("%s: fold angle %.9f deg measured from the positions, max strain %.3g\n", name, fold_angle * 180 / M_PI,
              strain);
}

}  // namespace virtual_origami::test

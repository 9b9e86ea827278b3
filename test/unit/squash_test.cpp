#include <gtest/gtest.h>

#include "test_models.h"
#include "virtual_origami/core/squash.h"

using namespace virtual_origami::core;
using namespace virtual_origami::core::test;

namespace
{
/// Unit square creased at x = 0.5 with its right half turned by `angle`.
Paper halfTurned(double angle)
{
  Paper paper = Paper::square(1.0);
  creaseLine(paper, p3(0.5, -1), p3(0.5, 2));
  RotateRequest request;
  request.click = p3(0.8, 0.5);
  request.angle = angle;
  EXPECT_TRUE(rotate(paper, request).ok());
  return paper;
}
}  // namespace

TEST(Squash, PressesAFoldPastHalfWayFlatOntoTheTable)
{
  Paper paper = halfTurned(2.0);  // 115°: pressed shut
  const Expected<SquashResult> r = squash(paper);
  ASSERT_TRUE(r.ok()) << r.message();
  EXPECT_TRUE(r->exact);
  for (const Vertex& v : paper.vertices)
    EXPECT_NEAR(v.folded.z(), 0.0, 1e-15);
  for (const Edge& e : paper.edges)
    if (e.isCrease())
    {
      EXPECT_NEAR(e.fold_angle, M_PI, 1e-12);
      EXPECT_EQ(e.assignment, Assignment::Valley);
    }
  expectValid(paper);
}

TEST(Squash, PressesAShallowFoldOpen)
{
  Paper paper = halfTurned(-0.6);
  ASSERT_TRUE(squash(paper).ok());
  for (const Vertex& v : paper.vertices)
  {
    EXPECT_NEAR(v.folded.z(), 0.0, 1e-15);
    EXPECT_NEAR(v.folded.x(), v.crease_pattern.x(), 1e-12);  // back to the unfolded square
  }
  for (const Edge& e : paper.edges)
    EXPECT_NEAR(e.fold_angle, 0.0, 1e-12);
  expectValid(paper);
}

TEST(Squash, ATiltedModelLandsOnTheTable)
{
  Paper paper = halfTurned(M_PI / 2);  // an L: the most level face is the half that stayed
  for (Vertex& v : paper.vertices)     // lift and tilt the whole model
    v.folded = Eigen::AngleAxisd(0.3, Vec3(1, 1, 0).normalized()) * v.folded + Vec3(0, 0, 2);
  ASSERT_TRUE(squash(paper).ok());
  for (const Vertex& v : paper.vertices)
    EXPECT_NEAR(v.folded.z(), 0.0, 1e-12);
  expectValid(paper);
}

TEST(Squash, WhatCannotBePressedRigidlyNeedsASolver)
{
  // A single crease folded 120° next to an unfolded crossing one cannot go flat rigidly.
  Paper paper = Paper::square(1.0);
  creaseLine(paper, p3(0.5, -1), p3(0.5, 2));
  creaseLine(paper, p3(-1, 0.5), p3(2, 0.5));
  for (Edge& e : paper.edges)  // pretend the vertical crease is at 120° (a non-developable record)
    if (e.isCrease() && std::abs(paper.vertices[e.vertices[0]].crease_pattern.x() - 0.5) < 1e-12 &&
        std::abs(paper.vertices[e.vertices[1]].crease_pattern.x() - 0.5) < 1e-12 &&
        paper.vertices[e.vertices[0]].crease_pattern.y() > 0.4 && paper.vertices[e.vertices[1]].crease_pattern.y() > 0.4)
      e.fold_angle = 2.0;
  const Paper before = paper;
  const Expected<SquashResult> r = squash(paper);
  EXPECT_FALSE(r.ok());
  EXPECT_NE(r.message().find("solver"), std::string::npos) << r.message();
  EXPECT_TRUE(paper == before);
}

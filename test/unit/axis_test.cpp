#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "test_models.h"
#include "virtual_origami/core/axis.h"

using namespace virtual_origami::core;
using namespace virtual_origami::core::test;

namespace
{
/// A 6 × 6 sheet whose middle face is the 4 × 1 rectangle [1, 5] × [2.5, 3.5], a crease on each side.
Paper rectangleWithFourCreases(int& face)
{
  Paper paper = Paper::square(6.0);
  creaseLine(paper, p3(1, -1), p3(1, 7));
  creaseLine(paper, p3(5, -1), p3(5, 7));
  creaseLine(paper, p3(-1, 2.5), p3(7, 2.5));
  creaseLine(paper, p3(-1, 3.5), p3(7, 3.5));
  face = faceAt(paper, p3(3, 3), 1e-9);
  return paper;
}

/// Which crease each rule picks over a grid of clicks inside the face.
std::set<int> chosenOverFace(const Paper& paper, int face, bool seed_rule)
{
  std::set<int> chosen;
  for (double x = 1.05; x < 5.0; x += 0.1)
    for (double y = 2.55; y < 3.5; y += 0.1)
    {
      const Expected<int> e =
          seed_rule ? automaticAxis(paper, face, p3(x, y)) : farthestCreaseAxis(paper, face, p3(x, y));
      EXPECT_TRUE(e.ok()) << e.message();
      if (e.ok())
        chosen.insert(*e);
    }
  return chosen;
}
}  // namespace

TEST(Axis, EveryCreaseOfTheFaceCanBeChosen)
{
  int face = -1;
  const Paper paper = rectangleWithFourCreases(face);
  ASSERT_GE(face, 0);
  ASSERT_EQ(paper.faces[face].vertices.size(), 4u);
  std::set<int> creases;
  for (int e : paper.faces[face].edges)
    if (paper.edges[e].isCrease())
      creases.insert(e);
  ASSERT_EQ(creases.size(), 4u);
  // Seed Fig. 9a: each crease has a click region that picks it.
  EXPECT_EQ(chosenOverFace(paper, face, true), creases);
  // Seed Fig. 9b: the farthest-crease rule never picks the long sides.
  EXPECT_EQ(chosenOverFace(paper, face, false).size(), 2u);
}

TEST(Axis, PicksTheCreaseAcrossTheCentreFromTheClick)
{
  int face = -1;
  const Paper paper = rectangleWithFourCreases(face);
  const auto side = [&](const Vec3& click) {
    const Expected<int> e = automaticAxis(paper, face, click);
    EXPECT_TRUE(e.ok());
    const Edge& edge = paper.edges[*e];
    return 0.5 * (paper.vertices[edge.vertices[0]].crease_pattern + paper.vertices[edge.vertices[1]].crease_pattern);
  };
  EXPECT_NEAR(side(p3(1.5, 3.0)).x(), 5.0, 1e-12);  // click near the left end: hinge on the right
  EXPECT_NEAR(side(p3(4.5, 3.1)).x(), 1.0, 1e-12);
  EXPECT_NEAR(side(p3(3.0, 2.6)).y(), 3.5, 1e-12);  // click near the bottom middle: hinge on top
  EXPECT_NEAR(side(p3(3.05, 3.4)).y(), 2.5, 1e-12);
}

TEST(Axis, EveryPressOnAHalfPicksItsOnlyCrease)
{
  // The half left of the diagonal: one crease, two boundary sides. The seed's G crosses the
  // diagonal only from part of the face (issue 23: 7 of 10 presses were refused).
  Paper paper = Paper::square(1.0);
  creaseLine(paper, p3(0, 0), p3(1, 1));
  const int half = faceAt(paper, p3(0.2, 0.7), 1e-9);
  ASSERT_GE(half, 0);
  int diagonal = -1;
  for (int e : paper.faces[half].edges)
    if (paper.edges[e].isCrease())
      diagonal = e;
  ASSERT_GE(diagonal, 0);
  int presses = 0;
  for (double x = 0.01; x < 1.0; x += 0.04)
    for (double y = x + 0.01; y < 1.0; y += 0.04)
    {
      const Expected<int> axis = automaticAxis(paper, half, p3(x, y));
      ASSERT_TRUE(axis.ok()) << "press (" << x << ", " << y << "): " << axis.message();
      EXPECT_EQ(*axis, diagonal);
      ++presses;
    }
  EXPECT_GT(presses, 250);
}

TEST(Axis, WhereTheSeedsLineCrossesNoCreaseTheCreaseAcrossTheCentreIsTaken)
{
  // The square with two opposite corners creased off: a hexagon, its cut sides the only
  // creases. A line through the centre and a press in the middle of a side crosses no crease.
  Paper paper = Paper::square(1.0);
  creaseLine(paper, p3(0.6, -0.1), p3(1.1, 0.4));  // x - y = 0.7 inside the sheet
  creaseLine(paper, p3(-0.1, 0.6), p3(0.4, 1.1));  // y - x = 0.7
  const int face = faceAt(paper, p3(0.5, 0.5), 1e-9);
  ASSERT_GE(face, 0);
  ASSERT_EQ(paper.faces[face].vertices.size(), 6u);
  const auto lowerRight = [&](const Expected<int>& axis) {
    EXPECT_TRUE(axis.ok()) << axis.message();
    const Edge& edge = paper.edges[*axis];
    return paper.vertices[edge.vertices[0]].folded.x() + paper.vertices[edge.vertices[1]].folded.x() > 1.0;
  };
  EXPECT_TRUE(lowerRight(automaticAxis(paper, face, p3(0.5, 0.9))));  // pressed at the top: hinge below
  EXPECT_TRUE(lowerRight(automaticAxis(paper, face, p3(0.1, 0.5))));
  EXPECT_FALSE(lowerRight(automaticAxis(paper, face, p3(0.5, 0.1))));
  EXPECT_FALSE(lowerRight(automaticAxis(paper, face, p3(0.9, 0.5))));
  EXPECT_TRUE(lowerRight(automaticAxis(paper, face, p3(0.1, 0.85))));  // G crosses both: the seed's rule
  std::set<int> chosen;
  for (double x = 0.02; x < 1.0; x += 0.04)
    for (double y = 0.02; y < 1.0; y += 0.04)
      if (std::abs(x - y) < 0.69)
      {
        const Expected<int> axis = automaticAxis(paper, face, p3(x, y));
        ASSERT_TRUE(axis.ok()) << "press (" << x << ", " << y << "): " << axis.message();
        chosen.insert(*axis);
      }
  EXPECT_EQ(chosen.size(), 2u);  // a region for each crease
}

TEST(Axis, AClickOnACreaseNamesIt)
{
  Paper paper = Paper::square(1.0);
  creaseLine(paper, p3(0, 0), p3(1, 1));
  creaseLine(paper, p3(0.5, 0), p3(0.5, 1));
  const auto joins = [&](int e, const Vec3& a, const Vec3& b) {
    if (e < 0)
      return false;
    const Vec3& p = paper.vertices[paper.edges[e].vertices[0]].folded;
    const Vec3& q = paper.vertices[paper.edges[e].vertices[1]].folded;
    return ((p - a).norm() < 1e-12 && (q - b).norm() < 1e-12) || ((p - b).norm() < 1e-12 && (q - a).norm() < 1e-12);
  };
  EXPECT_TRUE(joins(creaseNear(paper, p3(0.8, 0.79), 0.02), p3(0.5, 0.5), p3(1, 1)));
  EXPECT_TRUE(joins(creaseNear(paper, p3(0.51, 0.2), 0.02), p3(0.5, 0), p3(0.5, 0.5)));
  EXPECT_EQ(creaseNear(paper, p3(0.7, 0.3), 0.02), -1);  // on a face, away from the creases
  EXPECT_EQ(creaseNear(paper, p3(0.0, 0.5), 0.02), -1);  // on the boundary: not a crease
  EXPECT_EQ(creaseNear(paper, p3(NAN, 0.5), 0.02), -1);
}

TEST(Axis, FaceWithoutCreasesOrBadInput)
{
  const Paper paper = Paper::square(1.0);
  EXPECT_FALSE(automaticAxis(paper, 0, p3(0.2, 0.3)).ok());
  EXPECT_FALSE(automaticAxis(paper, 3, p3(0.2, 0.3)).ok());
  EXPECT_FALSE(automaticAxis(paper, -1, p3(0.2, 0.3)).ok());
  EXPECT_FALSE(automaticAxis(paper, 0, p3(NAN, 0.3)).ok());
}

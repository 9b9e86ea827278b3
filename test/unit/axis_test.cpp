#include <gtest/gtest.h>

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

TEST(Axis, FaceWithoutCreasesOrBadInput)
{
  const Paper paper = Paper::square(1.0);
  EXPECT_FALSE(automaticAxis(paper, 0, p3(0.2, 0.3)).ok());
  EXPECT_FALSE(automaticAxis(paper, 3, p3(0.2, 0.3)).ok());
  EXPECT_FALSE(automaticAxis(paper, -1, p3(0.2, 0.3)).ok());
  EXPECT_FALSE(automaticAxis(paper, 0, p3(NAN, 0.3)).ok());
}

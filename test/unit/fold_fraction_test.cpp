#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "virtual_origami/core/fold_fraction.h"
#include "virtual_origami/core/tessellations.h"

using namespace virtual_origami::core;

TEST(FoldFraction, IsTheLeastSquaresFitOfTheDrivenAnglesToTheirTargets)
{
  const Expected<Tessellation> miura = miuraTessellation(4, 3);
  ASSERT_TRUE(miura.ok()) << miura.message();
  Paper paper = miura->paper;
  EXPECT_TRUE(hasDrivenCreases(paper));
  EXPECT_EQ(foldFraction(paper), 0.0);
  for (size_t e = 0; e < paper.edges.size(); ++e)
    paper.edges[e].fold_angle = 0.4 * miura->target_fold_angle[e];
  EXPECT_NEAR(foldFraction(paper), 0.4, 1e-12);
  // Half the creases at 0.2, half at 0.6 of their targets (all targets ±π): 0.4 on the whole.
  bool low = true;
  for (size_t e = 0; e < paper.edges.size(); ++e)
    if (paper.edges[e].isCrease())
    {
      paper.edges[e].fold_angle = (low ? 0.2 : 0.6) * miura->target_fold_angle[e];
      low = !low;
    }
  const int creases = static_cast<int>(std::count_if(paper.edges.begin(), paper.edges.end(),
                                                     [](const Edge& e) { return e.isCrease(); }));
  const double expected = creases % 2 == 0 ? 0.4 : (0.2 * (creases / 2 + 1) + 0.6 * (creases / 2)) / creases;
  EXPECT_NEAR(foldFraction(paper), expected, 1e-12);
}

TEST(FoldFraction, FileTargetsCountAndTheResultStaysWithinMinusOneToOne)
{
  const Expected<Tessellation> miura = miuraTessellation(3, 3);
  ASSERT_TRUE(miura.ok()) << miura.message();
  Paper paper = miura->paper;
  // Targets of ±90° from a file: creases at ±45° are half way there.
  for (size_t e = 0; e < paper.edges.size(); ++e)
    if (paper.edges[e].isCrease())
    {
      paper.edges[e].target_angle = 0.5 * miura->target_fold_angle[e];
      paper.edges[e].fold_angle = 0.25 * miura->target_fold_angle[e];
    }
  EXPECT_NEAR(foldFraction(paper), 0.5, 1e-12);
  for (Edge& e : paper.edges)
    e.fold_angle = -e.fold_angle;  // every crease the other way: the opposite assignment half way
  EXPECT_NEAR(foldFraction(paper), -0.5, 1e-12);
  for (Edge& e : paper.edges)
    e.fold_angle = e.target_angle ? 3 * *e.target_angle : 0.0;  // past the targets
  EXPECT_EQ(foldFraction(paper), 1.0);
  for (Edge& e : paper.edges)
    e.fold_angle = -e.fold_angle;  // past the opposite targets
  EXPECT_EQ(foldFraction(paper), -1.0);
}

TEST(FoldFraction, AnUnfoldedSquareHasNoDrivenCrease)
{
  EXPECT_FALSE(hasDrivenCreases(Paper::square(1.0)));
  EXPECT_EQ(foldFraction(Paper::square(1.0)), 0.0);
}

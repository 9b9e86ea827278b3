#include <gtest/gtest.h>

#include <cmath>

#include "test_models.h"
#include "virtual_origami/core/metrics.h"
#include "virtual_origami/core/reference_patterns.h"

using namespace virtual_origami::core;
using namespace virtual_origami::core::test;

TEST(Metrics, AFlatSheetIsExact)
{
  const Paper paper = Paper::square(2.0);
  const ShapeMetrics m = measureShape(paper);
  EXPECT_EQ(m.strain.max, 0.0);
  EXPECT_EQ(m.strain.pairs, 6);  // every pair of the square's four corners
  EXPECT_EQ(m.planarity, 0.0);
  EXPECT_LT(m.shape_residual, 1e-15);
  EXPECT_EQ(m.force_residual, 0.0);
}

TEST(Metrics, StrainCountsEveryVertexPairOfAFace)
{
  Paper paper = Paper::square(1.0);
  paper.vertices[2].folded = p3(1.1, 1.1);
  // The diagonal 0–2 stretches by 10 %, the sides 1–2 and 2–3 by |(0.1, 1.1)| − 1 each, the
  // other three pairs not at all.
  const double side = std::hypot(0.1, 1.1) - 1;
  const StrainStats s = edgeStrain(paper);
  EXPECT_NEAR(s.max, side, 1e-12);
  EXPECT_NEAR(s.mean, (0.1 + 2 * side) / 6, 1e-12);
}

TEST(Metrics, PlanarityIsTheLargestDistanceFromTheBestPlane)
{
  Paper paper = Paper::square(1.0);
  paper.vertices[0].folded.z() = 0.01;
  paper.vertices[2].folded.z() = 0.01;
  // Least-squares plane through the twisted square: z = 0.005, every corner 0.005 off.
  EXPECT_NEAR(facePlanarity(paper, 0), 0.005, 1e-6);
  EXPECT_NEAR(measureShape(paper).planarity, 0.005, 1e-6);
}

TEST(Metrics, ForceResidualSkipsFixedVertices)
{
  Paper paper = Paper::square(1.0);
  paper.vertices[2].folded = p3(1.1, 1.1);
  EXPECT_GT(forceResidual(paper), 0.09);
  std::vector<char> fixed(4, 1);
  EXPECT_EQ(forceResidual(paper, fixed), 0.0);
}

TEST(Metrics, FoldAnglesAreMeasuredOnTheirBranch)
{
  Paper paper = stackOfLayers(1);
  const std::vector<double> angles = measuredFoldAngles(paper);
  for (size_t e = 0; e < paper.edges.size(); ++e)
  {
    if (paper.edges[e].isCrease())
      EXPECT_NEAR(angles[e], M_PI, 1e-12);  // +180° stays +180°, not −180°
    else
      EXPECT_EQ(angles[e], 0.0);
  }
}

// What lies under a point of a folded stack, the layer the eye sees first (SPEC §3.8).
#include <gtest/gtest.h>

#include <set>

#include "test_models.h"
#include "virtual_origami/core/layer_pick.h"
#include "virtual_origami/core/layers.h"

using namespace virtual_origami::core;
using namespace virtual_origami::core::test;

namespace
{
const Vec3 kFromAbove(0, 0, -1), kFromBelow(0, 0, 1);

/// Stack levels along the list: each one strictly below the one before (seen from above).
void expectTopFirst(const Paper& paper, const std::vector<int>& faces)
{
  const std::vector<int> levels = stackLevels(paper);
  for (size_t i = 1; i < faces.size(); ++i)
    EXPECT_GT(levels[faces[i - 1]], levels[faces[i]]) << "at " << i;
}
}  // namespace

TEST(LayerPick, OneSheetHasOneLayerUnderAnyPoint)
{
  const Paper paper = Paper::square(1.0);
  EXPECT_EQ(facesUnder(paper, p3(0.3, 0.7, 0.1), kFromAbove).size(), 1u);
  EXPECT_TRUE(facesUnder(paper, p3(1.3, 0.7, 0.1), kFromAbove).empty());  // off the sheet
}

TEST(LayerPick, AFourLayerStackListsEveryLayerTopFirstAndBottomFirstFromBelow)
{
  const Paper paper = stackOfLayers(2);  // four layers over [0, .5]²
  const std::vector<int> above = facesUnder(paper, p3(0.2, 0.3, 0.05), kFromAbove);
  ASSERT_EQ(above.size(), 4u);
  EXPECT_EQ(std::set<int>(above.begin(), above.end()).size(), 4u);
  expectTopFirst(paper, above);
  const std::vector<int> below = facesUnder(paper, p3(0.2, 0.3, -0.05), kFromBelow);
  EXPECT_EQ(below, std::vector<int>(above.rbegin(), above.rend()));
}

TEST(LayerPick, CoincidentCreasesOfAStackAreListedByLayer)
{
  const Paper paper = stackOfLayers(2);
  // The first fold's crease x = .5, cut in two by the second fold, lies folded along x = .5 twice.
  const std::vector<int> creases = creasesUnder(paper, p3(0.5, 0.25, 0.05), kFromAbove, 0.01);
  ASSERT_EQ(creases.size(), 2u);
  const std::vector<int> levels = stackLevels(paper);
  const auto top = [&](int e) {
    return std::max(levels[paper.edges[e].faces[0]], levels[paper.edges[e].faces[1]]);
  };
  EXPECT_GT(top(creases[0]), top(creases[1]));
  for (int e : creases)
    for (int v : paper.edges[e].vertices)
      EXPECT_NEAR(paper.vertices[v].crease_pattern.x(), 0.5, 1e-12);
  // Away from every crease: none.
  EXPECT_TRUE(creasesUnder(paper, p3(0.2, 0.2, 0.05), kFromAbove, 0.01).empty());
}

TEST(LayerPick, VerticesUnderAPointAreTheStackedCornersNearestFirstInEachLayer)
{
  const Paper paper = stackOfLayers(2);
  // Over the folded corner (0, 0): the sheet's corners (0,0), (1,0), (0,1), (1,1) all lie there.
  const std::vector<int> corners = verticesUnder(paper, p3(0.001, 0.001, 0.05), kFromAbove, 0.01);
  ASSERT_EQ(corners.size(), 4u);
  std::set<std::pair<double, double>> at;
  for (int v : corners)
    at.insert({ paper.vertices[v].crease_pattern.x(), paper.vertices[v].crease_pattern.y() });
  EXPECT_EQ(at, (std::set<std::pair<double, double>>{ { 0, 0 }, { 1, 0 }, { 0, 1 }, { 1, 1 } }));
}

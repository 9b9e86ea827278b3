// What lies under a point of a folded stack, the layer the eye sees first (SPEC §3.8).
#include <gtest/gtest.h>

#include <set>

#include "crane_reference.h"
#include "test_models.h"
#include "virtual_origami/core/drag.h"
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

/// rviz's default view (rviz/origami.rviz): the eye of an orbit about (0.5, 0.45, 0.1), 1.7 m
/// away, yaw 4.2, pitch 0.75.
Vec3 defaultEye()
{
  const double yaw = 4.2, pitch = 0.75, distance = 1.7;
  return Vec3(0.5, 0.45, 0.1) +
         distance * Vec3(std::cos(yaw) * std::cos(pitch), std::sin(yaw) * std::cos(pitch), std::sin(pitch));
}

/// The creases of `list` that lie on the folded line of crease `edge`.
std::vector<int> onTheLineOf(const Paper& paper, int edge, const std::vector<int>& list)
{
  const Vec3& a = paper.vertices[paper.edges[edge].vertices[0]].folded;
  const Vec3 d = (paper.vertices[paper.edges[edge].vertices[1]].folded - a).normalized();
  const auto off = [&](int v) {
    const Vec3 r = paper.vertices[v].folded - a;
    return (r - r.dot(d) * d).norm();
  };
  std::vector<int> out;
  for (int e : list)
    if (off(paper.edges[e].vertices[0]) < 1e-9 && off(paper.edges[e].vertices[1]) < 1e-9)
      out.push_back(e);
  return out;
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

TEST(LayerPick, StackedCreasesAreListedTopFirstWhicheverSideOfTheLineIsClicked)
{
  // Issue 42: a click beside a stacked crease of the square base listed its creases in one
  // order from one side of the line and in another from the other (coincident creases told
  // apart by their distances' rounding). Every stacked line of the square base and the bird
  // base, clicked 15 mm (8 px in the default view) to each side, from the default view, from
  // above and from below.
  const Expected<std::vector<Paper>> states = craneStates();
  ASSERT_TRUE(states.ok()) << states.message();
  const Vec3 eye = defaultEye();
  for (const size_t step : { 8, 13 })
  {
    const Paper& paper = (*states)[step];
    const std::vector<int> levels = stackLevels(paper);
    int stacked = 0;
    for (size_t e = 0; e < paper.edges.size(); ++e)
    {
      const Edge& edge = paper.edges[e];
      const Vec3& a = paper.vertices[edge.vertices[0]].folded;
      const Vec3& b = paper.vertices[edge.vertices[1]].folded;
      if (!edge.isCrease() || (b - a).norm() < 0.05)
        continue;
      const Vec3 across = Vec3::UnitZ().cross(b - a).normalized();
      for (int view = 0; view < 3; ++view)
      {
        SCOPED_TRACE("step " + std::to_string(step) + ", crease " + std::to_string(e) + ", view " +
                     std::to_string(view));
        std::vector<int> sides[2];
        Vec3 sight;
        for (int side = 0; side < 2; ++side)
        {
          const Vec3 beside = 0.5 * (a + b) + (side == 0 ? -0.015 : 0.015) * across;
          sight = view == 0 ? Vec3((beside - eye).normalized()) : view == 1 ? kFromAbove : kFromBelow;
          const Vec3 clicked = onSurface(paper, beside - 0.5 * sight, sight);
          sides[side] = onTheLineOf(paper, static_cast<int>(e), creasesUnder(paper, clicked, sight, 0.03));
        }
        if (sides[0].size() < 2)
          continue;
        ++stacked;
        EXPECT_EQ(sides[0], sides[1]);
        // Top first: the layers each crease joins, the nearer one to the eye first.
        for (size_t i = 1; i < sides[0].size(); ++i)
        {
          const auto joins = [&](int c) {
            const int l0 = levels[paper.edges[c].faces[0]], l1 = levels[paper.edges[c].faces[1]];
            return sight.z() < 0 ? std::make_pair(-std::max(l0, l1), -std::min(l0, l1)) :
                                   std::make_pair(std::min(l0, l1), std::max(l0, l1));
          };
          EXPECT_LE(joins(sides[0][i - 1]), joins(sides[0][i])) << "at " << i;
        }
      }
    }
    EXPECT_GT(stacked, 20) << "step " << step;
  }
}

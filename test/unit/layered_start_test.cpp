// The layered start (layered_start.h): a folded model's stacked layers lifted apart by their
// order, hinges set out, the sheet's raw edges drawn back, so that contact with a barrier can
// start from it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "folded_crane.h"
#include "virtual_origami/curved/bubble_mesh.h"
#include "virtual_origami/curved/contact.h"
#include "virtual_origami/curved/curved_metrics.h"
#include "virtual_origami/curved/layered_start.h"
#include "virtual_origami/curved/mesh_distance.h"
#include "virtual_origami/curved/seed_scenes.h"

using namespace virtual_origami::core;

namespace
{
CurvedMesh stripMesh(const Paper& paper, double spacing)
{
  BubbleMeshOptions options;
  options.spacing = spacing;
  options.crease_strip = LayeredStartOptions().stripFor(paper);
  Expected<CurvedMesh> mesh = bubbleMesh(paper, options);
  EXPECT_TRUE(mesh.ok()) << mesh.message();
  return *mesh;
}

}  // namespace

TEST(LayeredStart, AFlapFoldedOverLiesAGapAboveTheSheetWithNothingTouching)
{
  // Seed scene 3: the triangle ade folded over onto the sheet on de.
  const Expected<SeedScene> scene = seedScene(3, 1.0, 2e-3);
  ASSERT_TRUE(scene.ok()) << scene.message();
  const Paper& paper = scene->paper;
  const CurvedMesh mesh = stripMesh(paper, 0.1);
  const LayeredStartOptions options;
  const double gap = options.gapFor(paper);
  const LayeredStart start = layeredStart(mesh, paper, options);

  ASSERT_EQ(start.planes, 1);
  int lifted = 0;
  for (size_t f = 0; f < paper.faces.size(); ++f)
    lifted += start.levels[f];
  EXPECT_EQ(lifted, 1);  // the flap one level up, the sheet below it

  // Placed as folded, each node off by at most the lift and the strip.
  const Positions placed = placeNodes(mesh, paper);
  for (int i = 0; i < placed.cols(); ++i)
    EXPECT_LT((start.positions.col(i) - placed.col(i)).norm(), options.stripFor(paper) + 2 * gap);
  // Apart everywhere: no two elements that share no node nearer than a part of the lift;
  // without it they touch (0 apart) all over the flap.
  EXPECT_GT(closestApproach(mesh, start.positions, 10 * gap).distance, 0.2 * gap);
  EXPECT_LT(closestApproach(mesh, placed, 10 * gap).distance, 1e-3 * gap);
  const CurvedMetrics metrics = measureCurved(mesh, paper, start.positions, 1e-12);
  EXPECT_EQ(metrics.penetrations, 0);
  EXPECT_LT(metrics.strain.max, 1e-2);
}

TEST(LayeredStart, TheCranesTwelveLayersLiftApartExceptAtTheCornersWhereCreasesMeet)
{
  const Paper crane = foldedCrane();
  const CurvedMesh mesh = stripMesh(crane, 0.05);
  const LayeredStartOptions options;
  const double gap = options.gapFor(crane), strip = options.stripFor(crane);
  const LayeredStart start = layeredStart(mesh, crane, options);

  // The body's stack and the wings' plane.
  EXPECT_EQ(start.planes, 2);
  EXPECT_EQ(*std::max_element(start.levels.begin(), start.levels.end()), 11);
  const CurvedMetrics metrics = measureCurved(mesh, crane, start.positions, 1e-3 * gap);
  EXPECT_LT(metrics.strain.max, 1e-2);
  // Triangles still crossing (81 pairs of 2,088 triangles) lie next to paper vertices, within a
  // few strips' widths of one, where the hinges of several folds at several levels meet;
  // contact must leave such pairs alone until they part.
  const std::vector<std::array<int, 2>> crossings = findTriangleCrossings(mesh, start.positions, 1e-3 * gap);
  EXPECT_LE(crossings.size(), 100u);
  for (const auto& pair : crossings)
  {
    double nearest = INFINITY;
    for (int t : pair)
      for (int n : mesh.triangles[t].nodes)
        for (const Vertex& v : crane.vertices)
          nearest = std::min(nearest, (start.positions.col(n) - v.folded).norm());
    EXPECT_LT(nearest, 4 * strip) << "triangles " << pair[0] << " and " << pair[1];
  }
  // Laid as folded, the layers lie on each other: 0 apart.
  EXPECT_LT(closestApproach(mesh, placeNodes(mesh, crane), 10 * gap).distance, 1e-3 * gap);
}

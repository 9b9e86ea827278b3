// Seed scene 1 (corner a turned towards c) against a reference that is itself balanced and
// converged (issue 21): the curl on each finer bubble mesh comes nearer the finest one's, about
// as fast as the spacing falls. The same scene is mesh_bench's resolution chart.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "virtual_origami/core/geometry.h"
#include "virtual_origami/curved/bubble_mesh.h"
#include "virtual_origami/curved/seed_scenes.h"

namespace virtual_origami::core
{
namespace
{
/// The sheet's shape at a 21 × 21 grid of points of the paper, wherever its nodes are.
Positions curlAt(double spacing)
{
  const Expected<SeedScene> scene = seedScene(1);
  BubbleMeshOptions mesh_options;
  mesh_options.spacing = spacing;
  const Expected<CurvedMesh> mesh = bubbleMesh(scene->paper, mesh_options);
  EXPECT_TRUE(mesh.ok()) << mesh.message();
  const SeedSceneRun run = runSeedSceneOn(*scene, *mesh, refinementPullOptions());
  // Every step balanced to 1e-11 and stable (check_stability), no layer through another.
  EXPECT_TRUE(run.passed()) << "spacing " << spacing;
  for (const SeedSceneStep& step : run.steps)
    EXPECT_LE(step.report.max_force, 1e-11) << "spacing " << spacing << " at " << step.fraction;
  // The sheet has curled (a plate kept flat costs no bending).
  EXPECT_GT(run.steps.back().report.energy.bend, 1e-4) << "spacing " << spacing;
  return sheetOnGrid(run.mesh, run.positions, scene->paper.scale());
}

TEST(SeedSceneRefinement, EachFinerMeshBringsTheCurlNearerAtFirstOrder)
{
  const Positions reference = curlAt(0.035);
  std::vector<double> distance;
  for (double spacing : { 0.2, 0.1, 0.05 })
  {
    distance.push_back(shapeDistance(curlAt(spacing), reference).rms);
    RecordProperty("rms_distance_at_" + std::to_string(spacing), std::to_string(distance.back()));
  }
  // Each halving of the spacing brings the curl nearer the reference; and at first order (an
  // error of C·h) the distance, between C·(h − 0.035) and C·(h + 0.035) with the reference's own
  // error, falls from spacing 0.2 to 0.05 to at most 0.085/0.165 of what it was.
  EXPECT_LT(distance[1], distance[0]);
  EXPECT_LT(distance[2], distance[1]);
  EXPECT_LT(distance[2], (0.085 / 0.165) * distance[0]) << distance[0] << " → " << distance[2];
}
}  // namespace
}  // namespace virtual_origami::core

// A small curved sheet the curved-solver tests compare methods on: the unit square, three
// corners held flat, the fourth lifted.
#pragma once

#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "virtual_origami/curved/bubble_mesh.h"
#include "virtual_origami/curved/curved_solver.h"

namespace virtual_origami::core::test
{
struct CornerLift
{
  Paper paper = Paper::square(1.0);
  CurvedMesh mesh;
  std::vector<CurvedPin> pins;
};

/// Meshed at `spacing` (bubble mesh), corner 0 lifted by `lift` along z.
inline CornerLift cornerLift(double spacing, double lift)
{
  CornerLift scene;
  BubbleMeshOptions options;
  options.spacing = spacing;
  Expected<CurvedMesh> mesh = bubbleMesh(scene.paper, options);
  EXPECT_TRUE(mesh.ok()) << mesh.message();
  scene.mesh = std::move(*mesh);
  for (int v = 1; v < 4; ++v)
    scene.pins.push_back({ scene.mesh.vertex_nodes[v], scene.paper.vertices[v].folded });
  scene.pins.push_back({ scene.mesh.vertex_nodes[0], scene.paper.vertices[0].folded + lift * Vec3::UnitZ() });
  return scene;
}
}  // namespace virtual_origami::core::test

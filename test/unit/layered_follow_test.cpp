// A curved sheet following pins on a folded model with its layers lifted apart and kept apart
// by the barrier (CurvedFollowOptions::layered), as curved_mesh_solver runs it with `layers`:
// the folded crane of sequences/crane.json at rest as drawn, then its wing tips pulled apart.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "folded_crane.h"
#include "virtual_origami/curved/bubble_mesh.h"
#include "virtual_origami/curved/contact.h"
#include "virtual_origami/curved/curved_follow.h"
#include "virtual_origami/curved/layered_start.h"

using namespace virtual_origami::core;

TEST(LayeredFollow, TheFoldedCraneRestsAsDrawnAndItsWingTipsPullApartWithNoLayerPassingAnother)
{
  const Paper crane = foldedCrane();
  CurvedFollowOptions options;
  options.layered = true;
  options.material.crease = 10;
  options.solve.modified_newton_rate = 0;
  options.solve.damping = 1e-4;
  options.solve.max_iterations = 300;
  options.max_pin_step = 0.01;
  const double gap = layersFor(crane, options.layer_gap).gapFor(crane);
  CurvedSheetFollower follower(
      [&](const Paper& paper) {
        BubbleMeshOptions meshing;
        meshing.spacing = 0.05 * paper.scale();
        meshing.crease_strip = layersFor(paper, options.layer_gap).stripFor(paper);
        return bubbleMesh(paper, meshing);
      },
      options);
  const int tip0 = crane.vertexAt({ 0, 0 }), tip1 = crane.vertexAt({ 1, 1 });
  ASSERT_GE(tip0, 0);
  ASSERT_GE(tip1, 0);
  const Vec3 p0 = crane.vertices[tip0].folded, p1 = crane.vertices[tip1].folded;
  const Vec3 apart = (p1 - p0).normalized();

  // Held where the model has the tips: the sheet stays as the layered start draws it, layers
  // apart (the pins move the tips' nodes by as much as they move the vertices, from the few
  // gaps the start drew them off the model's).
  Expected<CurvedReport> report = follower.solveState(crane, { { tip0, p0 }, { tip1, p1 } });
  ASSERT_TRUE(report.ok()) << report.message();
  EXPECT_TRUE(report->converged) << report->message;
  const int start_crossings = countPenetrations(follower.mesh(), follower.positions(), gap);
  const Positions rest = follower.positions();

  // Pulled 0.004 apart, in steps of a hundredth of the spacing: balanced, no layer through
  // another, and the body's stack, 11 gaps across as drawn, opened to over 0.003.
  report = follower.follow({ { tip0, Vec3(p0 - 0.002 * apart) }, { tip1, Vec3(p1 + 0.002 * apart) } });
  ASSERT_TRUE(report.ok()) << report.message();
  EXPECT_TRUE(report->converged) << report->message;
  EXPECT_LE(countPenetrations(follower.mesh(), follower.positions(), gap), start_crossings);
  const LayeredStart layers = layeredStart(follower.mesh(), crane, layersFor(crane, options.layer_gap));
  auto bodySpread = [&](const Positions& at) {
    return stackThickness(follower.mesh(), crane, layers, layers.plane_of[0], at);
  };
  double held_off = 0.0;  // how far holding the tips where the model has them moved the sheet
  for (int i = 0; i < rest.cols(); ++i)
    held_off = std::max(held_off, (rest.col(i) - layers.positions.col(i)).norm());
  EXPECT_LT(bodySpread(layers.positions), 12 * gap);
  EXPECT_LT(held_off, 1e-12);  // held where the model has the tips, the sheet rests as drawn
  EXPECT_GT(bodySpread(follower.positions()), 0.003);
}

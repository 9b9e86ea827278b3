// The curved model of a kept bend (issue 38): a kept sheet's facets are paper bent, not creases,
// so the curved model that meshes the kept paper holds them at the bend they were kept with.
// Started flat, the sheet bends back into the kept shape (the closed form of bent_strips.h);
// before, its facets turned freely and a kept corner fell away when the curved model solved it.
#include <gtest/gtest.h>

#include <cmath>

#include "bent_strips.h"
#include "virtual_origami/core/compliant_faces.h"
#include "virtual_origami/core/kept_bend.h"
#include "virtual_origami/curved/bubble_mesh.h"
#include "virtual_origami/curved/curved_solver.h"

using namespace virtual_origami::core;

TEST(CurvedKeptBend, AKeptSheetStartedFlatBendsBackIntoTheShapeItWasKeptIn)
{
  constexpr double kFrom = 0.5, kTurn = 0.2;
  Paper paper = Paper::square(1.0);
  const Expected<KeptBend> kept = keepBend(paper, test::stripsBentFrom(kFrom, 8, kTurn));
  ASSERT_TRUE(kept.ok()) << kept.message();

  BubbleMeshOptions mesh_options;
  mesh_options.spacing = 0.1;
  const Expected<CurvedMesh> mesh = bubbleMesh(paper, mesh_options);
  ASSERT_TRUE(mesh.ok()) << mesh.message();
  const Positions shape = placeNodes(*mesh, paper);  // the kept shape: every kept triangle rigid

  // Every node where the sheet lies flat, the half left of kFrom pinned where it was kept (it
  // did not bend): the rest must bend back by itself.
  Positions x = shape;
  std::vector<CurvedPin> pins;
  for (size_t n = 0; n < mesh->nodes.size(); ++n)
  {
    const Vec2 at = mesh->nodes[n].crease_pattern;
    x.col(static_cast<Eigen::Index>(n)) = Vec3(at.x(), at.y(), 0.0);
    if (at.x() < kFrom - 1e-9)
      pins.push_back({ static_cast<int>(n), shape.col(static_cast<Eigen::Index>(n)) });
  }
  ASSERT_GT((x - shape).cwiseAbs().maxCoeff(), 0.1);
  CurvedSolveOptions options;
  options.max_iterations = 500;
  // Balanced to 1e-11 of an edge's force: the bending stiffness is a millionth of the stretch, so
  // the default 1e-8 would leave the shape some 1e-5 off its balance.
  options.tolerance = 1e-11;
  CurvedSolver solver(*mesh, paper, CurvedMaterial{}, ContactOptions{}, options);
  const CurvedReport report = solver.solve(x, pins);
  ASSERT_TRUE(report.converged) << report.message;
  // The strips' far corner, (1, 1), turned through every strip's bend: where the closed form has it.
  const Vec3 far = paper.vertices[2].folded;
  const Vec3 closed_form = test::stripsBentFrom(kFrom, 8, kTurn).positions.back();
  EXPECT_LT((far - closed_form).norm(), 1e-12);
  EXPECT_LT((x.col(mesh->vertex_nodes[2]) - closed_form).norm(), 1e-6);
  EXPECT_LT((x - shape).cwiseAbs().maxCoeff(), 1e-6);
}

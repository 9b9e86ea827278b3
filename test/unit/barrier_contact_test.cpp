// Barrier contact (barrier_contact.h): the first time of contact along a motion against closed
// forms, and the folded crane's wing tips pulled apart on it from the layered start — its body
// opening with no layer passing another.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>

#include "folded_crane.h"
#include "virtual_origami/curved/barrier_contact.h"
#include "virtual_origami/curved/bubble_mesh.h"
#include "virtual_origami/curved/contact.h"
#include "virtual_origami/curved/curved_solver.h"
#include "virtual_origami/curved/layered_start.h"
#include "virtual_origami/curved/mesh_distance.h"

using namespace virtual_origami::core;

TEST(Impact, APointFallingThroughATriangleMeetsItWhereItReachesItsPlane)
{
  const Vec3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0), still(0, 0, 0);
  const double h = 1e-6;
  // From h above to 3h below: the plane at a quarter of the motion.
  EXPECT_NEAR(pointTriangleImpact(Vec3(0.2, 0.2, h), a, b, c, Vec3(0, 0, -4 * h), still, still, still, 1e-12), 0.25,
              1e-12);
  // The triangle rising to meet it instead: the same time.
  const Vec3 up(0, 0, 4 * h);
  EXPECT_NEAR(pointTriangleImpact(Vec3(0.2, 0.2, h), a, b, c, still, up, up, up, 1e-12), 0.25, 1e-12);
  // Passing the plane beside the triangle: no contact.
  EXPECT_EQ(pointTriangleImpact(Vec3(0.8, 0.8, h), a, b, c, Vec3(0, 0, -4 * h), still, still, still, 1e-12), 2.0);
}

TEST(Impact, ALayerAHairAboveAnotherSlidesAlongItFarWithoutContact)
{
  // A node 10⁻⁶ above a triangle slides 0.3 along it and sinks by half its height: no contact,
  // the whole step allowed. A bound by the distance over the motion allows 3 × 10⁻⁶ of it.
  const Vec3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0), still(0, 0, 0);
  const double h = 1e-6;
  EXPECT_EQ(pointTriangleImpact(Vec3(0.1, 0.1, h), a, b, c, Vec3(0.3, 0.2, -0.5 * h), still, still, still, 1e-12),
            2.0);
  // Sinking twice its height on the way: it meets the plane half way, inside the triangle.
  EXPECT_NEAR(pointTriangleImpact(Vec3(0.1, 0.1, h), a, b, c, Vec3(0.3, 0.2, -2 * h), still, still, still, 1e-12),
              0.5, 1e-9);
}

TEST(Impact, TwoEdgesMeetWhenTheyCrossInOnePlane)
{
  const double h = 1e-5;
  const Vec3 still(0, 0, 0), down(0, 0, -4 * h), along(3, 0, 0);
  // Edge (−1, 0, h)–(1, 0, h) sinking across edge (0, −1, 0)–(0, 1, 0): they meet at a quarter.
  EXPECT_NEAR(edgeEdgeImpact(Vec3(-1, 0, h), Vec3(1, 0, h), Vec3(0, -1, 0), Vec3(0, 1, 0), down, down, still, still,
                             1e-12),
              0.25, 1e-12);
  // Sliding along its own line above the other: never in its plane.
  EXPECT_EQ(edgeEdgeImpact(Vec3(-1, 0, h), Vec3(1, 0, h), Vec3(0, -1, 0), Vec3(0, 1, 0), along, along, still, still,
                           1e-12),
            2.0);
}

TEST(BarrierContact, WatchesEveryPairWithinItsReach)
{
  // The crane's layered start: every node–triangle and edge–edge pair sharing no node that lies
  // within the reach (brute force, by true distances) is among the watched pairs.
  const Paper crane = foldedCrane();
  LayeredStartOptions layers;
  layers.gap = 1e-5;
  BubbleMeshOptions meshing;
  meshing.spacing = 0.05;
  meshing.crease_strip = layers.stripFor(crane);
  const Expected<CurvedMesh> mesh = bubbleMesh(crane, meshing);
  ASSERT_TRUE(mesh.ok()) << mesh.message();
  const Positions x = layeredStart(*mesh, crane, layers).positions;
  const double reach = 3 * layers.gap;
  BarrierContact contact(*mesh, { reach, 1.0 });
  contact.update(x, nullptr, reach);
  const std::vector<std::array<int, 4>> watched = contact.pairNodes();
  const std::set<std::array<int, 4>> found(watched.begin(), watched.end());
  int near = 0;
  for (int v = 0; v < x.cols(); ++v)
    for (const MeshTriangle& t : mesh->triangles)
    {
      const auto& n = t.nodes;
      if (v == n[0] || v == n[1] || v == n[2] ||
          pointTriangleDistance(x.col(v), x.col(n[0]), x.col(n[1]), x.col(n[2])) >= reach)
        continue;
      ++near;
      EXPECT_TRUE(found.count({ v, n[0], n[1], n[2] })) << "node " << v << " and triangle " << n[0] << " " << n[1] << " " << n[2];
    }
  for (size_t a = 0; a < mesh->edges.size(); ++a)
    for (size_t b = a + 1; b < mesh->edges.size(); ++b)
    {
      const auto& p = mesh->edges[a].nodes;
      const auto& q = mesh->edges[b].nodes;
      if (p[0] == q[0] || p[0] == q[1] || p[1] == q[0] || p[1] == q[1] ||
          segmentDistance(x.col(p[0]), x.col(p[1]), x.col(q[0]), x.col(q[1])) >= reach)
        continue;
      ++near;
      EXPECT_TRUE(found.count({ p[0], p[1], q[0], q[1] })) << "edges " << a << " and " << b;
    }
  EXPECT_GT(near, 1000);  // the stacked layers lie a gap apart: many pairs are near
}

TEST(BarrierContact, TheCranesBodyOpensAsItsWingTipsArePulledApartWithNoLayerPassingAnother)
{
  const Paper crane = foldedCrane();
  // Layers 10⁻⁵ of the sheet apart, strips 120 gaps wide (layered_start.h).
  LayeredStartOptions layers;
  layers.gap = 1e-5;
  layers.strip = 120 * layers.gap;
  BubbleMeshOptions meshing;
  meshing.spacing = 0.05;
  meshing.crease_strip = layers.strip;
  const Expected<CurvedMesh> mesh = bubbleMesh(crane, meshing);
  ASSERT_TRUE(mesh.ok()) << mesh.message();
  const LayeredStart start = layeredStart(*mesh, crane, layers);

  CurvedMaterial material;
  material.crease = 10;  // creases remember their folded angles
  ContactOptions contact;
  contact.barrier = true;
  contact.barrier_activation = 0.5 * layers.gap;
  CurvedSolveOptions options;
  options.max_iterations = 200;
  options.modified_newton_rate = 0;  // a fresh Hessian every step: contact changes it
  options.damping = 1e-4;
  CurvedSolver solver(*mesh, crane, material, contact, options);
  solver.restTermsAt(start.positions);  // the folded model at rest as drawn

  // The wing tips, paper corners (0, 0) and (1, 1), pinched through all their layers.
  std::array<int, 2> tip{ -1, -1 };
  for (size_t v = 0; v < crane.vertices.size(); ++v)
  {
    const Vec2 c = crane.vertices[v].crease_pattern;
    if (c.norm() < 1e-9)
      tip[0] = mesh->vertex_nodes[v];
    if ((c - Vec2(1, 1)).norm() < 1e-9)
      tip[1] = mesh->vertex_nodes[v];
  }
  ASSERT_GE(std::min(tip[0], tip[1]), 0);
  const Positions& rest = start.positions;
  const Vec3 apart = (rest.col(tip[1]) - rest.col(tip[0])).normalized();
  Positions x = rest;
  // The body's stack: how far its nodes lie apart across its plane.
  auto bodySpread = [&](const Positions& at) { return stackThickness(*mesh, crane, start, start.plane_of[0], at); };
  const int start_crossings = countPenetrations(*mesh, rest, layers.gap);
  const double pull = 0.001;
  for (int k = 1; k <= 4; ++k)
  {
    std::vector<CurvedPin> pins;
    for (int i = 0; i < rest.cols(); ++i)
      for (int s = 0; s < 2; ++s)
        if ((rest.col(i) - rest.col(tip[s])).norm() <= 0.03)
          pins.push_back({ i, Vec3(rest.col(i) + (s == 0 ? -0.5 : 0.5) * k * pull * apart) });
    const CurvedReport report = solver.solve(x, pins);
    ASSERT_TRUE(report.converged) << "pull " << k << ": " << report.message;
    // No edge passes through a triangle by more than the gap between two layers beyond what
    // the start had where hinges meet at paper vertices.
    EXPECT_LE(countPenetrations(*mesh, x, layers.gap), start_crossings) << "pull " << k;
  }
  // Pulled 0.004 apart, the body's layers have opened: its stack is several times as thick
  // as the twelve layers lying on each other (11 gaps).
  EXPECT_LT(bodySpread(rest), 12 * layers.gap);
  EXPECT_GT(bodySpread(x), 0.003);
}

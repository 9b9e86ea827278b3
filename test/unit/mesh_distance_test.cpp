// Distances between mesh elements (mesh_distance.h) against their closed forms, and the
// closest approach of two sheets.
#include <gtest/gtest.h>

#include <cmath>

#include "virtual_origami/curved/mesh_distance.h"

using namespace virtual_origami::core;

TEST(MeshDistance, PointToTriangleByItsNearestFeature)
{
  const Vec3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
  EXPECT_NEAR(pointTriangleDistance(Vec3(0.2, 0.2, 0.3), a, b, c), 0.3, 1e-15);     // over the face
  EXPECT_NEAR(pointTriangleDistance(Vec3(0.5, -0.4, 0.3), a, b, c), 0.5, 1e-15);    // beside side ab
  EXPECT_NEAR(pointTriangleDistance(Vec3(1, 1, 0), a, b, c), std::sqrt(0.5), 1e-15);  // beside side bc
  EXPECT_NEAR(pointTriangleDistance(Vec3(-3, -4, 0), a, b, c), 5.0, 1e-15);         // past corner a
  EXPECT_NEAR(pointTriangleDistance(Vec3(2, 0, 0), a, b, c), 1.0, 1e-15);           // past corner b
  EXPECT_EQ(pointTriangleDistance(Vec3(0.25, 0.25, 0), a, b, c), 0.0);              // in it
}

TEST(MeshDistance, SegmentsCrossingParallelAndEndToEnd)
{
  // Crossing lines 0.5 apart along z.
  EXPECT_NEAR(segmentDistance(Vec3(-1, 0, 0), Vec3(1, 0, 0), Vec3(0, -1, 0.5), Vec3(0, 1, 0.5)), 0.5, 1e-15);
  // Their nearest points beyond an end: from the end (1, 0, 0) to the other line.
  EXPECT_NEAR(segmentDistance(Vec3(-1, 0, 0), Vec3(1, 0, 0), Vec3(3, -1, 0), Vec3(3, 1, 0)), 2.0, 1e-15);
  // Parallel, overlapping: their separation; parallel end to end: the gap between the ends.
  EXPECT_NEAR(segmentDistance(Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(1, 0.25, 0), Vec3(3, 0.25, 0)), 0.25, 1e-15);
  EXPECT_NEAR(segmentDistance(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1.5, 0, 0), Vec3(2.5, 0, 0)), 0.5, 1e-15);
}

TEST(MeshDistance, TwoSheetsApartByTheirSeparation)
{
  // Two unit squares of two triangles each, one 1e-6 above the other and shifted along it.
  CurvedMesh mesh;
  mesh.nodes.resize(8);
  Positions x(3, 8);
  for (int k = 0; k < 2; ++k)
  {
    const double z = k * 1e-6, shift = k * 0.3;
    const Vec3 corners[4] = { { shift, 0, z }, { 1 + shift, 0, z }, { 1 + shift, 1, z }, { shift, 1, z } };
    for (int i = 0; i < 4; ++i)
      x.col(4 * k + i) = corners[i];
    mesh.triangles.push_back({ { 4 * k, 4 * k + 1, 4 * k + 2 }, k });
    mesh.triangles.push_back({ { 4 * k, 4 * k + 2, 4 * k + 3 }, k });
    for (const auto& e : { std::array<int, 2>{ 0, 1 }, { 1, 2 }, { 2, 3 }, { 3, 0 }, { 0, 2 } })
    {
      MeshEdge edge;
      edge.nodes = { 4 * k + e[0], 4 * k + e[1] };
      mesh.edges.push_back(edge);
    }
  }
  const ClosestApproach near = closestApproach(mesh, x, 1e-3);
  EXPECT_NEAR(near.distance, 1e-6, 1e-15);
  // Lying in one plane, overlapping: they touch.
  x.row(2).setZero();
  EXPECT_LT(closestApproach(mesh, x, 1e-3).distance, 1e-15);
  // Far apart: the nearest pair lies within a sheet, a corner and the triangle across the
  // diagonal from it (√½).
  x.row(2).tail(4).setConstant(1.0);
  EXPECT_NEAR(closestApproach(mesh, x, 1e-3).distance, std::sqrt(0.5), 1e-15);
}

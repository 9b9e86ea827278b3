// The seed's spring scheme: where it converges, how far, and where it must diverge.
#include <gtest/gtest.h>

#include <cmath>

#include "test_models.h"
#include "virtual_origami/core/metrics.h"
#include "virtual_origami/core/reference_patterns.h"
#include "virtual_origami/core/rotate.h"
#include "virtual_origami/solvers/seed_spring_solver.h"

using namespace virtual_origami::core;
using namespace virtual_origami::core::test;

namespace
{
/// One face: a regular n-gon of circumradius 1.
Paper polygon(int n)
{
  std::vector<Vec2> vertices;
  std::vector<int> cycle;
  for (int k = 0; k < n; ++k)
  {
    vertices.emplace_back(std::cos(2 * M_PI * k / n), std::sin(2 * M_PI * k / n));
    cycle.push_back(k);
  }
  Expected<Paper> paper = patternPaper(vertices, { cycle });
  EXPECT_TRUE(paper.ok()) << paper.message();
  return *paper;
}

/// Moves every vertex by a small fixed pseudo-random amount (deterministic); `lift` scales the
/// part out of the sheet's plane.
void disturb(Paper& paper, double size, double lift = 1.0)
{
  for (size_t v = 0; v < paper.vertices.size(); ++v)
  {
    const double k = static_cast<double>(v);
    paper.vertices[v].folded +=
        size * Vec3(std::sin(3.1 * k + 0.3), std::cos(1.7 * k + 0.1), lift * std::sin(2.3 * k + 1.1));
  }
}

/// A degree-4 vertex whose four faces are sectors with `arc` extra boundary vertices each
/// (faces of arc + 3 vertices).
Paper degree4WithArcs(int arc)
{
  const std::array<double, 4> sectors{ M_PI / 3, 4 * M_PI / 9, 2 * M_PI / 3, 5 * M_PI / 9 };
  std::vector<Vec2> vertices{ Vec2::Zero() };
  std::vector<std::vector<int>> faces(4);
  double start = 0;
  for (int k = 0; k < 4; ++k)
  {
    faces[k].push_back(0);
    for (int a = 0; a <= arc; ++a)
    {
      const double angle = start + sectors[k] * a / (arc + 1);
      faces[k].push_back(static_cast<int>(vertices.size()));
      vertices.emplace_back(std::cos(angle), std::sin(angle));
    }
    start += sectors[k];
  }
  for (int k = 0; k < 4; ++k)
    faces[k].push_back(faces[(k + 1) % 4][1]);
  Expected<Paper> paper = patternPaper(vertices, faces);
  EXPECT_TRUE(paper.ok()) << paper.message();
  return *paper;
}
}  // namespace

TEST(SeedSpring, StabilityLimitIsTheSeedConstants)
{
  EXPECT_DOUBLE_EQ(seedStabilityLimit(SeedSpringOptions{}), 10.0);  // d λ Δt² < 2
  SeedSpringOptions carried;
  carried.velocity_carry = 1.0;
  EXPECT_DOUBLE_EQ(seedStabilityLimit(carried), 20.0);
}

TEST(SeedSpring, AnNGonHasStiffnessN)
{
  for (int n : { 3, 4, 7, 12 })
  {
    const Paper paper = polygon(n);
    EXPECT_NEAR(springStiffnessMax(paper, {}, 2000), restStiffnessBound(n), 1e-6) << n;
  }
}

TEST(SeedSpring, ConvergesBelowItsBound)
{
  // In the face's plane: a flat face's springs have no stiffness across it to first order, so
  // a lifted vertex creeps back sublinearly (see ReachableAccuracyIsReported).
  Paper paper = polygon(9);  // λ = 9 < 10
  disturb(paper, 1e-3, 0.0);
  SeedSpringSolver solver;
  const SolveReport report = solver.solve(paper, {});
  EXPECT_TRUE(report.converged) << report.message;
  EXPECT_FALSE(report.diverged);
  EXPECT_LT(edgeStrain(paper).max, solver.limits().tolerance * (1 + 1e-9));
}

TEST(SeedSpring, DivergesAboveItsBoundAndRollsBack)
{
  Paper paper = polygon(12);  // λ = 12 > 10: the dilation mode grows by |1 − 0.2·12| = 1.4 a step
  disturb(paper, 1e-3, 0.0);
  ASSERT_GT(springStiffnessMax(paper, {}), seedStabilityLimit(SeedSpringOptions{}));
  const Paper before = paper;
  SeedSpringSolver solver;
  const SolveReport report = solver.solve(paper, {});
  EXPECT_TRUE(report.diverged);
  EXPECT_FALSE(report.converged);
  EXPECT_NE(report.message.find("diverged"), std::string::npos) << report.message;
  EXPECT_TRUE(paper == before);  // rolled back bit for bit
}

TEST(SeedSpring, ARotationItCannotFinishChangesNothing)
{
  // Faces of 12 vertices: turning one drags the rest through the seed scheme, which diverges.
  Paper paper = degree4WithArcs(9);
  expectValid(paper);
  const int crease1 = paper.findEdge(0, 1);
  ASSERT_GE(crease1, 0);
  RotateRequest request;
  request.face = 3;
  request.axis_edge = crease1;
  request.angle = 0.5;
  const Paper before = paper;
  SeedSpringSolver solver;
  const Expected<RotateResult> result = rotate(paper, request, &solver);
  ASSERT_FALSE(result.ok());
  EXPECT_NE(result.message().find("diverged"), std::string::npos) << result.message();
  EXPECT_TRUE(paper == before);
}

TEST(SeedSpring, ReachableAccuracyIsReported)
{
  // The scheme's accuracy after a fixed budget, on triangles (degree-4 vertex) and on
  // quadrilaterals (Miura-ori), whose out-of-plane flex the springs hold only to fourth order.
  const double deg = M_PI / 180;
  Paper triangles = degree4Vertex({ 60 * deg, 80 * deg, 120 * deg, 100 * deg });
  std::vector<double> angles(triangles.edges.size(), 0.0);
  const std::array<double, 4> mode1 = degree4FoldAngles(60 * deg, 80 * deg, 30 * deg, 1);
  for (int k = 0; k < 4; ++k)
    angles[triangles.findEdge(0, k + 1)] = mode1[k];
  ASSERT_TRUE(foldToAngles(triangles, angles).ok());  // off the flat state, where the vertex bifurcates
  Paper quads = miuraOri(4, 4, 1.0, 1.3, M_PI / 3);
  ASSERT_TRUE(foldToAngles(quads, miuraFoldAngles(quads, 4, 4, M_PI / 3, 0.3)).ok());
  for (Paper* paper : { &triangles, &quads })
  {
    SeedSpringSolver solver;
    solver.setLimits({ 0.0, 20000, 0.0 });  // run the whole budget
    std::vector<char> fixed(paper->vertices.size(), 0);
    for (int v : paper->faces[0].vertices)
      fixed[v] = 1;
    disturb(*paper, 1e-2);
    for (int v : paper->faces[0].vertices)  // keep the held face exact (face 0 is not moved by foldToAngles)
      paper->vertices[v].folded << paper->vertices[v].crease_pattern, 0.0;
    const double before = edgeStrain(*paper).max;
    const SolveReport report = solver.solve(*paper, fixed);
    EXPECT_FALSE(report.diverged) << report.message;
    EXPECT_LT(report.max_strain, before);
    const ShapeMetrics m = measureShape(*paper, fixed);
    RecordProperty(paper == &triangles ? "triangles_max_strain" : "quads_max_strain", std::to_string(m.strain.max));
    std::cout << (paper == &triangles ? "triangles" : "quads") << ": after " << report.iterations
              << " seed iterations max strain " << m.strain.max << ", planarity " << m.planarity << ", force residual "
              << m.force_residual << "\n";
  }
}

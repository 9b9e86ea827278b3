// The paper's weight and the table under it: the table carries exactly the weight, its force
// is the energy's gradient, and a sheet lifted by one corner stays down where nothing lifts it.
#include <gtest/gtest.h>

#include <cmath>

#include "virtual_origami/curved/bubble_mesh.h"
#include "virtual_origami/curved/curved_follow.h"
#include "virtual_origami/curved/surroundings.h"

namespace virtual_origami::core
{
namespace
{

Surroundings onTable(double gravity)
{
  Surroundings s;
  s.gravity = gravity;
  s.table = true;
  s.table_stiffness = 100.0;
  return s;
}
}  // namespace

TEST(Surroundings, ForcesAreTheEnergysGradient)
{
  const Surroundings s = onTable(0.5);
  const std::vector<double> mass = { 1.0, 2.0, 3.0 };
  Positions x(3, 3);
  x << 0, 1, 2,          //
      0, 0, 1,           //
      0.2, -0.01, -0.3;  // above the table, just below, far below
  const std::vector<int> free_index = { 0, 1, 2 };
  Eigen::VectorXd g = Eigen::VectorXd::Zero(9);
  std::vector<Eigen::Triplet<double>> h;
  evaluateSurroundings(s, mass, x, { &free_index, &g, &h });
  const double step = 1e-7;
  for (int v = 0; v < 3; ++v)
    for (int c = 0; c < 3; ++c)
    {
      Positions plus = x, minus = x;
      plus(c, v) += step;
      minus(c, v) -= step;
      const double fd = (evaluateSurroundings(s, mass, plus) - evaluateSurroundings(s, mass, minus)) / (2 * step);
      EXPECT_NEAR(g[3 * v + c], fd, 1e-6) << "node " << v << " axis " << c;
    }
  // Weight only: m·g up the gradient; the table adds w·depth below it, and w on z·z.
  EXPECT_DOUBLE_EQ(g[2], 0.5);
  EXPECT_DOUBLE_EQ(g[5], 2.0 * 0.5 - 100.0 * 0.01);
  EXPECT_DOUBLE_EQ(g[8], 3.0 * 0.5 - 100.0 * 0.3);
  double zz = 0;
  for (const auto& t : h)
    zz += t.value();
  EXPECT_DOUBLE_EQ(zz, 200.0);  // the two nodes below the table
}

TEST(Surroundings, ASheetOnTheTableRestsWithTheTableCarryingItsWeight)
{
  const Paper paper = Paper::square(1.0);
  const CurvedMesh mesh = *bubbleMesh(paper);
  Surroundings s = onTable(1e-2);
  CurvedSolveOptions options;
  options.tolerance = 1e-10;
  CurvedSolver solver(mesh, paper, {}, {}, options, s);
  Positions x = placeNodes(mesh, paper);
  const CurvedReport report = solver.solve(x, {});
  ASSERT_TRUE(report.converged) << report.message;
  // Forces on the sheet sum to zero: the table's reaction, Σ w·depth, is its whole weight.
  double reaction = 0.0, weight = 0.0, deepest = 0.0;
  for (Eigen::Index v = 0; v < x.cols(); ++v)
  {
    reaction += s.table_stiffness * std::max(0.0, -x(2, v));
    weight += solver.terms().mass[v] * s.gravity;
    deepest = std::max(deepest, -x(2, v));
  }
  EXPECT_NEAR(reaction, weight, 1e-6 * weight);
  // Every node sinks about its own weight over w, and the sheet stays flat.
  double heaviest = 0.0;
  for (double m : solver.terms().mass)
    heaviest = std::max(heaviest, m);
  EXPECT_GT(deepest, 0.0);
  EXPECT_LE(deepest, 1.01 * heaviest * s.gravity / s.table_stiffness);
}

// Held at the far edge's corners and lifted at a near corner (turned a quarter of the way over
// the middle line), the sheet curls up from the table near that corner. Weightless it lifts far
// into the sheet (held at two corners it may swing about their line); the heavier, the more of
// it lies on the table: the lifted part shrinks with the gravity–bending length.
TEST(Surroundings, TheHeavierTheSheetTheMoreOfItStaysOnTheTable)
{
  const Paper paper = Paper::square(1.0);
  const int a = paper.vertexAt({ 0, 0 }), d = paper.vertexAt({ 0, 1 }), corner = paper.vertexAt({ 1, 0 });
  // Highest node of the far third of the sheet, and lowest node of all, after the lift.
  const auto lift = [&](double gravity, double* lowest) {
    CurvedFollowOptions options;
    options.solve.tolerance = 1e-8;
    options.solve.max_iterations = 500;
    options.surroundings = onTable(gravity);
    options.surroundings.table_stiffness = 0;  // the default: layer contact's
    CurvedSheetFollower follower([](const Paper& p) { return bubbleMesh(p); }, options);
    std::vector<PullTarget> pins = { { a, paper.vertices[a].folded },
                                     { d, paper.vertices[d].folded },
                                     { corner, paper.vertices[corner].folded } };
    EXPECT_TRUE(follower.solveState(paper, pins));
    for (int k = 1; k <= 40; ++k)
    {
      const double angle = M_PI / 2 * k / 40;
      pins[2].position = Vec3(0.5 + 0.5 * std::cos(angle), 0.0, 0.5 * std::sin(angle));
      const Expected<CurvedReport> r = follower.follow(pins);
      EXPECT_TRUE(r && r->converged) << "gravity " << gravity << " step " << k << ": "
                                     << (r ? r->message : r.message());
    }
    const Positions& x = follower.positions();
    const CurvedMesh& mesh = follower.mesh();
    EXPECT_NEAR(x(2, mesh.vertex_nodes[corner]), 0.5, 1e-12);
    double far_third = 0.0;
    *lowest = 0.0;
    for (size_t n = 0; n < mesh.nodes.size(); ++n)
    {
      *lowest = std::min(*lowest, x(2, n));
      if (mesh.nodes[n].crease_pattern.x() < 1.0 / 3)
        far_third = std::max(far_third, x(2, n));
    }
    return far_third;
  };
  double lowest_weightless = 0, lowest_paper = 0, lowest_heavy = 0;
  const double weightless = lift(0.0, &lowest_weightless);
  const double paper_weight = lift(3e-5, &lowest_paper);  // bending length a third of the side
  const double heavy = lift(1e-4, &lowest_heavy);         // a fifth
  EXPECT_GT(weightless, 0.03) << "weightless, the far third lifts off";
  EXPECT_LT(paper_weight, 0.5 * weightless);
  EXPECT_LT(heavy, 0.5 * paper_weight);
  // The table holds: what presses a node in (its weight, the sheet's bending) sinks it by that
  // force over the table's stiffness, under a hundredth of the layer thickness (1e-3) here.
  for (double lowest : { lowest_weightless, lowest_paper, lowest_heavy })
    EXPECT_GT(lowest, -1e-5);
}

}  // namespace virtual_origami::core

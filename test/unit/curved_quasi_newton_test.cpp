// The quasi-Newton method of curved paper (CurvedMethod::QuasiNewton: L-BFGS on one constant
// factorised matrix) against Newton, the reference: the same balances on a lifted corner, a
// bent strip and a drag, the same refusals, and no motion where the sheet is balanced already.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include <Eigen/Eigenvalues>

#include "corner_lift.h"
#include "virtual_origami/curved/bubble_mesh.h"
#include "virtual_origami/curved/curved_solver.h"
#include "virtual_origami/curved/elastica.h"
#include "virtual_origami/curved/paper_material.h"
#include "virtual_origami/curved/seed_scenes.h"
#include "virtual_origami/curved/strip_scenes.h"

using namespace virtual_origami::core;
using namespace virtual_origami::core::test;

namespace
{
CurvedSolveOptions quasiNewtonAlone()
{
  CurvedSolveOptions options;
  options.method = CurvedMethod::QuasiNewton;
  options.hand_over = false;  // L-BFGS must balance on its own: Newton would hide its failures
  options.lbfgs_iterations = 5000;
  return options;
}

/// The free nodes' gradient (stacked) and the softest stiffness of the Hessian over them, of
/// the terms alone (these scenes have no contact), at `x` with `pins` applied.
struct Stiffness
{
  double gradient_norm = 0.0;
  double softest = 0.0;
};

Stiffness stiffnessAt(const CurvedMesh& mesh, const Paper& paper, const CurvedMaterial& material, Positions x,
                      const std::vector<CurvedPin>& pins)
{
  std::vector<char> fixed(mesh.nodes.size(), 0);
  for (const CurvedPin& pin : pins)
  {
    fixed[pin.node] = 1;
    x.col(pin.node) = pin.position;
  }
  int free_count = 0;
  const std::vector<int> free_index = freeIndices(fixed, mesh.nodes.size(), &free_count);
  const CurvedTerms terms = curvedTerms(mesh, paper, material);
  std::vector<Eigen::Triplet<double>> triplets;
  Eigen::VectorXd g = Eigen::VectorXd::Zero(3 * free_count);
  evaluateCurved(terms, x, { &free_index, &g, &triplets });
  Eigen::SparseMatrix<double> h(3 * free_count, 3 * free_count);
  h.setFromTriplets(triplets.begin(), triplets.end());
  const Eigen::MatrixXd dense(h);
  return { g.norm(), Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(dense, Eigen::EigenvaluesOnly).eigenvalues().minCoeff() };
}

/// How far apart two shapes may lie that balance the same energy to their residual forces:
/// each is within |∇E| / λ_min of the balance (to first order, λ_min the softest stiffness
/// there, positive at a minimum), so the two within the sum.
double balanceDistanceBound(const CurvedMesh& mesh, const Paper& paper, const CurvedMaterial& material,
                            const Positions& a, const Positions& b, const std::vector<CurvedPin>& pins)
{
  const Stiffness sa = stiffnessAt(mesh, paper, material, a, pins);
  const Stiffness sb = stiffnessAt(mesh, paper, material, b, pins);
  EXPECT_GT(sa.softest, 0) << "not a minimum";
  return (sa.gradient_norm + sb.gradient_norm) / std::min(sa.softest, sb.softest);
}

double largestNodeDistance(const Positions& a, const Positions& b)
{
  return (a - b).colwise().norm().maxCoeff();
}
}  // namespace

TEST(CurvedQuasiNewton, ReachesNewtonsBalanceOnALiftedCorner)
{
  // The corner lifted in ten small steps by L-BFGS alone (as a hand drags it: its use), the
  // last balance against Newton's, solved in one go.
  const double lift = 0.06;
  const int steps = 6;
  const CornerLift scene = cornerLift(0.05, lift);
  const Positions start = placeNodes(scene.mesh, scene.paper);
  CurvedSolveOptions newton_options;
  newton_options.tolerance = 1e-10;
  CurvedSolveOptions quasi_options = quasiNewtonAlone();
  quasi_options.tolerance = 1e-10;
  Positions x_newton = start, x_quasi = start;
  const CurvedReport rn = CurvedSolver(scene.mesh, scene.paper, {}, {}, newton_options).solve(x_newton, scene.pins);
  ASSERT_TRUE(rn.converged) << rn.message;
  CurvedSolver quasi(scene.mesh, scene.paper, {}, {}, quasi_options);
  std::vector<CurvedPin> pins = scene.pins;
  int factorizations = 0, lbfgs_steps = 0;
  for (int k = 1; k <= steps; ++k)
  {
    pins.back().position = scene.paper.vertices[0].folded + lift * k / steps * Vec3::UnitZ();
    const CurvedReport rq = quasi.solve(x_quasi, pins);
    ASSERT_TRUE(rq.converged) << k << ": " << rq.message;
    EXPECT_FALSE(rq.handed_over);
    EXPECT_LE(rq.max_force, quasi_options.tolerance);
    factorizations += rq.factorizations;
    lbfgs_steps += rq.lbfgs_steps;
  }
  std::printf("lifted corner: %d L-BFGS steps over %d pulls\n", lbfgs_steps, steps);
  EXPECT_EQ(factorizations, 1);  // the constant matrix, once for the whole drag
  const double bound = balanceDistanceBound(scene.mesh, scene.paper, {}, x_newton, x_quasi, scene.pins);
  EXPECT_LT(largestNodeDistance(x_newton, x_quasi), bound);
  // The sheet really bent (the lifted corner drags its free neighbours up).
  double highest_free = 0;
  for (Eigen::Index v = 0; v < x_quasi.cols(); ++v)
    if (scene.mesh.nodes[v].paper_vertex < 0)
      highest_free = std::max(highest_free, x_quasi(2, v));
  EXPECT_GT(highest_free, 0.5 * lift);
  for (const CurvedPin& pin : scene.pins)
    EXPECT_EQ(x_quasi.col(pin.node), pin.position);
}

TEST(CurvedQuasiNewton, BendsAStripAsNewtonDoesOntoTheElastica)
{
  // A 20 × 2 cm strip of copy paper clamped at one end, the other end zone turned by 45° and
  // moved: a bending-dominated balance, started from the elastica's own shape.
  const double length = 0.2, width = 0.02;
  const StripScene scene = *stripScene(length, width, true);
  const Eigen::Vector2d end = Eigen::Vector2d(0.8, 0.3) * length;
  const Expected<HeldElastica> elastica = heldElastica(length, end, M_PI / 4);
  ASSERT_TRUE(elastica.ok()) << elastica.message();
  const CurvedMesh mesh = *meshStrip(scene, StripMesher::Bubble, width / 4);
  PaperMaterial paper = *paperPreset("copy_paper");
  paper.poisson_ratio = 0.0;
  const CurvedMaterial material = stripMaterial(*curvedMaterial(paper));
  const std::vector<CurvedPin> pins = stripPins(scene, mesh, end, M_PI / 4);
  // Balanced to 1e-4 of the bending force D·κ on a node (κ ~ 1/length), as the closed-form tests.
  const double tolerance = 1e-4 * bendingStiffness(paper) / length / (material.stretch * mesh.spacing);
  CurvedSolveOptions newton_options;
  newton_options.tolerance = tolerance;
  CurvedSolveOptions quasi_options = quasiNewtonAlone();
  quasi_options.tolerance = tolerance;
  const Positions start = stripAlong(scene, mesh, elastica->curve);
  Positions x_newton = start, x_quasi = start;
  const CurvedReport rn = CurvedSolver(mesh, scene.paper, material, {}, newton_options).solve(x_newton, pins);
  const CurvedReport rq = CurvedSolver(mesh, scene.paper, material, {}, quasi_options).solve(x_quasi, pins);
  ASSERT_TRUE(rn.converged) << rn.message;
  ASSERT_TRUE(rq.converged) << rq.message;
  EXPECT_FALSE(rq.handed_over);
  const double bound = balanceDistanceBound(mesh, scene.paper, material, x_newton, x_quasi, pins);
  const double apart = largestNodeDistance(x_newton, x_quasi);
  EXPECT_LT(apart, bound);
  // The same shape, so the same distance from the elastica (to within how far apart they are).
  const double off_newton = *midlineDeviation(scene, mesh, x_newton, elastica->curve);
  const double off_quasi = *midlineDeviation(scene, mesh, x_quasi, elastica->curve);
  EXPECT_NEAR(off_quasi, off_newton, apart / length + 1e-12);
  EXPECT_LT(off_quasi, 1e-2);  // and near the elastica at this coarse mesh (b/4)
}

TEST(CurvedQuasiNewton, DragsSeedScene1ThroughNewtonsBalances)
{
  // Seed scene 1's corner dragged in small pulls by each method (the quasi-Newton one with its
  // hand-over to Newton, as a user gets it): every pull balances, to the same energy, and the
  // last shape of each is a balance by the other solver's measure.
  const SeedScene scene = *seedScene(1, 1.0, 0.5e-3);
  SeedSceneOptions newton_run;
  newton_run.steps = 12;
  newton_run.until = 0.6;
  newton_run.mesh.spacing = 0.1;
  newton_run.contact.thickness = 0.25e-3;
  SeedSceneOptions quasi_run = newton_run;
  quasi_run.solve.method = CurvedMethod::QuasiNewton;
  const SeedSceneRun a = *runSeedScene(scene, newton_run);
  const SeedSceneRun b = *runSeedScene(scene, quasi_run);
  ASSERT_EQ(a.steps.size(), b.steps.size());
  int lbfgs_steps = 0, handed_over = 0;
  for (size_t k = 0; k < a.steps.size(); ++k)
  {
    const CurvedReport& ra = a.steps[k].report;
    const CurvedReport& rb = b.steps[k].report;
    ASSERT_TRUE(ra.converged) << k << ": " << ra.message;
    ASSERT_TRUE(rb.converged) << k << ": " << rb.message;
    lbfgs_steps += rb.lbfgs_steps;
    handed_over += rb.handed_over;
    const double ea = ra.energy.total() + ra.contact_energy, eb = rb.energy.total() + rb.contact_energy;
    EXPECT_NEAR(ea, eb, 1e-6 * std::max(ea, eb)) << k;
  }
  std::printf("quasi-Newton drag: %d L-BFGS steps, %d of %zu pulls handed over to Newton\n", lbfgs_steps, handed_over,
              b.steps.size());
  EXPECT_GT(lbfgs_steps, 0);
  const int fixed = a.mesh.vertex_nodes[scene.fixed], pulled = a.mesh.vertex_nodes[scene.pulled];
  const std::vector<CurvedPin> pins = { { fixed, scene.paper.vertices[scene.fixed].folded },
                                        { pulled, scene.pullAt(newton_run.until) } };
  CurvedSolver newton_check(a.mesh, scene.paper, newton_run.material, newton_run.contact, newton_run.solve);
  CurvedSolver quasi_check(b.mesh, scene.paper, quasi_run.material, quasi_run.contact, quasi_run.solve);
  EXPECT_LE(newton_check.maxForce(b.positions, pins), newton_run.solve.tolerance);
  EXPECT_LE(quasi_check.maxForce(a.positions, pins), newton_run.solve.tolerance);
}

TEST(CurvedQuasiNewton, RefusesWhatNewtonRefuses)
{
  const CornerLift scene = cornerLift(0.25, 0.1);
  const Positions start = placeNodes(scene.mesh, scene.paper);
  const int nodes = static_cast<int>(scene.mesh.nodes.size());
  const std::vector<std::vector<CurvedPin>> bad_pins = {
    { { nodes, Vec3::Zero() } },                           // off the sheet
    { { -1, Vec3::Zero() } },                              // off the sheet
    { { scene.pins[0].node, Vec3(NAN, 0, 0) } },           // at no finite point
    { { scene.pins[0].node, Vec3(0, INFINITY, 0) } },      // at no finite point
  };
  CurvedSolveOptions newton_options, quasi_options;
  quasi_options.method = CurvedMethod::QuasiNewton;
  CurvedSolver newton(scene.mesh, scene.paper, {}, {}, newton_options);
  CurvedSolver quasi(scene.mesh, scene.paper, {}, {}, quasi_options);
  for (const std::vector<CurvedPin>& pins : bad_pins)
  {
    Positions x_newton = start, x_quasi = start;
    const CurvedReport rn = newton.solve(x_newton, pins);
    const CurvedReport rq = quasi.solve(x_quasi, pins);
    EXPECT_TRUE(rq.refused);
    EXPECT_FALSE(rq.converged);
    EXPECT_EQ(rq.message, rn.message);
    EXPECT_EQ(x_quasi, start);
  }
  Positions too_few = start.leftCols(nodes - 1);
  const CurvedReport rn = newton.solve(too_few, scene.pins);
  const CurvedReport rq = quasi.solve(too_few, scene.pins);
  EXPECT_TRUE(rq.refused);
  EXPECT_EQ(rq.message, rn.message);
  EXPECT_EQ(too_few, start.leftCols(nodes - 1));
}

TEST(CurvedQuasiNewton, StaysPutWhenBalancedAlready)
{
  const CornerLift scene = cornerLift(0.1, 0.15);
  CurvedSolveOptions newton_options;
  newton_options.tolerance = 1e-10;
  Positions x = placeNodes(scene.mesh, scene.paper);
  ASSERT_TRUE(CurvedSolver(scene.mesh, scene.paper, {}, {}, newton_options).solve(x, scene.pins).converged);
  const Positions balanced = x;
  CurvedSolveOptions quasi_options = quasiNewtonAlone();
  quasi_options.tolerance = 1e-8;
  const CurvedReport report = CurvedSolver(scene.mesh, scene.paper, {}, {}, quasi_options).solve(x, scene.pins);
  EXPECT_TRUE(report.converged) << report.message;
  EXPECT_EQ(report.iterations, 0);
  EXPECT_EQ(report.lbfgs_steps, 0);
  EXPECT_EQ(report.factorizations, 0);  // no constant matrix needed for a shape already balanced
  EXPECT_EQ(x, balanced);
}

TEST(CurvedQuasiNewton, RollsBackANonFiniteStart)
{
  const CornerLift scene = cornerLift(0.25, 0.2);
  Positions x = placeNodes(scene.mesh, scene.paper);
  int free_node = 0;
  while (scene.mesh.nodes[free_node].paper_vertex >= 0)
    ++free_node;
  x(0, free_node) = NAN;
  Positions given = x;
  for (const CurvedPin& pin : scene.pins)
    given.col(pin.node) = pin.position;
  CurvedSolveOptions options;
  options.method = CurvedMethod::QuasiNewton;
  const CurvedReport report = CurvedSolver(scene.mesh, scene.paper, {}, {}, options).solve(x, scene.pins);
  EXPECT_TRUE(report.diverged);
  EXPECT_FALSE(report.message.empty());
  EXPECT_TRUE(x.hasNaN());
  for (Eigen::Index v = 0; v < x.cols(); ++v)
    if (v != free_node)
    {
      EXPECT_EQ(x.col(v), given.col(v));
    }
}

TEST(CurvedQuasiNewton, ASheetPressedInItsPlaneBucklesWhenItsBalancesAreChecked)
{
  // Two opposite corners pushed together along the diagonal by 2 %, from the flat sheet: the
  // flat, compressed sheet is a balance (nothing pushes out of the plane) but a saddle. L-BFGS
  // has no factorisation of the Hessian to fail there and stays flat; with check_stability its
  // balance is searched for a way down (the exact Hessian, the constant matrix as
  // preconditioner), and the sheet buckles.
  Paper paper = Paper::square(1.0);
  BubbleMeshOptions mesh_options;
  mesh_options.spacing = 0.1;
  const Expected<CurvedMesh> mesh = bubbleMesh(paper, mesh_options);
  ASSERT_TRUE(mesh.ok()) << mesh.message();
  const Vec3 a = paper.vertices[0].folded, c = paper.vertices[2].folded;
  const std::vector<CurvedPin> pins = { { mesh->vertex_nodes[0], a + 0.01 * (c - a) },
                                        { mesh->vertex_nodes[2], c + 0.01 * (a - c) } };
  const auto height = [](const Positions& x) { return x.row(2).cwiseAbs().maxCoeff(); };

  CurvedSolveOptions unchecked = quasiNewtonAlone();
  CurvedSolver flat_solver(*mesh, paper, {}, {}, unchecked);
  Positions flat = placeNodes(*mesh, paper);
  const CurvedReport at_saddle = flat_solver.solve(flat, pins);
  ASSERT_TRUE(at_saddle.converged) << at_saddle.message;
  EXPECT_EQ(height(flat), 0.0);  // the flat saddle
  EXPECT_EQ(at_saddle.saddles_left, 0);
  EXPECT_FALSE(at_saddle.handed_over);

  // The way down is found by the constant matrix's search; the buckled balance, far from the
  // flat sheet the matrix was made on, is finished by Newton if L-BFGS does not reach it.
  CurvedSolveOptions checked;
  checked.method = CurvedMethod::QuasiNewton;
  checked.check_stability = true;
  CurvedSolver solver(*mesh, paper, {}, {}, checked);
  Positions x = placeNodes(*mesh, paper);
  const CurvedReport report = solver.solve(x, pins);
  ASSERT_TRUE(report.converged) << report.message;
  EXPECT_GE(report.saddles_left, 1);
  EXPECT_GT(height(x), 0.05);  // buckled out of the plane
  EXPECT_LT(report.energy.total() + report.contact_energy, 0.5 * (at_saddle.energy.total() + at_saddle.contact_energy));
  EXPECT_LE(solver.maxForce(x, pins), checked.tolerance);
}

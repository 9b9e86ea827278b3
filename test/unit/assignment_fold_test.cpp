// Folding by assignment: the crease drivers' energy (gradient, Gauss–Newton product), the
// closed forms it must meet (a degree-4 vertex in both modes, a Miura-ori at every interior
// vertex), a square twist folded flat, targets from a file, previews, and bad input.
#include "virtual_origami/core/assignment_fold.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <random>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "closed_form_search.h"
#include "virtual_origami/core/fold_io.h"
#include "virtual_origami/core/layer_order.h"
#include "virtual_origami/core/reference_patterns.h"
#include "virtual_origami/core/tessellations.h"
#include "virtual_origami/solvers/crease_driver_factory.h"
#include "virtual_origami/solvers/driven_faces.h"
#include "virtual_origami/solvers/newton_solver.h"
#include "virtual_origami/solvers/quasi_newton_driver.h"

namespace virtual_origami::core
{
namespace
{
using test::hingeWeights;
using test::minimise;

using ::testing::HasSubstr;

constexpr double kAlpha = 1.1, kBeta = 0.7;  // sectors α, β, π − α, π − β of the degree-4 vertex

std::unique_ptr<QuasiNewtonDriver> driver(DriverHessian hessian, double face_stiffness)
{
  QuasiNewtonOptions options;
  options.hessian = hessian;
  options.face_stiffness = face_stiffness;
  return std::make_unique<QuasiNewtonDriver>(options);
}

/// How far a slide's last frame lies from the balance of its fraction (solved from it to 1e-9
/// by a fresh driver), over the sheet's size; infinity where that balance is not reached.
double distanceFromBalance(const Paper& slid, const AssignmentFoldRequest& frame)
{
  const auto reference = makeCreaseDriver("quasi_newton");
  reference->setLimits(SolveLimits{ 1e-9, 5000, 0.0 });
  Paper balance = slid;
  const Expected<AssignmentFoldResult> exact = foldByAssignment(balance, frame, *reference, nullptr);
  if (!exact || !exact->solve.converged)
    return std::numeric_limits<double>::infinity();
  double distance = 0.0;
  for (size_t v = 0; v < slid.vertices.size(); ++v)
    distance = std::max(distance, (slid.vertices[v].folded - balance.vertices[v].folded).norm());
  return distance / slid.scale();
}

Paper degree4(int mode)
{
  Paper paper = degree4Vertex({ kAlpha, kBeta, M_PI - kAlpha, M_PI - kBeta });
  const std::array<double, 4> signs = degree4FoldAngles(kAlpha, kBeta, 0.5, mode);
  for (int k = 0; k < 4; ++k)
    paper.edges[paper.findEdge(0, k + 1)].assignment = signs[k] > 0 ? Assignment::Valley : Assignment::Mountain;
  return paper;
}

/// Two drives of the same paper to the same targets, by drivers that differ in one option (the
/// second has it): the steps each took, and how far apart their balances lie over the sheet's size.
struct TwoDrives
{
  int steps[2] = { 0, 0 };
  SolveReport reports[2];
  double distance = 0.0;
};

TwoDrives driveBoth(const Paper& start, const std::vector<double>& target, const std::vector<char>& held,
                    const QuasiNewtonOptions (&options)[2], const SolveLimits& limits)
{
  TwoDrives out;
  Paper balance[2] = { start, start };
  for (int k = 0; k < 2; ++k)
  {
    QuasiNewtonDriver d(options[k]);
    d.setLimits(limits);
    const SolveReport report = d.drive(balance[k], target, held);
    EXPECT_TRUE(report.converged) << "driver " << k << ": " << report.message;
    out.steps[k] = report.iterations;
    out.reports[k] = report;
  }
  for (size_t v = 0; v < start.vertices.size(); ++v)
    out.distance = std::max(out.distance, (balance[0].vertices[v].folded - balance[1].vertices[v].folded).norm());
  out.distance /= start.scale();
  return out;
}

/// A commit's drive a percent on (from 40 % to 41 %) from a 12 × 12 Miura-ori balanced at 40 %,
/// with each of two option sets, to a balance of 1e-10.
TwoDrives commitOnBothFromBalance(const QuasiNewtonOptions (&options)[2])
{
  Paper start = miuraTessellation(12, 12).value().paper;
  const auto warm = makeCreaseDriver("quasi_newton");
  warm->setLimits(SolveLimits{ 1e-9, 5000, 0.0 });
  AssignmentFoldRequest request;
  request.fraction = 0.4;
  EXPECT_TRUE(foldByAssignment(start, request, *warm, nullptr));
  std::vector<double> target = creaseTargets(start);
  for (double& t : target)
    t *= 0.41;
  const std::vector<char> held(start.vertices.size(), 0);
  return driveBoth(start, target, held, options, SolveLimits{ 1e-10, 5000, 0.0 });
}

TEST(DrivenFaces, GradientMatchesFiniteDifferences)
{
  Paper paper = miuraTessellationFolded(3, 2, 1.0, 1.2, 1.0, 0.8).value().paper;
  DrivenFaces energy(paper, 50.0);
  std::vector<double> targets = creaseTargets(paper);
  for (double& t : targets)
    t *= 0.4;
  energy.setTargets(targets);
  Positions x = foldedPositions(paper) / energy.scale();
  std::mt19937 random(7);
  std::normal_distribution<double> noise(0.0, 1e-2);
  for (Eigen::Index i = 0; i < x.size(); ++i)
    x.data()[i] += noise(random);
  Positions gradient;
  energy.evaluate(x, &gradient);
  const double h = 1e-6;
  for (Eigen::Index i = 0; i < x.size(); ++i)
  {
    Positions plus = x, minus = x;
    plus.data()[i] += h;
    minus.data()[i] -= h;
    const double numeric = (energy.evaluate(plus).energy - energy.evaluate(minus).energy) / (2 * h);
    EXPECT_NEAR(gradient.data()[i], numeric, 1e-6 * std::max(1.0, std::abs(numeric))) << "coordinate " << i;
  }
}

TEST(DrivenFaces, HingeAnglesAreTheFoldAngles)
{
  const Paper paper = miuraTessellationFolded(3, 3, 1.0, 1.0, 1.0, 2.0).value().paper;
  const DrivenFaces energy(paper, 1.0);
  const std::vector<double> angles = energy.angles(foldedPositions(paper) / energy.scale());
  ASSERT_FALSE(energy.hinges().empty());
  for (const Hinge& h : energy.hinges())
    EXPECT_NEAR(angles[h.edge], paper.edges[h.edge].fold_angle, 1e-12) << "edge " << h.edge;
}

TEST(DrivenFaces, GaussNewtonProductIsItsMatrix)
{
  Paper paper = miuraTessellationFolded(3, 2, 1.0, 1.0, 1.2, 1.0).value().paper;
  DrivenFaces energy(paper, 30.0);
  energy.setTargets(creaseTargets(paper));
  const Positions x = foldedPositions(paper) / energy.scale();
  std::vector<char> fixed(paper.vertices.size(), 0);
  fixed[0] = 1;
  int free_count = 0;
  const std::vector<int> free_index = freeIndices(fixed, paper.vertices.size(), &free_count);
  const Eigen::SparseMatrix<double> lower = energy.gaussNewtonMatrix(x, free_index, free_count);
  const Eigen::MatrixXd full = Eigen::MatrixXd(lower).selfadjointView<Eigen::Lower>();
  std::mt19937 random(3);
  std::normal_distribution<double> noise(0.0, 1.0);
  Positions v = Positions::Zero(3, x.cols());
  Eigen::VectorXd flat(3 * free_count);
  for (size_t vertex = 0; vertex < free_index.size(); ++vertex)
    if (free_index[vertex] >= 0)
      for (int a = 0; a < 3; ++a)
        flat(3 * free_index[vertex] + a) = v(a, static_cast<Eigen::Index>(vertex)) = noise(random);
  Positions product;
  energy.gaussNewtonProduct(energy.linearize(x), v, product);
  const Eigen::VectorXd expected = full * flat;
  for (size_t vertex = 0; vertex < free_index.size(); ++vertex)
    if (free_index[vertex] >= 0)
    {
      for (int a = 0; a < 3; ++a)
      {
        EXPECT_NEAR(product(a, static_cast<Eigen::Index>(vertex)), expected(3 * free_index[vertex] + a),
                    1e-9 * expected.cwiseAbs().maxCoeff());
      }
    }
}

/// The energy's own Hessian against central differences of its gradient, on a folded Miura-ori
/// whose faces are stretched at random and whose hinges miss their targets: it must meet them
/// to the differences' own error, where the Gauss–Newton matrix misses by what it leaves out.
TEST(DrivenFaces, HessianProductIsTheGradientsDerivative)
{
  const Paper paper = miuraTessellationFolded(4, 3, 1.0, 1.0, 1.2, 1.0).value().paper;
  DrivenFaces energy(paper, 1e4);
  std::vector<double> targets = creaseTargets(paper);
  for (size_t e = 0; e < targets.size(); ++e)
    if (std::isfinite(targets[e]))
      targets[e] = 0.7 * paper.edges[e].fold_angle + 0.2;
  energy.setTargets(targets);
  std::mt19937 random(5);
  std::normal_distribution<double> noise(0.0, 1.0);
  Positions x = foldedPositions(paper) / energy.scale();
  Positions v(3, x.cols());
  for (Eigen::Index i = 0; i < x.cols(); ++i)
    for (int a = 0; a < 3; ++a)
    {
      x(a, i) += 1e-3 * noise(random);
      v(a, i) = noise(random);
    }
  const DrivenFaces::Linearization l = energy.linearize(x);
  Positions exact, gauss_newton, plus, minus;
  energy.hessianProduct(l, v, exact);
  energy.gaussNewtonProduct(l, v, gauss_newton);
  const double h = 1e-6;
  energy.evaluate(x + h * v, &plus);
  energy.evaluate(x - h * v, &minus);
  const Positions differences = (plus - minus) / (2 * h);
  EXPECT_LE((exact - differences).norm(), 1e-8 * differences.norm());
  EXPECT_GE((gauss_newton - differences).norm(), 1e-4 * differences.norm());
}

TEST(AssignmentFold, CreaseTargetsFollowAssignmentsAndFiles)
{
  Paper paper = degree4(1);
  paper.edges[paper.findEdge(0, 2)].target_angle = -0.75;
  paper.edges[paper.findEdge(0, 3)].assignment = Assignment::Unassigned;
  const std::vector<double> t = creaseTargets(paper);
  EXPECT_DOUBLE_EQ(t[paper.findEdge(0, 1)], M_PI);
  EXPECT_DOUBLE_EQ(t[paper.findEdge(0, 2)], -0.75);
  EXPECT_TRUE(std::isnan(t[paper.findEdge(0, 3)]));
  EXPECT_TRUE(std::isnan(t[paper.findEdge(1, 2)]));  // the boundary
}

/// The degree-4 vertex at half its targets: the drivers' answer is rigid and on the mode's
/// closed-form curve to rounding, and its ρ1 is the one the closed form gives for the crease
/// springs (the minimum of Σ w (ρ_k(ρ1) − ρ*_k/2)² along the curve), to within what the faces'
/// finite stiffness allows: a thousand times stiffer faces, a thousand times closer.
TEST(AssignmentFold, Degree4VertexMeetsItsClosedFormInBothModes)
{
  NewtonSolver rigid;
  for (int mode : { 1, 2 })
    for (DriverHessian hessian : { DriverHessian::Lagged, DriverHessian::Exact })
    {
      const Paper start = degree4(mode);
      const std::vector<double> targets = creaseTargets(start);
      const std::vector<double> w = hingeWeights(start);
      int edge[4];
      for (int k = 0; k < 4; ++k)
        edge[k] = start.findEdge(0, k + 1);
      const auto energy = [&](double rho1) {
        const std::array<double, 4> rho = degree4FoldAngles(kAlpha, kBeta, rho1, mode);
        double sum = 0.0;
        for (int k = 0; k < 4; ++k)
          sum += w[edge[k]] * std::pow(rho[k] - 0.5 * targets[edge[k]], 2);
        return sum;
      };
      const double sign = targets[edge[0]] > 0 ? 1.0 : -1.0;
      const double expected = sign * minimise([&](double r) { return energy(sign * r); }, 0.0, 3.0);
      std::vector<double> errors;
      for (double stiffness : { 1e3, 1e6 })
      {
        Paper paper = start;
        const auto d = driver(hessian, stiffness);
        AssignmentFoldRequest request;
        request.fraction = 0.5;
        const Expected<AssignmentFoldResult> result = foldByAssignment(paper, request, *d, &rigid);
        ASSERT_TRUE(result) << result.message();
        EXPECT_TRUE(result->rigid) << "mode " << mode;
        EXPECT_LE(result->max_strain, 1e-9);
        const double rho1 = paper.edges[edge[0]].fold_angle;
        const std::array<double, 4> closed = degree4FoldAngles(kAlpha, kBeta, rho1, mode);
        for (int k = 0; k < 4; ++k)
          EXPECT_NEAR(paper.edges[edge[k]].fold_angle, closed[k], 1e-9) << "mode " << mode << " crease " << k;
        errors.push_back(std::abs(rho1 - expected));
      }
      EXPECT_LE(errors[1], 1e-5) << "mode " << mode;
      EXPECT_LE(errors[1], errors[0] / 100) << "mode " << mode << ": " << errors[0] << " → " << errors[1];
    }
}

/// A 4 × 4 Miura-ori at 40 %: every crease at every interior vertex on the rigid Miura-ori of
/// one straight-crease angle ρ (miuraFoldAngles), and ρ the closed form's balance of the springs.
TEST(AssignmentFold, MiuraOriMeetsItsClosedFormAtEveryInteriorVertex)
{
  const int columns = 4, rows = 4;
  const double gamma = 1.0471975511965976;
  const Tessellation t = miuraTessellation(columns, rows, 1.0, 1.0, gamma).value();
  const double expected = test::miuraBalanceRho(t, columns, rows, gamma, 0.4, 3.0);
  const auto d = driver(DriverHessian::Lagged, 1e6);
  NewtonSolver rigid;
  Paper paper = t.paper;
  AssignmentFoldRequest request;
  request.fraction = 0.4;
  const Expected<AssignmentFoldResult> result = foldByAssignment(paper, request, *d, &rigid);
  ASSERT_TRUE(result) << result.message();
  EXPECT_TRUE(result->rigid);
  // Straight crease (0, 1)→(1, 1) folds (−1)^1·ρ.
  const double rho = -paper.edges[paper.findEdge(columns + 1, columns + 2)].fold_angle;
  EXPECT_NEAR(rho, expected, 1e-5);
  const std::vector<double> closed = miuraFoldAngles(paper, columns, rows, gamma, rho);
  int checked = 0;
  for (int j = 1; j < rows; ++j)
    for (int i = 1; i < columns; ++i)
    {
      const int v = j * (columns + 1) + i;
      for (size_t e = 0; e < paper.edges.size(); ++e)
        if (paper.edges[e].isCrease() && (paper.edges[e].vertices[0] == v || paper.edges[e].vertices[1] == v))
        {
          EXPECT_NEAR(paper.edges[e].fold_angle, closed[e], 1e-9) << "vertex " << v << " edge " << e;
          ++checked;
        }
    }
  EXPECT_EQ(checked, 4 * (columns - 1) * (rows - 1));
}

/// A square twist is no rigid mechanism: its faces must strain on the way, which the result
/// reports; at 100 % it lies flat-folded, rigid again, in the shape its ±π angles give.
TEST(AssignmentFold, SquareTwistFoldsFlatAtFullFraction)
{
  const Tessellation t = squareTwistTessellation(2, 2).value();  // one twist, at the middle
  Paper expected = t.paper;
  ASSERT_TRUE(foldToAngles(expected, t.target_fold_angle));
  const auto d = makeCreaseDriver("quasi_newton");
  NewtonSolver rigid;
  Paper paper = t.paper;
  AssignmentFoldRequest half;
  half.fraction = 0.5;
  const Expected<AssignmentFoldResult> middle = foldByAssignment(paper, half, *d, &rigid);
  ASSERT_TRUE(middle) << middle.message();
  EXPECT_FALSE(middle->rigid);
  EXPECT_GT(middle->max_strain, 1e-4) << "a square twist cannot fold half way with rigid faces";
  AssignmentFoldRequest full;
  full.fraction = 1.0;
  const Expected<AssignmentFoldResult> folded = foldByAssignment(paper, full, *d, &rigid);
  ASSERT_TRUE(folded) << folded.message();
  EXPECT_TRUE(folded->rigid);
  EXPECT_LE(folded->max_strain, 1e-9);
  for (size_t e = 0; e < paper.edges.size(); ++e)
    if (paper.edges[e].isCrease())
    {
      EXPECT_NEAR(paper.edges[e].fold_angle, t.target_fold_angle[e], 1e-6) << "edge " << e;
    }
  // Flat, its layers carry their order like every flat fold's: every stacked pair, by the rules.
  EXPECT_EQ(folded->layer_problem, "");
  EXPECT_GT(folded->ordered_pairs, 0);
  EXPECT_EQ(static_cast<int>(paper.face_orders.size()), folded->ordered_pairs);
  EXPECT_EQ(layerOrderViolation(paper, paper.face_orders), "");
  // The same shape up to a rigid motion: every distance between vertices as in the closed form.
  for (size_t a = 0; a < paper.vertices.size(); ++a)
    for (size_t b = a + 1; b < paper.vertices.size(); ++b)
      EXPECT_NEAR((paper.vertices[a].folded - paper.vertices[b].folded).norm(),
                  (expected.vertices[a].folded - expected.vertices[b].folded).norm(), 1e-6);
}

TEST(AssignmentFold, FileTargetAnglesAreWhereCreasesGo)
{
  Paper paper = miuraTessellation(2, 2).value().paper;
  for (Edge& e : paper.edges)
    if (e.isCrease())
      e.target_angle = (e.assignment == Assignment::Valley ? 1.0 : -1.0) * 0.6;
  const Tessellation folded = miuraTessellationFolded(2, 2, 1.0, 1.0, 1.0471975511965976, 0.6).value();
  const auto d = makeCreaseDriver("quasi_newton");
  NewtonSolver rigid;
  AssignmentFoldRequest request;
  request.fraction = 1.0;
  const Expected<AssignmentFoldResult> result = foldByAssignment(paper, request, *d, &rigid);
  ASSERT_TRUE(result) << result.message();
  // Driven to ±0.6 everywhere, a Miura-ori balances between its straight and zigzag creases.
  // At the one interior vertex (1, 1): straight crease (0, 1)→(1, 1), zigzag (1, 0)→(1, 1).
  const double straight = std::abs(paper.edges[paper.findEdge(3, 4)].fold_angle);
  const double zigzag = std::abs(paper.edges[paper.findEdge(1, 4)].fold_angle);
  EXPECT_LT(straight, 0.6);
  EXPECT_GT(zigzag, 0.6);
  EXPECT_NEAR(zigzag, 2 * std::atan(std::tan(straight / 2) / std::cos(1.0471975511965976)), 1e-9);
  (void)folded;
}

/// A crease pattern's edges_foldAngle are where its creases go; they survive a save and a load
/// (in a field of their own, as the frame's edges_foldAngle then says where the creases are).
TEST(AssignmentFold, TargetAnglesComeFromTheFileAndSurviveSaving)
{
  const std::string text = R"({
    "file_spec": 1.1, "frame_classes": ["creasePattern"],
    "vertices_coords": [[0,0],[1,0],[1,1],[0,1]],
    "edges_vertices": [[0,1],[1,2],[2,3],[3,0],[0,2]],
    "edges_assignment": ["B","B","B","B","V"],
    "edges_foldAngle": [0,0,0,0,90],
    "faces_vertices": [[0,1,2],[0,2,3]]
  })";
  const Expected<FoldDocument> document = parseFold(text);
  ASSERT_TRUE(document) << document.message();
  Paper paper = document->frames.at(0);
  const int diagonal = paper.findEdge(0, 2);
  ASSERT_TRUE(paper.edges[diagonal].target_angle);
  EXPECT_DOUBLE_EQ(*paper.edges[diagonal].target_angle, M_PI / 2);
  EXPECT_DOUBLE_EQ(creaseTargets(paper)[diagonal], M_PI / 2);
  const auto d = makeCreaseDriver("quasi_newton");
  NewtonSolver rigid;
  AssignmentFoldRequest request;
  request.fraction = 0.5;
  // It loaded folded to its angles already; half of the target is 45°.
  ASSERT_TRUE(foldByAssignment(paper, request, *d, &rigid));
  EXPECT_NEAR(paper.edges[diagonal].fold_angle, M_PI / 4, 1e-9);
  const Expected<FoldDocument> again = parseFold(formatFold(paper));
  ASSERT_TRUE(again) << again.message();
  ASSERT_TRUE(again->frames.at(0).edges[diagonal].target_angle);
  EXPECT_NEAR(*again->frames.at(0).edges[diagonal].target_angle, M_PI / 2, 1e-12);
  EXPECT_NEAR(again->frames.at(0).edges[diagonal].fold_angle, M_PI / 4, 1e-9);
  const Expected<FoldDocument> broken = parseFold(
      R"({"vertices_coords": [[0,0],[1,0],[1,1]], "edges_vertices": [[0,1],[1,2],[2,0]],
          "faces_vertices": [[0,1,2]], "virtual_origami:edges_targetFoldAngle": [0, "x", null]})");
  ASSERT_FALSE(broken);
  EXPECT_THAT(broken.message(), HasSubstr("virtual_origami:edges_targetFoldAngle"));
}

TEST(AssignmentFold, PreviewFramesTrackTheSliderAndZeroUnfolds)
{
  Paper paper = miuraTessellation(6, 6).value().paper;
  const auto d = makeCreaseDriver("quasi_newton");
  NewtonSolver rigid;
  AssignmentFoldRequest commit;
  commit.fraction = 0.3;
  ASSERT_TRUE(foldByAssignment(paper, commit, *d, &rigid));
  Paper committed_at_40 = paper;
  commit.fraction = 0.4;
  ASSERT_TRUE(foldByAssignment(committed_at_40, commit, *d, &rigid));
  SolveLimits frame;
  frame.max_iterations = 3;
  d->setLimits(frame);
  AssignmentFoldRequest preview;
  preview.converge = false;
  for (int k = 1; k <= 10; ++k)
  {
    preview.fraction = 0.3 + 0.01 * k;
    const Expected<AssignmentFoldResult> r = foldByAssignment(paper, preview, *d, nullptr);
    ASSERT_TRUE(r) << r.message();
    EXPECT_LE(r->max_strain, 1e-3) << "frame " << k;
  }
  // Ten frames of 1 % land near the state a commit at 40 % reaches.
  const int interior = paper.findEdge(7, 8);  // straight crease (0, 1)→(1, 1)
  EXPECT_NEAR(paper.edges[interior].fold_angle, committed_at_40.edges[interior].fold_angle, 1e-2);
  d->setLimits(SolveLimits{ 1e-9, 2000, 0.0 });
  commit.fraction = 0.0;
  const Expected<AssignmentFoldResult> flat = foldByAssignment(paper, commit, *d, &rigid);
  ASSERT_TRUE(flat) << flat.message();
  for (const Edge& e : paper.edges)
    EXPECT_NEAR(e.fold_angle, 0.0, 1e-6);
}

// A slide of anytime frames (one iteration each) on a driver that balanced other frames first
// (its kept matrix factorised elsewhere on the path): the frames stay on the balanced path,
// within a few thousandths of the sheet, instead of falling behind along the mechanism's turn.
TEST(AssignmentFold, AnytimeSlideOnAUsedDriverFollowsTheBalance)
{
  const Paper flat = miuraTessellation(20, 20).value().paper;
  const auto d = makeCreaseDriver("quasi_newton");
  NewtonSolver rigid;
  Paper start = flat;
  AssignmentFoldRequest commit;
  commit.fraction = 0.3;
  ASSERT_TRUE(foldByAssignment(start, commit, *d, &rigid));
  AssignmentFoldRequest preview;
  preview.converge = false;
  d->setLimits(SolveLimits{ 1e-6, 5000, 0.0 });
  Paper balanced = start;
  for (int k = 1; k <= 5; ++k)
  {
    preview.fraction = 0.3 + 0.01 * k;
    const Expected<AssignmentFoldResult> r = foldByAssignment(balanced, preview, *d, nullptr);
    ASSERT_TRUE(r && r->solve.converged) << "balanced frame " << k;
  }
  d->setLimits(SolveLimits{ 1e-6, 1, 0.0 });
  Paper slid = start;
  for (int k = 1; k <= 40; ++k)
  {
    preview.fraction = 0.3 + 0.01 * k;
    const Expected<AssignmentFoldResult> r = foldByAssignment(slid, preview, *d, nullptr);
    ASSERT_TRUE(r) << r.message();
    EXPECT_LE(r->max_strain, 1e-3) << "frame " << k;
  }
  EXPECT_LE(distanceFromBalance(slid, preview), 5e-3);
}

// Frames within a time budget too small for a factorisation (paper_model's previews) take their
// steps in the subspace of the last motion and the constant matrix's directions: on a driver
// that balanced other frames first, a slide keeps its faces within the strain a preview may
// show and stays near the balanced path, whether the budget allows one iteration or many.
TEST(AssignmentFold, BudgetedSlideFollowsTheBalanceWithoutAFactorisation)
{
  const Paper flat = miuraTessellation(20, 20).value().paper;
  for (const double budget : { 1e-9, 0.05 })
  {
    QuasiNewtonDriver driver;
    NewtonSolver rigid;
    Paper start = flat;
    AssignmentFoldRequest commit;
    commit.fraction = 0.3;
    ASSERT_TRUE(foldByAssignment(start, commit, driver, &rigid));
    AssignmentFoldRequest preview;
    preview.converge = false;
    driver.setLimits(SolveLimits{ 1e-6, 5000, 0.0 });
    Paper balanced = start;
    for (int k = 1; k <= 5; ++k)
    {
      preview.fraction = 0.3 + 0.01 * k;
      const Expected<AssignmentFoldResult> r = foldByAssignment(balanced, preview, driver, nullptr);
      ASSERT_TRUE(r && r->solve.converged) << "balanced frame " << k;
    }
    driver.setLimits(SolveLimits{ 1e-6, 5000, budget });
    Paper slid = start;
    for (int k = 1; k <= 40; ++k)
    {
      preview.fraction = 0.3 + 0.01 * k;
      const Expected<AssignmentFoldResult> r = foldByAssignment(slid, preview, driver, nullptr);
      ASSERT_TRUE(r) << r.message();
      EXPECT_LE(r->max_strain, 1e-3) << "budget " << budget << " s, frame " << k;
    }
    EXPECT_LE(distanceFromBalance(slid, preview), 5e-3) << "budget " << budget << " s";
  }
}

// A corner face of a flat Miura-ori driven 10° about its zigzag crease, the face across held (a
// turn's guide, rotate.h): the first Gauss–Newton steps from the flat sheet move the turning
// faces linearly and stretch them. Tried again with the faces restored before it is shortened,
// a refused step is mostly taken whole: the same balance in fewer steps.
TEST(AssignmentFold, RestoredTrialsReachATurnsBalanceInFewerSteps)
{
  const Paper flat = miuraTessellation(20, 20).value().paper;
  int axis = -1;
  for (int e : flat.faces[0].edges)
  {
    const Edge& edge = flat.edges[e];
    const Vec2 along = flat.vertices[edge.vertices[1]].crease_pattern - flat.vertices[edge.vertices[0]].crease_pattern;
    if (edge.isCrease() && std::abs(along.y()) > 1e-9)  // the zigzag crease, not the straight one
      axis = e;
  }
  ASSERT_GE(axis, 0);
  std::vector<double> target(flat.edges.size(), std::numeric_limits<double>::quiet_NaN());
  target[axis] = 10 * M_PI / 180;
  std::vector<char> held(flat.vertices.size(), 0);
  for (int v : flat.faces[flat.edges[axis].otherFace(0)].vertices)
    held[v] = 1;
  QuasiNewtonOptions options[2];
  for (int k = 0; k < 2; ++k)
  {
    options[k].restore_trial_faces = k == 1;
    options[k].face_stiffness = 100.0;  // the guide's (TurnGuide)
  }
  const TwoDrives drives = driveBoth(flat, target, held, options, QuasiNewtonDriver().limits());
  EXPECT_LT(drives.steps[1], drives.steps[0]);
  EXPECT_LE(drives.distance, 1e-7) << "steps " << drives.steps[0] << " → " << drives.steps[1];
}

/// A commit a percent on from a balanced Miura-ori: with the energy's own Hessian the
/// Newton–Krylov steps converge quadratically near the balance, where Gauss–Newton's converge
/// linearly (it leaves out the faces' residual stress and the hinges' curvature), so it takes
/// fewer steps to the same balance.
TEST(AssignmentFold, ExactHessianReachesACommitsBalanceInFewerSteps)
{
  QuasiNewtonOptions options[2];
  options[0].exact_hessian = false;
  options[1].exact_hessian = true;
  const TwoDrives drives = commitOnBothFromBalance(options);
  EXPECT_LT(drives.steps[1], drives.steps[0]);
  EXPECT_LE(drives.distance, 1e-8) << "steps " << drives.steps[0] << " → " << drives.steps[1];
}

/// A commit a percent on from a balanced 12 × 12 Miura-ori: its first step turns the faces by
/// about a degree, and a matrix factorised before that calls the mechanism's new turn stiff
/// (its face term charges K·δ², above the hinges' stiffness). Refactorised before the next
/// step, not after conjugate gradients stalled on the old one: fewer back-substitutions
/// (measured 12 against 25), no more factorisations, the same balance.
TEST(AssignmentFold, FacesTurnedSinceTheFactorisationRefactoriseBeforeTheStep)
{
  QuasiNewtonOptions options[2];
  options[0].refactor_turn = 0.0;
  const TwoDrives drives = commitOnBothFromBalance(options);
  EXPECT_LT(drives.reports[1].back_substitutions, drives.reports[0].back_substitutions);
  EXPECT_LE(drives.reports[1].factorizations, drives.reports[0].factorizations);
  EXPECT_LE(drives.distance, 1e-8) << "back-substitutions " << drives.reports[0].back_substitutions << " → "
                                   << drives.reports[1].back_substitutions;
}

TEST(AssignmentFold, BadInputChangesNothing)
{
  const auto d = makeCreaseDriver("quasi_newton");
  const Paper start = miuraTessellation(2, 2).value().paper;
  for (double fraction : { std::numeric_limits<double>::quiet_NaN(), -1.1, 1.5, std::numeric_limits<double>::infinity() })
  {
    Paper paper = start;
    AssignmentFoldRequest request;
    request.fraction = fraction;
    const Expected<AssignmentFoldResult> r = foldByAssignment(paper, request, *d, nullptr);
    ASSERT_FALSE(r);
    EXPECT_THAT(r.message(), HasSubstr("-1 to 1"));
    EXPECT_TRUE(paper == start);
  }
  Paper square = Paper::square();
  const Paper square_start = square;
  const Expected<AssignmentFoldResult> none = foldByAssignment(square, AssignmentFoldRequest{}, *d, nullptr);
  ASSERT_FALSE(none);
  EXPECT_THAT(none.message(), HasSubstr("no crease"));
  EXPECT_TRUE(square == square_start);
  Paper paper = start;
  const Expected<AssignmentFoldResult> held = foldByAssignment(paper, AssignmentFoldRequest{}, *d, nullptr, { 99 });
  ASSERT_FALSE(held);
  EXPECT_THAT(held.message(), HasSubstr("not on the paper"));
  EXPECT_TRUE(paper == start);
}

}  // namespace
}  // namespace virtual_origami::core

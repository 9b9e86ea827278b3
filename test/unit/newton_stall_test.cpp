// The rigid solver, asked by fold by assignment's closures (SolveLimits::stall_window), ends a
// solve whose energy has stopped falling far from its tolerance ("stalled") instead of spending
// its 200 iterations on a closure it cannot make; a solve whose energy keeps falling is not
// stopped, and the commit answers as before (docs/FOLD_BY_ASSIGNMENT.md, "What a commit costs").
#include <gtest/gtest.h>

#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

#include "library_patterns.h"
#include "test_models.h"
#include "virtual_origami/core/assignment_fold.h"
#include "virtual_origami/core/rotate.h"
#include "virtual_origami/core/tessellations.h"
#include "virtual_origami/solvers/crease_driver_factory.h"
#include "virtual_origami/solvers/newton_solver.h"

namespace virtual_origami::core
{
namespace
{
constexpr double kDeg = M_PI / 180;

/// The Newton solver, each solve's report kept; with `stall_rule` false it runs every solve
/// without the stall rule, whatever its caller asks.
class RecordingNewton : public ShapeSolver
{
public:
  explicit RecordingNewton(bool stall_rule) : stall_rule_(stall_rule)
  {
    limits_ = newton_.limits();
  }
  std::string name() const override
  {
    return newton_.name();
  }
  SolveReport solve(Paper& paper, const std::vector<char>& fixed) override
  {
    SolveLimits limits = limits_;
    if (!stall_rule_)
      limits.stall_window = 0;
    newton_.setLimits(limits);
    reports.push_back(newton_.solve(paper, fixed));
    return reports.back();
  }
  std::vector<SolveReport> reports;

private:
  NewtonSolver newton_;
  bool stall_rule_;
};

/// The rigid solver with the stall rule's window of fold by assignment's closures.
std::unique_ptr<NewtonSolver> stallingNewton()
{
  auto solver = std::make_unique<NewtonSolver>();
  SolveLimits limits = solver->limits();
  limits.stall_window = 30;
  solver->setLimits(limits);
  return solver;
}

/// A 400-vertex Miura-ori turned 40° at its corner face, every vertex then moved by up to
/// `noise` of the sheet (the same pseudo-random moves each time).
Paper shakenMiura(double noise)
{
  Paper paper = tessellationWithVertices(TessellationKind::Miura, 400).value().paper;
  RotateRequest request;
  request.face = 0;
  request.axis_edge = test::slantedCreaseOf(paper, 0);
  request.angle = 40 * kDeg;
  NewtonSolver solver;
  EXPECT_TRUE(rotate(paper, request, &solver));
  std::srand(7);
  for (Vertex& v : paper.vertices)
    v.folded += noise * paper.scale() * Vec3::Random();
  return paper;
}

/// Two faces' vertices held where the shaking left them: those faces cannot regain their shape,
/// so no rigid state exists. The energy stops falling at once; the solve used to go on to its
/// 200 iterations and now stops after 31, at the same strain.
TEST(NewtonStall, ASolveWithNoRigidStateWithinReachStopsEarlyWhereItWouldHaveStopped)
{
  const Paper shaken = shakenMiura(0.03);
  std::vector<char> held(shaken.vertices.size(), 0);
  for (int v : shaken.faces.front().vertices)
    held[v] = 1;
  for (int v : shaken.faces.back().vertices)
    held[v] = 1;

  // By default (a turn, a drag) the rule is off: the solve runs to its iteration limit.
  Paper to_limit = shaken;
  NewtonSolver without_rule;
  ASSERT_EQ(without_rule.limits().stall_window, 0);
  const SolveReport old = without_rule.solve(to_limit, held);
  ASSERT_FALSE(old.converged);
  ASSERT_EQ(old.iterations, without_rule.limits().max_iterations);  // the cliff

  Paper stalled = shaken;
  const std::unique_ptr<NewtonSolver> solver = stallingNewton();
  const SolveReport report = solver->solve(stalled, held);
  EXPECT_FALSE(report.converged);
  EXPECT_FALSE(report.diverged);
  EXPECT_LE(report.iterations, 2 * solver->limits().stall_window);
  EXPECT_NE(report.message.find("stalled"), std::string::npos) << report.message;
  // As far from rigid as the long solve ended: its last 169 iterations only let the free
  // vertices drift along the sheet's mechanism (by 2 % of the sheet), not towards a rigid state.
  EXPECT_NEAR(report.max_strain, old.max_strain, 1e-9 * old.max_strain);
}

/// A solve that converges from far after a long damped start (40 iterations, 30 of them more
/// than 10^8 times its tolerance away) is judged by the stall rule at every iteration from the
/// 31st and is not stopped: the same iterations and the same state as without the rule.
TEST(NewtonStall, ASolveFromFarThatConvergesSlowlyIsNotStopped)
{
  const Paper shaken = shakenMiura(0.3);
  const std::unique_ptr<NewtonSolver> solver = stallingNewton();
  Paper free_run = shaken;
  NewtonSolver without_rule;
  const SolveReport old = without_rule.solve(free_run, {});
  ASSERT_TRUE(old.converged) << old.message;
  ASSERT_GT(old.iterations, solver->limits().stall_window);  // long enough to be judged

  Paper judged = shaken;
  const SolveReport report = solver->solve(judged, {});
  EXPECT_TRUE(report.converged) << report.message;
  EXPECT_LE(report.max_strain, solver->limits().tolerance);
  EXPECT_EQ(report.iterations, old.iterations);
  EXPECT_TRUE(judged == free_run);
}

/// Origami Simulator's open sink base committed to 100 % after 25, 50 and 75 %: its balance is
/// strained (7.7e-7) and its rigid closure cannot be made. The closure used to spend the rigid
/// solver's 200 iterations before failing; it now stalls within 60, and the commit answers the
/// same (the failed closure's state is never taken).
TEST(NewtonStall, AStrainedCommitsFailedClosureStopsEarlyWithTheSameAnswer)
{
  Paper paper = test::libraryPattern("Bases/openSinkBase.svg");
  const std::unique_ptr<CreaseDriver> driver = makeCreaseDriver("quasi_newton");
  AssignmentFoldRequest request;
  NewtonSolver steps;
  for (double fraction : { 0.25, 0.5, 0.75 })
  {
    request.fraction = fraction;
    ASSERT_TRUE(foldByAssignment(paper, request, *driver, &steps));
  }
  request.fraction = 1.0;

  Paper to_limit = paper;
  RecordingNewton without_rule(false);
  const Expected<AssignmentFoldResult> old = foldByAssignment(to_limit, request, *driver, &without_rule);
  ASSERT_TRUE(old) << old.message();
  ASSERT_FALSE(without_rule.reports.empty());
  int old_iterations = 0;
  for (const SolveReport& s : without_rule.reports)
    old_iterations += s.iterations;
  ASSERT_GE(old_iterations, 200);  // the cliff

  Paper committed = paper;
  RecordingNewton solver(true);
  const Expected<AssignmentFoldResult> now = foldByAssignment(committed, request, *driver, &solver);
  ASSERT_TRUE(now) << now.message();
  ASSERT_EQ(solver.reports.size(), without_rule.reports.size());
  int iterations = 0;
  for (const SolveReport& s : solver.reports)
  {
    iterations += s.iterations;
    EXPECT_FALSE(s.converged);
    EXPECT_NE(s.message.find("stalled"), std::string::npos) << s.message;
  }
  EXPECT_LE(iterations, 60 * static_cast<int>(solver.reports.size()));
  EXPECT_FALSE(now->rigid);
  EXPECT_EQ(now->rigid, old->rigid);
  EXPECT_EQ(now->max_strain, old->max_strain);
  EXPECT_EQ(now->angle_error, old->angle_error);
  EXPECT_EQ(now->against_target, old->against_target);
  EXPECT_EQ(now->crossings, old->crossings);
  EXPECT_EQ(assignmentFoldProblems(*now, {}), assignmentFoldProblems(*old, {}));
  EXPECT_TRUE(committed == to_limit);
}

}  // namespace
}  // namespace virtual_origami::core

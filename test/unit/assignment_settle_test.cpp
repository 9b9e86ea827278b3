// A commit by assignment stops its crease driver once the balance is settled (a run of it moves
// no vertex by 1e-6 of the sheet), instead of creeping on to the driver's iteration limit near a
// singular balance: the same state and figures as the driver run to its limit, in a fraction of
// its iterations (docs/FOLD_BY_ASSIGNMENT.md, "No cliffs").
#include <gtest/gtest.h>

#include <memory>
#include <string>

#include "library_patterns.h"
#include "virtual_origami/core/assignment_fold.h"
#include "virtual_origami/core/positions.h"
#include "virtual_origami/solvers/crease_driver_factory.h"
#include "virtual_origami/solvers/solver_factory.h"

namespace virtual_origami::core
{
namespace
{
Expected<AssignmentFoldResult> commit(Paper& paper, double fraction, double settled_move)
{
  AssignmentFoldRequest request;
  request.fraction = fraction;
  request.settled_move = settled_move;
  const std::unique_ptr<CreaseDriver> driver = makeCreaseDriver("quasi_newton");
  const std::unique_ptr<ShapeSolver> rigid = makeSolver("newton");
  return foldByAssignment(paper, request, *driver, rigid.get());
}

// Origami Simulator's curvedcrease2 (54 vertices) committed in steps: from 50 % to 75 % one of
// its stages creeps on to the driver's 2,000 iterations (1.6 s of its 1.6 s).
TEST(AssignmentSettle, ASettledCommitEndsWhereTheDriverRunToItsLimitEnds)
{
  Paper paper = test::libraryPattern("Curved/curvedcrease2.svg");
  const double settled = AssignmentFoldRequest{}.settled_move;
  ASSERT_GT(settled, 0.0);
  for (double fraction : { 0.25, 0.5 })
    ASSERT_TRUE(commit(paper, fraction, settled));

  Paper crept = paper;
  const Expected<AssignmentFoldResult> to_limit = commit(crept, 0.75, 0.0);
  ASSERT_TRUE(to_limit) << to_limit.message();
  ASSERT_GE(to_limit->solve.iterations, 2000);  // the cliff this settles

  const Expected<AssignmentFoldResult> step = commit(paper, 0.75, settled);
  ASSERT_TRUE(step) << step.message();
  EXPECT_TRUE(step->solve.converged) << step->solve.message;
  EXPECT_LT(step->solve.iterations, to_limit->solve.iterations / 4);
  // The same state, and so the same answer.
  EXPECT_LT((foldedPositions(paper) - foldedPositions(crept)).colwise().norm().maxCoeff(), 1e-4 * paper.scale());
  EXPECT_NEAR(step->max_strain, to_limit->max_strain, 1e-6);
  EXPECT_NEAR(step->angle_error, to_limit->angle_error, 1e-4);
  EXPECT_EQ(step->against_target, to_limit->against_target);
  EXPECT_EQ(step->crossings, to_limit->crossings);
  EXPECT_EQ(step->rigid, to_limit->rigid);
  EXPECT_EQ(assignmentFoldProblems(*step, {}).empty(), assignmentFoldProblems(*to_limit, {}).empty());
}

}  // namespace
}  // namespace virtual_origami::core

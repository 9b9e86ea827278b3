// A commit that goes on from a preview frame far behind its fraction (the slider let go after a
// fast slide of one-iteration frames) drives the goal in one stage where that closes rigidly,
// instead of staging the rest of the way through soft faces: the same rigid fold at its targets.
#include <gtest/gtest.h>

#include "virtual_origami/core/assignment_fold.h"
#include "virtual_origami/core/fold_fraction.h"
#include "virtual_origami/core/tessellations.h"
#include "virtual_origami/solvers/crease_driver_factory.h"
#include "virtual_origami/solvers/newton_solver.h"

namespace virtual_origami::core
{
namespace
{
/// The slider moved 5 % at a time from flat to `to`, each frame one iteration of `driver`.
Paper fastSlide(const Paper& flat, CreaseDriver& driver, double to)
{
  Paper frame = flat;
  AssignmentFoldRequest preview;
  preview.converge = false;
  for (int k = 1; 0.05 * k <= to + 1e-12; ++k)
  {
    preview.fraction = 0.05 * k;
    EXPECT_TRUE(foldByAssignment(frame, preview, driver, nullptr)) << "frame " << k;
  }
  return frame;
}

TEST(ReleaseFromPreview, AFastSlidesReleaseAtFullFoldsInOneStageToTheRigidFlatFold)
{
  const Paper flat = miuraTessellation(12, 12).value().paper;
  const auto driver = makeCreaseDriver("quasi_newton");
  const auto frames = driver->clone();
  frames->setLimits(SolveLimits{ 1e-6, 1, 1e-9 });  // a preview's: every step over budget
  const Paper frame = fastSlide(flat, *frames, 1.0);
  // The frames fell behind: the rest of the way is more than one stage (10°) of a π target.
  ASSERT_LT(foldFraction(frame), 1.0 - 0.2 / M_PI);

  NewtonSolver rigid;
  AssignmentFoldRequest release;
  release.fraction = 1.0;
  release.committed = &flat;
  Paper direct = frame;
  const Expected<AssignmentFoldResult> one = foldByAssignment(direct, release, *driver, &rigid);
  // The same commit from the same frame, staged (as from a paper no preview is on show for).
  AssignmentFoldRequest from_frame = release;
  from_frame.committed = nullptr;
  Paper staged = frame;
  const Expected<AssignmentFoldResult> stages = foldByAssignment(staged, from_frame, *driver, &rigid);
  ASSERT_TRUE(one && stages) << one.message() << " / " << stages.message();
  for (const AssignmentFoldResult* r : { &*one, &*stages })
  {
    EXPECT_TRUE(r->rigid);
    EXPECT_LE(r->max_strain, kRigidStrain);
    EXPECT_LE(r->angle_error, 1e-6);
    EXPECT_EQ(r->against_target, 0);
    EXPECT_EQ(r->crossings, 0);
    EXPECT_TRUE(r->layer_problem.empty()) << r->layer_problem;
    EXPECT_EQ(assignmentFoldProblems(*r, AssignmentFoldAcceptance{}), "");
  }
  EXPECT_EQ(one->ordered_pairs, stages->ordered_pairs);
  // Every driven crease where the staged commit put it.
  const std::vector<double> targets = creaseTargets(flat);
  for (size_t e = 0; e < targets.size(); ++e)
  {
    if (std::isfinite(targets[e]))
    {
      EXPECT_NEAR(direct.edges[e].fold_angle, staged.edges[e].fold_angle, 1e-6) << "crease " << e;
    }
  }
  // In one stage: fewer driver iterations than the staged way.
  EXPECT_LT(one->solve.iterations, stages->solve.iterations);
}

}  // namespace
}  // namespace virtual_origami::core

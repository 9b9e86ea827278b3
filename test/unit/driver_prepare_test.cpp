// A crease driver prepared ahead of its first preview frame (CreaseDriver::prepare, what
// paper_model does in the background after a new pattern): the frames are the ones an unprepared
// driver makes, bit for bit, and the first pays for no factorisation; a used driver's frames are
// left as they were. A commit made in the previews' driver (its frames set aside) is the one a
// fresh clone makes, bit for bit, and the frames after it go on from the slide.
#include <gtest/gtest.h>

#include "virtual_origami/core/assignment_fold.h"
#include "virtual_origami/core/tessellations.h"
#include "virtual_origami/solvers/crease_driver_factory.h"
#include "virtual_origami/solvers/solver_factory.h"

namespace virtual_origami::core
{
namespace
{
/// Preview frames 1 % apart from `from` (fractions from + 0.01 … from + 0.01·count), each as
/// paper_model's: one call of the driver within its limits, from the frame before.
std::vector<Expected<AssignmentFoldResult>> slide(Paper& paper, CreaseDriver& driver, double from, int count)
{
  std::vector<Expected<AssignmentFoldResult>> frames;
  AssignmentFoldRequest preview;
  preview.converge = false;
  for (int k = 1; k <= count; ++k)
  {
    preview.fraction = from + 0.01 * k;
    frames.push_back(foldByAssignment(paper, preview, driver, nullptr));
  }
  return frames;
}

// Frames of one iteration, and frames whose time budget every step overruns (a preview's, its
// later frames subspace frames): the same with and without the preparation.
TEST(DriverPrepare, PreparedSlideIsTheUnpreparedOneWithoutItsFirstFactorisation)
{
  const Paper flat = miuraTessellation(12, 12).value().paper;
  for (const double budget : { 0.0, 1e-9 })
  {
    const auto plain = makeCreaseDriver("quasi_newton");
    const auto prepared = makeCreaseDriver("quasi_newton");
    for (CreaseDriver* d : { plain.get(), prepared.get() })
      d->setLimits(SolveLimits{ 1e-6, 1, budget });
    prepareAssignmentPreviews(flat, *prepared);

    Paper a = flat, b = flat;
    const auto unprepared_frames = slide(a, *plain, 0.0, 6);
    const auto prepared_frames = slide(b, *prepared, 0.0, 6);
    for (size_t k = 0; k < prepared_frames.size(); ++k)
    {
      ASSERT_TRUE(unprepared_frames[k] && prepared_frames[k]) << "budget " << budget << ", frame " << k;
      EXPECT_EQ(prepared_frames[k]->solve.iterations, unprepared_frames[k]->solve.iterations);
      EXPECT_EQ(prepared_frames[k]->max_strain, unprepared_frames[k]->max_strain)
          << "budget " << budget << ", frame " << k;
    }
    EXPECT_GE(unprepared_frames[0]->solve.factorizations, 1);
    EXPECT_EQ(prepared_frames[0]->solve.factorizations, 0) << "budget " << budget;
    EXPECT_TRUE(foldedPositions(a) == foldedPositions(b)) << "budget " << budget;
    EXPECT_GT(foldedPositions(b).row(2).cwiseAbs().maxCoeff(), 1e-3 * b.scale()) << "the frames folded nothing";
  }
}

// Prepared again on the state of a slide in progress (the pattern unchanged), a driver keeps its
// kept factorisation and its last frames: the next frame is the one it would have made.
TEST(DriverPrepare, PreparingAUsedDriverLeavesItsFramesAsTheyWere)
{
  const Paper flat = miuraTessellation(12, 12).value().paper;
  const auto plain = makeCreaseDriver("quasi_newton");
  const auto prepared = makeCreaseDriver("quasi_newton");
  for (CreaseDriver* d : { plain.get(), prepared.get() })
    d->setLimits(SolveLimits{ 1e-6, 1, 0.0 });
  Paper a = flat, b = flat;
  slide(a, *plain, 0.0, 3);
  slide(b, *prepared, 0.0, 3);
  prepareAssignmentPreviews(b, *prepared);
  const auto next_plain = slide(a, *plain, 0.03, 2);
  const auto next_prepared = slide(b, *prepared, 0.03, 2);
  ASSERT_TRUE(next_plain[1] && next_prepared[1]);
  EXPECT_EQ(next_prepared[0]->solve.factorizations, next_plain[0]->solve.factorizations);
  EXPECT_TRUE(foldedPositions(a) == foldedPositions(b));
}

// Held vertices not on the paper: nothing is prepared (the frame itself refuses them), and the
// driver's first frame makes its own factorisation.
TEST(DriverPrepare, HeldVertexNotOnThePaperPreparesNothing)
{
  const Paper flat = miuraTessellation(6, 6).value().paper;
  const auto d = makeCreaseDriver("quasi_newton");
  d->setLimits(SolveLimits{ 1e-6, 1, 0.0 });
  prepareAssignmentPreviews(flat, *d, { static_cast<int>(flat.vertices.size()) });
  Paper paper = flat;
  const auto frames = slide(paper, *d, 0.0, 1);
  ASSERT_TRUE(frames[0]);
  EXPECT_GE(frames[0]->solve.factorizations, 1);
}

// A release after a slide, made in the slide's driver under a commit's limits (the set-up its
// frames made serving it, as paper_model's releases are), at the slide's fraction (one stage) and
// further on (first tried in one stage from the frame): the paper a fresh clone commits, bit for
// bit. Its frames set aside meanwhile, the driver's next frame goes on from the slide as a twin's
// that made no commit does (a prediction along the last frames), not from the commit's motion.
TEST(DriverPrepare, ACommitInTheSlidesDriverIsAFreshClonesAndTheSlideGoesOnAfterIt)
{
  const Paper flat = miuraTessellation(12, 12).value().paper;
  const SolveLimits frame_limits{ 1e-6, 1, 0.0 };
  const auto commit_template = makeCreaseDriver("quasi_newton");
  const auto rigid = makeSolver("newton");
  for (const double release_at : { 0.2, 0.6 })
  {
    const auto slid = makeCreaseDriver("quasi_newton");
    const auto twin = makeCreaseDriver("quasi_newton");
    for (CreaseDriver* d : { slid.get(), twin.get() })
      d->setLimits(frame_limits);
    Paper frame = flat, twin_frame = flat;
    slide(frame, *slid, 0.0, 20);
    slide(twin_frame, *twin, 0.0, 20);
    ASSERT_TRUE(foldedPositions(frame) == foldedPositions(twin_frame));

    AssignmentFoldRequest release;
    release.fraction = release_at;
    release.committed = &flat;
    Paper in_clone = frame;
    const auto cloned = commit_template->clone();
    const auto by_clone = foldByAssignment(in_clone, release, *cloned, rigid.get());
    ASSERT_TRUE(by_clone) << by_clone.message();

    Paper in_driver = frame;
    release.in_driver = true;
    slid->setLimits(commit_template->limits());
    const auto by_driver = foldByAssignment(in_driver, release, *slid, rigid.get());
    slid->setLimits(frame_limits);
    ASSERT_TRUE(by_driver) << by_driver.message();
    EXPECT_TRUE(by_driver->rigid) << release_at;
    EXPECT_GT(by_driver->solve.iterations, 0) << release_at;
    EXPECT_EQ(by_driver->solve.iterations, by_clone->solve.iterations) << release_at;
    // The constant matrix the slide factorised is not made again.
    EXPECT_LE(by_driver->solve.factorizations, by_clone->solve.factorizations) << release_at;
    EXPECT_TRUE(foldedPositions(in_driver) == foldedPositions(in_clone)) << release_at;

    // The slide goes on (the release undone): the next frames start where the twin's do.
    const auto next = slide(frame, *slid, 0.2, 3);
    const auto twin_next = slide(twin_frame, *twin, 0.2, 3);
    for (size_t k = 0; k < next.size(); ++k)
    {
      ASSERT_TRUE(next[k] && twin_next[k]);
      EXPECT_EQ(next[k]->solve.factorizations, twin_next[k]->solve.factorizations) << release_at << ", " << k;
      // Gone on from the commit's motion instead, the first frames kept 1.7 times the strain.
      EXPECT_NEAR(next[k]->max_strain, twin_next[k]->max_strain, 1e-3 * twin_next[k]->max_strain)
          << release_at << ", " << k;
    }
  }
}

}  // namespace
}  // namespace virtual_origami::core

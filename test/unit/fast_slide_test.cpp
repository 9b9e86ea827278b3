// A fast slide's preview frames (the fold slider moved 5 % a frame, each a subspace frame of one
// step): a step the line search refuses for the strain it makes is taken whole with its faces
// restored, so the previews keep up with the handle (before, they fell behind: 85 % at 100 %).
#include <algorithm>
#include <cmath>
#include <functional>

#include <gtest/gtest.h>

#include "virtual_origami/core/assignment_fold.h"
#include "virtual_origami/core/fold_fraction.h"
#include "virtual_origami/core/tessellations.h"
#include "virtual_origami/solvers/quasi_newton_driver.h"

namespace virtual_origami::core
{
namespace
{
/// `flat` slid from 0 to 100 % in preview frames 5 % apart, each one step of a subspace frame (a
/// preview's: no factorisation) with all its directions: a budget no frame here comes near, below
/// which frames are subspace frames. `frame_done(k, frame, paper)` after each; the paper at the end.
Paper slideInFivePercentFrames(const Paper& flat, QuasiNewtonOptions options,
                               const std::function<void(int, const AssignmentFoldResult&, const Paper&)>& frame_done)
{
  options.subspace_below_seconds = 100.0;
  QuasiNewtonDriver driver(options);
  driver.setLimits(SolveLimits{ 1e-6, 1, 10.0 });
  prepareAssignmentPreviews(flat, driver);
  Paper paper = flat;
  AssignmentFoldRequest preview;
  preview.converge = false;
  for (int k = 1; k <= 20; ++k)
  {
    preview.fraction = 0.05 * k;
    const Expected<AssignmentFoldResult> frame = foldByAssignment(paper, preview, driver, nullptr);
    EXPECT_TRUE(frame) << "frame " << k << ": " << frame.message();
    if (!frame)
      break;
    EXPECT_EQ(frame->solve.iterations, 1) << "frame " << k;
    frame_done(k, *frame, paper);
  }
  return paper;
}
}  // namespace

TEST(FastSlide, PreviewFramesFivePercentApartKeepUpWithTheHandle)
{
  const Paper flat = miuraTessellation(20, 20).value().paper;
  const Paper end = slideInFivePercentFrames(flat, {}, [](int k, const AssignmentFoldResult& frame, const Paper& paper) {
    // No more stretched than the frames that fell behind (their largest strain here, 2.6e-3).
    EXPECT_LE(frame.max_strain, 2.5e-3) << "frame " << k;
    // Where the handle is: the fraction the creases fit, a frame's step behind at most.
    EXPECT_GE(foldFraction(paper), 0.05 * k - 0.05) << "frame " << k;
  });
  EXPECT_GE(foldFraction(end), 0.97);
}

/// A steeper Miura-ori (γ 70°, as the user's-path bench slides) slid 5 % a frame with and
/// without the frames' step remembered: where the whole step overshoots, the frame's line search
/// halves it, an energy pass and a restoring step (a back-substitution) more, and the frames after
/// it overshoot the same way. Started at the length the frames before took, they make fewer
/// restoring steps and follow the handle as closely, as little stretched.
TEST(FastSlide, FramesStartTheirLineSearchAtTheStepTheFramesBeforeTook)
{
  const Paper flat = miuraTessellation(20, 20, 1.0, 1.0, 70.0 * M_PI / 180.0).value().paper;
  int back_substitutions[2] = { 0, 0 };
  double fitted[2] = { 0.0, 0.0 }, largest_strain[2] = { 0.0, 0.0 }, largest_lag[2] = { 0.0, 0.0 };
  for (int remember = 0; remember < 2; ++remember)
  {
    QuasiNewtonOptions options;
    options.remember_frame_step = remember == 1;
    const Paper end =
        slideInFivePercentFrames(flat, options, [&](int k, const AssignmentFoldResult& frame, const Paper& paper) {
          back_substitutions[remember] += frame.solve.back_substitutions;
          largest_strain[remember] = std::max(largest_strain[remember], frame.max_strain);
          largest_lag[remember] = std::max(largest_lag[remember], 0.05 * k - foldFraction(paper));
        });
    fitted[remember] = foldFraction(end);
  }
  EXPECT_LT(back_substitutions[1], back_substitutions[0]);
  EXPECT_NEAR(fitted[1], fitted[0], 1e-3) << "back-substitutions " << back_substitutions[0] << " → "
                                          << back_substitutions[1];
  EXPECT_LE(largest_strain[1], largest_strain[0] * 1.01);
  EXPECT_LE(largest_lag[1], largest_lag[0] + 1e-3);
}

}  // namespace virtual_origami::core

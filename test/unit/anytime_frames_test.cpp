// Anytime frames (anytime_frames.h) on a 2,025-vertex sheet dragged along seed scene 1's pull:
// each shown shape against the tight balance of the same pins (solved afresh, force 1e-10), a
// snap reaching its branch, the release converging to 1e-8, and a factor made for another state
// never trusted past the residual check. The factorisations are made in the frames (background
// off) and a frame ends on its count of corrections, not on the clock, so every run shows the
// same frames; nothing here is timed.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "../../bench/bench_common.h"
#include "virtual_origami/curved/anytime_frames.h"
#include "virtual_origami/curved/seed_scenes.h"

using namespace virtual_origami::core;
using virtual_origami::bench::gridMesh;

namespace
{
/// Seed scene 1's sheet as an n × n grid, corner c held, corner a on the scene's pull.
struct PulledGrid
{
  SeedScene scene = *seedScene(1);
  CurvedMesh mesh;
  Positions rest;
  std::vector<CurvedPin> pins;

  explicit PulledGrid(int n) : mesh(gridMesh(scene.paper, n)), rest(placeNodes(mesh, scene.paper))
  {
    const int fixed = mesh.vertex_nodes[scene.fixed], pulled = mesh.vertex_nodes[scene.pulled];
    pins = { { fixed, rest.col(fixed) }, { pulled, rest.col(pulled) } };
  }
  void pullTo(double s)
  {
    pins[1].position = scene.pullAt(s);
  }
};

AnytimeFrameOptions deterministic()
{
  AnytimeFrameOptions options;
  options.background = false;
  options.refactor_frames = 1;
  options.frame_seconds = INFINITY;  // the corrections' count, not the clock, ends a frame
  return options;
}

/// The bound on a shown shape: within 1e-4 of the side of the tight balance.
constexpr double kFrameBound = 1e-4;
constexpr int kDragFrames = 40;  // 1/2000 of the pull each: the sheet leaves the flat and snaps twice

/// One drag, shared by the tests that read it: each frame's report, and its shape's distance
/// to the balance a fresh Newton solver reaches from it at 1e-10 (leaving saddles).
struct Drag
{
  PulledGrid sheet{ 45 };  // 2,025 vertices
  std::unique_ptr<AnytimeFrames> frames;
  std::vector<FrameReport> reports;
  std::vector<double> errors;
  std::vector<bool> balanced;  // the tight solve converged

  Drag()
  {
    frames = std::make_unique<AnytimeFrames>(sheet.mesh, sheet.scene.paper, CurvedMaterial{}, ContactOptions{},
                                             deterministic());
    if (!frames->start(sheet.rest, sheet.pins))
      return;
    CurvedSolver exact(sheet.mesh, sheet.scene.paper);
    exact.options().tolerance = 1e-10;
    exact.options().predict = false;
    double s = 0;
    for (int k = 1; k <= kDragFrames; ++k)
    {
      sheet.pullTo(s += 5e-4);
      const Expected<FrameReport> r = frames->frame(sheet.pins);
      if (!r)
        return;
      reports.push_back(*r);
      Positions balance = frames->positions();
      balanced.push_back(exact.solve(balance, sheet.pins).converged);
      errors.push_back(std::sqrt((balance - frames->positions()).colwise().squaredNorm().maxCoeff()) /
                       sheet.scene.paper.scale());
    }
  }
  /// Within 3 frames of an inertial one (a detected loss of stability: the issue excepts them).
  bool nearSnap(size_t k) const
  {
    for (size_t j = k >= 3 ? k - 3 : 0; j < reports.size() && j <= k + 3; ++j)
      if (reports[j].inertial)
        return true;
    return false;
  }
};

Drag& drag()
{
  static Drag shared;
  return shared;
}
}  // namespace

TEST(AnytimeFrames, ADragsSteadyFramesStayWithinATenThousandthOfTheSideOfTheTightBalance)
{
  const Drag& d = drag();
  ASSERT_EQ(d.reports.size(), static_cast<size_t>(kDragFrames));
  int steady = 0;
  for (size_t k = 0; k < d.reports.size(); ++k)
  {
    if (d.nearSnap(k))
      continue;
    ++steady;
    ASSERT_TRUE(d.balanced[k]) << "frame " << k + 1;
    EXPECT_LE(d.errors[k], kFrameBound) << "frame " << k + 1 << ": force " << d.reports[k].max_force;
    EXPECT_FALSE(d.reports[k].inertial);
  }
  // Most of the drag is steady: the snaps' exceptions do not swallow it.
  EXPECT_GE(steady, kDragFrames / 2);
}

TEST(AnytimeFrames, ASnapTurnsTheFramesInertialAndReachesItsBranchWithinASecondOfFrames)
{
  const Drag& d = drag();
  ASSERT_EQ(d.reports.size(), static_cast<size_t>(kDragFrames));
  size_t first = d.reports.size();
  for (size_t k = 0; k < d.reports.size() && first == d.reports.size(); ++k)
    if (d.reports[k].inertial)
      first = k;
  ASSERT_LT(first, d.reports.size()) << "no loss of stability met along the drag";
  // Where the static matrix no longer factorised, the drag's branch had turned unstable: the
  // tight solve from that frame left it (a node moved by more than the bound).
  EXPECT_GT(d.errors[first], kFrameBound);
  // Within 30 frames (1 s at 30 Hz): a static frame at force 1e-6, on the branch the tight
  // solve also reaches.
  bool reached = false;
  for (size_t k = first; k < d.reports.size() && k <= first + 30 && !reached; ++k)
    reached = !d.reports[k].inertial && d.reports[k].max_force <= 1e-6 && d.errors[k] <= kFrameBound;
  EXPECT_TRUE(reached);
}

// Each factor costs a whole factorisation (a third of a second of the background's at 10,000
// vertices): a static matrix indefinite at the largest shift allowed is indefinite at every
// smaller one, and is not tried again there before the inertial matrix is. A corner pushed in
// by a tenth of the side, the sheet not yet relaxed: its compressed edges curve the energy
// down out of the plane, far beyond any static shift.
TEST(AnytimeFrames, AStaticMatrixIndefiniteAtTheLargestShiftIsNotTriedAtSmallerOnes)
{
  PulledGrid sheet(20);
  Positions pushed = sheet.rest;
  const int corner = sheet.pins[1].node, held = sheet.pins[0].node;
  pushed.col(corner) += 0.1 * (sheet.rest.col(held) - sheet.rest.col(corner));
  const auto factorizationsAt = [&](double static_shift_limit) {
    AnytimeFrameOptions options = deterministic();
    options.static_shift_limit = static_shift_limit;
    AnytimeFrames frames(sheet.mesh, sheet.scene.paper, {}, {}, options);
    EXPECT_TRUE(frames.start(sheet.rest, sheet.pins));
    const int before = frames.factorizations();
    frames.keepFactorAt(pushed, 1);
    return frames.factorizations() - before;
  };
  const int one_shift = factorizationsAt(1e-10);
  EXPECT_GE(one_shift, 2) << "one static try, then the inertial matrix";
  EXPECT_EQ(factorizationsAt(1e-8), one_shift);
}

// The release corrects only with a static factor: where the static matrix does not factorise
// (the corner of the test above pushed in, the sheet not relaxed), it makes no inertial one
// (two more factorisations here, the ladder starting below the start's inertial shift) and
// Newton finishes from there.
TEST(AnytimeFrames, TheReleaseMakesNoInertialFactorWhereTheStaticMatrixFails)
{
  PulledGrid sheet(20);
  std::vector<CurvedPin> pins = sheet.pins;
  Positions pushed = sheet.rest;
  pushed.col(pins[1].node) += 0.1 * (sheet.rest.col(pins[0].node) - sheet.rest.col(pins[1].node));
  pins[1].position = pushed.col(pins[1].node);
  AnytimeFrames frames(sheet.mesh, sheet.scene.paper, {}, {}, deterministic());
  ASSERT_TRUE(frames.start(pushed, pins));
  const ReleaseReport release = frames.release();
  EXPECT_EQ(release.frame_factorizations, 1) << "one static try";
  EXPECT_EQ(release.corrections, 0);
  EXPECT_GT(release.newton_iterations, 0);
  EXPECT_TRUE(release.converged);
  CurvedSolver solver(sheet.mesh, sheet.scene.paper);
  EXPECT_LE(solver.maxForce(frames.positions(), pins), 1e-8);
}

TEST(AnytimeFrames, TheReleaseConvergesToTheTolerance)
{
  Drag& d = drag();
  ASSERT_EQ(d.reports.size(), static_cast<size_t>(kDragFrames));
  const ReleaseReport release = d.frames->release();
  EXPECT_TRUE(release.converged);
  EXPECT_LE(release.max_force, 1e-8);
  // The force measured afresh by the solver, not the frames' own count.
  CurvedSolver solver(d.sheet.mesh, d.sheet.scene.paper);
  EXPECT_LE(solver.maxForce(d.frames->positions(), d.sheet.pins), 1e-8);
  // A release right after a snap's inertial frames too (the drag ends in one).
  EXPECT_TRUE(d.reports.back().inertial || d.reports[d.reports.size() - 2].inertial);
}

TEST(AnytimeFrames, AFactorMadeForAnotherStateIsUsedOnlyWhereItLowersTheEnergy)
{
  PulledGrid sheet(30);
  AnytimeFrames frames(sheet.mesh, sheet.scene.paper, {}, {}, deterministic());
  ASSERT_TRUE(frames.start(sheet.rest, sheet.pins));
  double s = 0;
  for (int k = 0; k < 6; ++k)
  {
    sheet.pullTo(s += 5e-4);
    ASSERT_TRUE(frames.frame(sheet.pins));
  }
  CurvedSolver solver(sheet.mesh, sheet.scene.paper);
  // Stale factors: the flat sheet's (Hessian of another shape), and one of the sheet stretched
  // to twice its size (stiff across the sheet where the bent one is soft: its steps are far too
  // short), each tagged as made at frame 0.
  Positions stretched = 2.0 * sheet.rest;
  for (const Positions* stale : { &sheet.rest, &stretched })
  {
    frames.keepFactorAt(*stale, 0);
    sheet.pullTo(s += 5e-4);
    const Expected<FrameReport> r = frames.frame(sheet.pins);
    ASSERT_TRUE(r);
    EXPECT_EQ(r->factor_frame, 0);  // the stale factor was the one used
    EXPECT_FALSE(r->inertial);
    // The residual check: no shown shape above the energy the frame started from, and the
    // force the frame reports is the shape's own.
    EXPECT_LE(r->energy, r->start_energy);
    EXPECT_NEAR(r->max_force, solver.maxForce(frames.positions(), sheet.pins), 1e-6 * r->max_force + 1e-15);
    Eigen::VectorXd g;
    EXPECT_NEAR(frames.energy(frames.positions(), &g), r->energy, 1e-12 * std::abs(r->energy));
  }
}

TEST(AnytimeFrames, RefusesAnotherMeshsPositionsAndOtherPins)
{
  PulledGrid sheet(10);
  AnytimeFrames frames(sheet.mesh, sheet.scene.paper, {}, {}, deterministic());
  EXPECT_FALSE(frames.frame(sheet.pins));  // before start
  EXPECT_FALSE(frames.start(Positions::Zero(3, 5), sheet.pins));
  std::vector<CurvedPin> off = sheet.pins;
  off[0].node = 100000;
  EXPECT_FALSE(frames.start(sheet.rest, off));
  ASSERT_TRUE(frames.start(sheet.rest, sheet.pins));
  std::vector<CurvedPin> other = sheet.pins;
  other[1].node = other[1].node == 1 ? 2 : 1;
  EXPECT_FALSE(frames.frame(other));
  other = sheet.pins;
  other[1].position.x() = NAN;
  EXPECT_FALSE(frames.frame(other));
  EXPECT_EQ(frames.frames(), 0);
}

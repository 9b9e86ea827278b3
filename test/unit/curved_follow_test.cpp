// A curved sheet following a moving pin: a corner of the uncreased square swung on a half
// circle about the middle line, the far edge held, solved from the last balance at every step.
#include <gtest/gtest.h>

#include <cmath>

#include "test_models.h"
#include "virtual_origami/curved/bubble_mesh.h"
#include "virtual_origami/curved/curved_follow.h"
#include "virtual_origami/curved/curved_metrics.h"

namespace virtual_origami::core
{
namespace
{
CurvedSheetFollower makeFollower(CurvedFollowOptions options = {})
{
  options.solve.tolerance = 1e-8;
  options.solve.max_iterations = 200;
  return CurvedSheetFollower([](const Paper& paper) { return bubbleMesh(paper); }, options);
}

/// The corner (1, 0) on the half circle about the line x = 0.5, up along +z.
Vec3 along(double angle)
{
  return Vec3(0.5 + 0.5 * std::cos(angle), 0.0, 0.5 * std::sin(angle));
}

TEST(CurvedFollow, TheSheetBendsAfterACornerSwungOverTheMiddleLine)
{
  const Paper paper = Paper::square(1.0);
  const int a = paper.vertexAt({ 0, 0 }), d = paper.vertexAt({ 0, 1 }), corner = paper.vertexAt({ 1, 0 });
  ASSERT_GE(a, 0);
  ASSERT_GE(d, 0);
  ASSERT_GE(corner, 0);
  CurvedSheetFollower follower = makeFollower();
  const auto pins = [&](double angle) {
    return std::vector<PullTarget>{ { a, paper.vertices[a].folded },
                                    { d, paper.vertices[d].folded },
                                    { corner, along(angle) } };
  };
  Expected<CurvedReport> report = follower.solveState(paper, pins(0.0));
  ASSERT_TRUE(report) << report.message();
  EXPECT_TRUE(report->converged);
  const int steps = 80;  // the corner moves 0.02 a step, less than a quarter spacing
  double deepest_bend = 0.0;
  for (int k = 1; k <= steps; ++k)
  {
    const double angle = M_PI * k / steps;  // to the end: the corner on the held corner
    report = follower.follow(pins(angle));
    ASSERT_TRUE(report) << report.message();
    EXPECT_TRUE(report->converged) << "step " << k << ": force " << report->max_force;
    EXPECT_EQ(follower.lastSteps(), 1) << "a small move is one solve";
    EXPECT_TRUE(follower.balanced());
    const Positions& x = follower.positions();
    EXPECT_EQ((x.col(follower.mesh().vertex_nodes[corner]) - along(angle)).norm(), 0.0);
    EXPECT_EQ((x.col(follower.mesh().vertex_nodes[a]) - paper.vertices[a].folded).norm(), 0.0);
    const CurvedMetrics metrics = measureCurved(follower.mesh(), follower.paper(), x);
    // A triangle mesh bends without stretching only along its edges: curled across them, at
    // spacing 0.1, the edges stretch by up to about 2.5e-3 at the end of this path (hinges of
    // some 0.7 rad), growing with the curl from 5e-5 at the first step.
    EXPECT_LT(metrics.strain.max, 3e-3) << "paper barely stretches";
    EXPECT_EQ(metrics.penetrations, 0);
    deepest_bend = std::max(deepest_bend, metrics.max_bend);
  }
  EXPECT_GT(deepest_bend, 0.5) << "the sheet curls: neighbouring triangles meet at a clear angle";
  std::printf("curved follow: largest dihedral inside the face %.3f rad\n", deepest_bend);
}

TEST(CurvedFollow, ALongMoveIsSplitAndTheSameStateKeepsItsBalance)
{
  const Paper paper = Paper::square(1.0);
  const int a = paper.vertexAt({ 0, 0 }), d = paper.vertexAt({ 0, 1 }), corner = paper.vertexAt({ 1, 0 });
  CurvedSheetFollower follower = makeFollower();
  ASSERT_TRUE(follower.solveState(paper, { { a, paper.vertices[a].folded }, { d, paper.vertices[d].folded } }));
  const std::vector<PullTarget> lifted{ { a, paper.vertices[a].folded },
                                        { d, paper.vertices[d].folded },
                                        { corner, along(M_PI / 2) } };
  Expected<CurvedReport> report = follower.solveState(paper, lifted);
  ASSERT_TRUE(report) << report.message();
  EXPECT_TRUE(report->converged);
  EXPECT_GT(follower.lastSteps(), 1) << "half a metre in steps of a quarter spacing";
  const Positions bent = follower.positions();
  // The same state again (a pin request, the model unchanged): the balance is kept.
  report = follower.solveState(paper, lifted);
  ASSERT_TRUE(report);
  EXPECT_EQ(follower.lastSteps(), 1);
  EXPECT_LT((follower.positions() - bent).cwiseAbs().maxCoeff(), 1e-6);
  EXPECT_GT(measureCurved(follower.mesh(), follower.paper(), follower.positions()).max_bend, 0.1);
  // Let go of the corner and solved anew: the sheet of the flat state, exactly flat (going on
  // from the bend it would stop wherever the soft bending's forces fall below the tolerance).
  report = follower.solveState(paper, { lifted[0], lifted[1] }, true);
  ASSERT_TRUE(report) << report.message();
  EXPECT_TRUE(report->converged);
  EXPECT_EQ(follower.positions().row(2).cwiseAbs().maxCoeff(), 0.0);
}

TEST(CurvedFollow, BadPinsAreRefusedAndChangeNothing)
{
  const Paper paper = Paper::square(1.0);
  CurvedSheetFollower follower = makeFollower();
  EXPECT_FALSE(follower.follow({ { 0, Vec3::Zero() } })) << "no state yet";
  ASSERT_TRUE(follower.solveState(paper, { { 0, paper.vertices[0].folded } }));
  const Positions before = follower.positions();
  const auto refused = [&](const std::vector<PullTarget>& pins) {
    EXPECT_FALSE(follower.follow(pins));
    EXPECT_FALSE(follower.solveState(paper, pins));
    EXPECT_EQ(follower.positions(), before);
  };
  refused({ { 99, Vec3::Zero() } });
  refused({ { 1, Vec3(NAN, 0, 0) } });
  refused({ { 1, Vec3::Zero() }, { 1, Vec3::Zero() } });
  refused({ { 1, Vec3(1e6, 0, 0) } });  // thousands of steps
  ASSERT_EQ(follower.pins().size(), 1u);
  EXPECT_EQ(follower.pins()[0].vertex, 0);
}

}  // namespace
}  // namespace virtual_origami::core

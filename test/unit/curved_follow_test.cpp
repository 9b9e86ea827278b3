// A curved sheet following a moving pin: a corner of the uncreased square swung on a half
// circle about the middle line, the far edge held, solved from the last balance at every step.
#include <gtest/gtest.h>

#include <cmath>

#include "test_models.h"
#include "virtual_origami/curved/anytime_frames.h"
#include "virtual_origami/curved/bubble_mesh.h"
#include "virtual_origami/curved/curved_follow.h"
#include "virtual_origami/curved/curved_metrics.h"
#include "virtual_origami/curved/seed_scenes.h"

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
  // Frames too.
  EXPECT_FALSE(follower.frame({ { 99, Vec3::Zero() } }));
  EXPECT_FALSE(follower.frame({ { 1, Vec3(NAN, 0, 0) } }));
  EXPECT_EQ(follower.positions(), before);
  EXPECT_FALSE(follower.onFrames());
}

// The drag at the mouse (curved_mesh_solver): a corner grabbed, three held, and lifted in
// towards the middle in anytime frames, one per move, each holding the pins exactly; standing
// still, the sheet settles on the balance that solving every move to the tolerance reaches.
TEST(CurvedFollow, FramesAtTheMouseSettleOnTheBalanceEachMoveSolvedReaches)
{
  const Paper paper = Paper::square(1.0);
  const int corner = paper.vertexAt({ 0, 0 });
  std::vector<PullTarget> held;
  for (const Vec2& at : { Vec2(1, 0), Vec2(1, 1), Vec2(0, 1) })
    held.push_back({ paper.vertexAt(at), paper.vertices[paper.vertexAt(at)].folded });
  const auto lifted = [](double t) { return Vec3(0.1 * t, 0.1 * t, 0.2 * t); };
  const auto pins = [&](double t) {
    std::vector<PullTarget> p = held;
    p.push_back({ corner, lifted(t) });
    return p;
  };
  CurvedFollowOptions options;
  options.frames.background = false;  // the same frames every run
  CurvedSheetFollower frames = makeFollower(options), solved = makeFollower();
  EXPECT_FALSE(frames.frame(pins(0.0))) << "no state yet";
  ASSERT_TRUE(frames.solveState(paper, held));
  ASSERT_TRUE(solved.solveState(paper, held));
  EXPECT_FALSE(frames.onFrames());
  const int node = frames.mesh().vertex_nodes[corner];
  const int moves = 20;  // 0.012 of the side a move
  for (int k = 1; k <= moves; ++k)
  {
    const double t = static_cast<double>(k) / moves;
    const Expected<FrameReport> frame = frames.frame(pins(t));  // the corner grabbed at the first
    ASSERT_TRUE(frame) << frame.message();
    EXPECT_EQ(frames.positions().col(node), lifted(t)) << "move " << k;
    for (const PullTarget& pin : held)
      EXPECT_EQ(frames.positions().col(frames.mesh().vertex_nodes[pin.vertex]), pin.position);
    EXPECT_EQ(frames.pins().size(), 4u);
    EXPECT_TRUE(frames.positions().allFinite());
    ASSERT_TRUE(solved.follow(pins(t)));
  }
  const Expected<CurvedReport> settled = frames.settle();
  ASSERT_TRUE(settled) << settled.message();
  EXPECT_TRUE(settled->converged);
  EXPECT_LE(settled->max_force, 1e-8);
  EXPECT_TRUE(frames.balanced());
  EXPECT_FALSE(frames.onFrames());
  ASSERT_TRUE(solved.balanced());
  EXPECT_EQ(frames.positions().col(node), lifted(1.0));
  // Two balances to the same tolerance of the same pins: a hundred thousandth of the side apart
  // at most (the soft bending modes move that far under forces of the tolerance).
  const double apart = (frames.positions() - solved.positions()).colwise().norm().maxCoeff();
  EXPECT_LT(apart, 1e-5);
  std::printf("frames settled %.3g from the balance of every move solved (%d iterations, %.3f s)\n", apart,
              settled->iterations, settled->seconds);
  // Settled, it stays: settling again changes nothing.
  const Positions balanced = frames.positions();
  ASSERT_TRUE(frames.settle());
  EXPECT_EQ(frames.positions(), balanced);
  // Let go of the corner: the frames start again with the three held corners, which hold.
  const Expected<FrameReport> let_go = frames.frame(held);
  ASSERT_TRUE(let_go) << let_go.message();
  EXPECT_EQ(frames.pins().size(), 3u);
  for (const PullTarget& pin : held)
    EXPECT_EQ(frames.positions().col(frames.mesh().vertex_nodes[pin.vertex]), pin.position);
}

// Nothing pulls a sheet with no pins (weightless, no table): it lies exactly as the state's rigid
// faces, with no solve; a pin that comes later bends it, and let go it lies as the faces again.
TEST(CurvedFollow, AnUnpinnedSheetLiesAsTheStatesFacesAndBendsWhenAPinComes)
{
  const Expected<SeedScene> scene = seedScene(3);  // the flap ade folded over: layers on layers
  ASSERT_TRUE(scene) << scene.message();
  const Paper& paper = scene->paper;
  CurvedSheetFollower follower = makeFollower();
  Expected<CurvedReport> report = follower.solveState(paper, {});
  ASSERT_TRUE(report) << report.message();
  EXPECT_TRUE(report->converged);
  EXPECT_EQ(report->iterations, 0);
  const Positions rigid = placeNodes(follower.mesh(), paper);
  EXPECT_TRUE(follower.positions() == rigid);

  const Vec3 lifted = scene->pullAt(0.05);  // b a little way along the seed's pull
  report = follower.follow({ { scene->fixed, paper.vertices[scene->fixed].folded }, { scene->pulled, lifted } });
  ASSERT_TRUE(report) << report.message();
  EXPECT_TRUE(report->converged) << report->message;
  EXPECT_GT(report->iterations, 0);
  EXPECT_EQ(follower.positions().col(follower.mesh().vertex_nodes[scene->pulled]), lifted);
  EXPECT_EQ(measureCurved(follower.mesh(), paper, follower.positions()).penetrations, 0);

  report = follower.solveState(paper, {}, true);  // let go
  ASSERT_TRUE(report) << report.message();
  EXPECT_TRUE(follower.positions() == rigid);
}

}  // namespace
}  // namespace virtual_origami::core

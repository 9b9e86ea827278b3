#include <gtest/gtest.h>

#include <random>

#include "test_models.h"
#include "virtual_origami/core/metrics.h"
#include "virtual_origami/core/session.h"
#include "virtual_origami/core/tessellations.h"
#include "virtual_origami/solvers/crease_driver_factory.h"
#include "virtual_origami/solvers/newton_solver.h"
#include "virtual_origami/solvers/solver_factory.h"

using namespace virtual_origami::core;
using namespace virtual_origami::core::test;

namespace
{
/// A random crease or rotation; returns whether it was committed.
bool randomOperation(Session& session, std::mt19937& rng)
{
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const Paper& paper = session.paper();
  const int face = static_cast<int>(rng() % paper.faces.size());
  if (rng() % 3 == 0)
  {
    // A line through a random point of a random face, in a random direction in its plane.
    const Vec3 n = paper.faceNormal(face);
    const Vec3 centre = paper.faceCentroid(face);
    const Vec3 u = n.unitOrthogonal();
    const Vec3 w = n.cross(u);
    const double a = 2 * M_PI * unit(rng);
    const Vec3 dir = std::cos(a) * u + std::sin(a) * w;
    CreaseRequest request;
    request.start = centre - 3 * paper.scale() * dir;
    request.end = centre + 3 * paper.scale() * dir;
    return session.crease(request).ok();
  }
  RotateRequest request;
  request.face = face;
  request.click = paper.faceCentroid(face) + 1e-3 * Vec3(unit(rng), unit(rng), 0);
  request.angle = (unit(rng) * 2 - 1) * M_PI;
  return session.rotate(request, true).ok();
}

/// A generated 1,100-vertex Miura-ori's corner face turned about its slanted crease: a turn the
/// solver follows, guided (from 1,000 vertices up).
struct MiuraCornerTurn
{
  Paper flat = tessellationWithVertices(TessellationKind::Miura, 1100).value().paper;
  int axis = test::slantedCreaseOf(flat, 0);
  RotateRequest request = [this] {
    RotateRequest r;
    r.face = 0;
    r.axis_edge = axis;
    return r;
  }();
};

/// The newton solver (balanced to `tolerance`) and the quasi_newton driver, as paper_model sets
/// them.
void equipForTurns(Session& session, double tolerance = SolveLimits{}.tolerance)
{
  std::shared_ptr<ShapeSolver> solver = makeSolver("newton");
  solver->setLimits(SolveLimits{ tolerance, 1000, 0.0 });
  session.setSolver(solver);
  session.setCreaseDrivers(makeCreaseDriver("quasi_newton"));
}

/// The session's last operation with where its vertices ended, as a recording carries it.
Operation recordedLast(const Session& session)
{
  Operation recorded = session.history().log.back();
  for (const Vertex& v : session.paper().vertices)
    recorded.folded.push_back(v.folded);
  return recorded;
}

void expectWithinOfTheSheet(const Paper& a, const Paper& b, double share)
{
  for (size_t v = 0; v < a.vertices.size(); ++v)
    EXPECT_LE((a.vertices[v].folded - b.vertices[v].folded).norm(), share * a.scale()) << "vertex " << v;
}
}  // namespace

TEST(Session, FailuresKeepTheRevisionAndThePaper)
{
  Session session;
  CreaseRequest miss;
  miss.start = p3(5, 5);
  miss.end = p3(6, 6);
  EXPECT_FALSE(session.crease(miss).ok());
  EXPECT_EQ(session.revision(), 0u);
  EXPECT_TRUE(session.paper() == Paper::square(1.0));
  EXPECT_FALSE(session.undo().ok());
  EXPECT_FALSE(session.redo().ok());
  EXPECT_FALSE(session.reset(NAN).ok());
  EXPECT_FALSE(session.reset(-1).ok());
  EXPECT_EQ(session.revision(), 0u);
  EXPECT_TRUE(session.log().empty());
}

TEST(Session, PreviewsStayOutOfHistory)
{
  Session session;
  CreaseRequest line;
  line.start = p3(0.5, -1);
  line.end = p3(0.5, 2);
  ASSERT_TRUE(session.crease(line).ok());
  const Paper creased = session.paper();
  RotateRequest request;
  request.click = p3(0.8, 0.5);
  for (double angle : { 0.1, 0.5, 1.0 })
  {
    request.angle = angle;
    ASSERT_TRUE(session.rotate(request, false).ok());
    ASSERT_TRUE(session.preview().has_value());
    EXPECT_TRUE(session.paper() == creased);
    EXPECT_EQ(session.revision(), 1u);
  }
  const int axis = session.rotate(request, true)->axis_edge;
  EXPECT_EQ(session.revision(), 2u);
  EXPECT_FALSE(session.preview().has_value());
  EXPECT_NEAR(session.paper().edges[axis].fold_angle, 1.0, 1e-12);  // not 1.6: previews don't add up
  ASSERT_EQ(session.log().size(), 2u);
  EXPECT_EQ(session.log()[1].kind, Operation::Kind::Rotate);
  EXPECT_EQ(session.log()[1].rotate.axis_edge, axis);
  ASSERT_TRUE(session.undo().ok());
  EXPECT_TRUE(session.paper() == creased);
}

TEST(Session, HundredRandomOperationsUndoAndRedoBitIdentically)
{
  std::mt19937 rng(20061);
  Session session;
  std::vector<Paper> states{ session.paper() };
  while (states.size() < 101)
    if (randomOperation(session, rng))
      states.push_back(session.paper());
  for (size_t i = states.size() - 1; i > 0; --i)
  {
    ASSERT_TRUE(session.undo().ok());
    ASSERT_TRUE(session.paper() == states[i - 1]) << "undo to state " << i - 1;
  }
  EXPECT_FALSE(session.undo().ok());
  for (size_t i = 1; i < states.size(); ++i)
  {
    ASSERT_TRUE(session.redo().ok());
    ASSERT_TRUE(session.paper() == states[i]) << "redo to state " << i;
  }
  EXPECT_FALSE(session.redo().ok());
  // A new operation after undo drops the redo branch.
  ASSERT_TRUE(session.undo().ok());
  ASSERT_TRUE(session.reset(2.0).ok());
  EXPECT_FALSE(session.canRedo());
}

TEST(Session, ReplayingTheLogReproducesTheState)
{
  std::mt19937 rng(7);
  Session session;
  for (int committed = 0; committed < 40;)
    committed += randomOperation(session, rng) ? 1 : 0;
  ASSERT_TRUE(session.undo().ok());
  ASSERT_TRUE(session.undo().ok());
  ASSERT_TRUE(session.redo().ok());
  Session replay;
  for (const Operation& op : session.log())
    ASSERT_TRUE(replay.apply(op).ok()) << kindName(op.kind);
  EXPECT_TRUE(replay.paper() == session.paper());
  EXPECT_EQ(replay.revision(), session.revision());
}

TEST(Session, InvariantsHoldAfterThousandsOfRandomCreasesAndRotations)
{
  std::mt19937 rng(2006);
  Session session;
  int creases = 0, rotations = 0, refused = 0;
  for (int step = 0; creases + rotations < 1200 && step < 8000; ++step)
  {
    if (session.paper().faces.size() > 200)
    {
      ASSERT_TRUE(session.reset(1.0).ok());  // keep the sheet at a size folding keeps to
    }
    const Paper before = session.paper();
    const uint64_t revision = session.revision();
    const size_t logged = session.log().size();
    if (randomOperation(session, rng))
    {
      (session.log().back().kind == Operation::Kind::Crease ? creases : rotations) += 1;
      ASSERT_EQ(session.log().size(), logged + 1);
      const ValidityReport report = checkValidity(session.paper());
      ASSERT_TRUE(report.ok()) << "step " << step << ":\n" << report.summary();
    }
    else
    {
      ++refused;
      ASSERT_TRUE(session.paper() == before) << "a refused operation changed the paper at step " << step;
      ASSERT_EQ(session.revision(), revision);
    }
  }
  EXPECT_GE(creases + rotations, 1000);
  EXPECT_GE(creases, 300);
  EXPECT_GE(rotations, 300);
  RecordProperty("creases", creases);
  RecordProperty("rotations", rotations);
  RecordProperty("refused", refused);
}

TEST(Session, AChangeComputedFromAnOlderRevisionIsRefused)
{
  Session session;
  CreaseRequest diagonal;
  diagonal.start = p3(0, 0);
  diagonal.end = p3(1, 1);
  auto first = computeCrease(session.workspace(), diagonal);
  ASSERT_TRUE(first) << first.message();
  CreaseRequest other;
  other.start = p3(0, 1);
  other.end = p3(1, 0);
  auto second = computeCrease(session.workspace(), other);  // from the same revision
  ASSERT_TRUE(second) << second.message();
  EXPECT_EQ(first->change.operation.revision, 1u);
  ASSERT_TRUE(session.commit(std::move(first->change)));
  const Paper after_first = session.paper();
  const Status stale = session.commit(std::move(second->change));
  EXPECT_FALSE(stale);
  EXPECT_FALSE(stale.message().empty());
  EXPECT_EQ(session.revision(), 1u);
  EXPECT_EQ(session.log().size(), 1u);
  EXPECT_TRUE(session.paper() == after_first);
  // A preview computed before a commit is not shown after it.
  auto preview = computeCrease(session.workspace(), other);
  ASSERT_TRUE(preview);
  ASSERT_TRUE(session.undo());
  EXPECT_FALSE(session.setPreview(std::move(preview->change)));
  EXPECT_FALSE(session.preview().has_value());
}

TEST(Session, APullOfNothingIsRefused)
{
  Session session;
  EXPECT_FALSE(session.pull({}));
  EXPECT_EQ(session.revision(), 0u);
  EXPECT_TRUE(session.log().empty());
}

TEST(Session, TheHistoryStaysWithinItsMemoryLimitOldestFirst)
{
  Session session;
  std::vector<Paper> states{ session.paper() };
  for (int i = 1; i <= 8; ++i)
  {
    CreaseRequest line;
    line.start = p3(i / 9.0, -0.1);
    line.end = p3(i / 9.0, 1.1);
    ASSERT_TRUE(session.crease(line));
    states.push_back(session.paper());
  }
  size_t all = 0;
  for (size_t i = 0; i + 1 < states.size(); ++i)
    all += approximateBytes(states[i]);
  EXPECT_EQ(session.historyBytes(), all);
  // Room for the three newest undo states only.
  const size_t three = approximateBytes(states[5]) + approximateBytes(states[6]) + approximateBytes(states[7]);
  session.setHistoryLimit(three);
  EXPECT_EQ(session.forgottenStates(), 5u);
  EXPECT_LE(session.historyBytes(), three);
  for (int back = 7; back >= 5; --back)
  {
    ASSERT_TRUE(session.undo());
    EXPECT_TRUE(session.paper() == states[back]);
  }
  const Status none = session.undo();
  EXPECT_FALSE(none);
  EXPECT_NE(none.message().find("memory"), std::string::npos) << none.message();
  // Redo still reaches the newest state, and the log keeps every operation.
  for (int forward = 6; forward <= 8; ++forward)
  {
    ASSERT_TRUE(session.redo());
    EXPECT_TRUE(session.paper() == states[forward]);
  }
  EXPECT_EQ(session.log().size(), 8u + 3u + 3u);
}

// Found by the round-3 probe: undo at the start of history and squash on a flat sheet answered
// success and made new revisions.
TEST(Session, NothingToUndoAndNothingToSquashAreRefusedWithoutARevision)
{
  Session session;
  EXPECT_FALSE(session.undo());
  EXPECT_FALSE(session.redo());
  const Expected<SquashResult> squashed = session.squash();
  EXPECT_FALSE(squashed);
  EXPECT_EQ(session.revision(), 0u);
  EXPECT_TRUE(session.log().empty());
  // After a load: one undo goes back to the sheet before it, the next is refused.
  Paper loaded = Paper::square(2.0);
  ASSERT_TRUE(session.load(loaded, "two.fold"));
  ASSERT_TRUE(session.undo());
  const uint64_t revision = session.revision();
  EXPECT_FALSE(session.undo());
  EXPECT_EQ(session.revision(), revision);
  // A session resumed from a history with nothing to undo.
  Session resumed(session.history());
  ASSERT_TRUE(resumed.redo());
  ASSERT_TRUE(resumed.undo());
  EXPECT_FALSE(resumed.undo());
  EXPECT_EQ(resumed.revision(), revision + 2);
}

// Found by the round-3 probe: loads answered "loaded" and the paper was as before.
TEST(Session, ALoadOfThePaperAsItIsIsRefused)
{
  Session session;
  const Status same = session.load(Paper::square(1.0), "same.fold");
  ASSERT_FALSE(same);
  EXPECT_NE(same.message().find(kNothingLoaded), std::string::npos) << same.message();
  EXPECT_EQ(session.revision(), 0u);
  // The check a node makes before it journals says the same.
  const Expected<Change> change = computeLoad(0, Paper::square(1.0), "same.fold");
  ASSERT_TRUE(change);
  EXPECT_FALSE(session.check(*change));
  EXPECT_TRUE(session.load(Paper::square(2.0), "other.fold"));
  EXPECT_EQ(session.revision(), 1u);
}

/// A drag's turn previews go on from each other (from 1,000 vertices up), each starting where
/// the previews before it lead. The commit at the last preview's angle is that preview, solved no
/// further; within the tolerance of the same turn committed with no previews (one rigid state);
/// and a replay of it with the positions it recorded (Operation::folded) lands on it bit for bit.
TEST(Session, ATurnCommittedAfterItsPreviewsIsItsLastPreviewAndItsReplay)
{
  MiuraCornerTurn turn;
  const Paper& flat = turn.flat;
  const int axis = turn.axis;
  RotateRequest& request = turn.request;
  ASSERT_GE(flat.vertices.size(), TurnGuide{}.min_vertices);
  ASSERT_GE(axis, 0);
  // Balanced to 1e-12: near the flat sheet's singular state a strain of 1e-10 leaves the
  // vertices free along the soft mode by some 1e-9 of the sheet, by where each solve started
  // (measured 1.5e-9 between a drag's previews and the turn at once).
  Session dragged(flat), at_once(flat), replay(flat);
  for (Session* session : { &dragged, &at_once, &replay })
    equipForTurns(*session, 1e-12);
  for (int degrees : { 4, 6, 8 })
  {
    request.angle = degrees * M_PI / 180;
    const Expected<RotateResult> preview = dragged.rotate(request, false);
    ASSERT_TRUE(preview) << preview.message();
    ASSERT_TRUE(dragged.preview().has_value());
    EXPECT_LT(edgeStrain(*dragged.preview()).max, 1e-11) << degrees << "°";
    EXPECT_NEAR(dragged.preview()->edges[axis].fold_angle, request.angle, 1e-12);
  }
  const Paper last_preview = *dragged.preview();
  const Expected<RotateResult> committed = dragged.rotate(request, true);
  ASSERT_TRUE(committed) << committed.message();
  EXPECT_EQ(committed->solve.iterations, 0);
  for (size_t v = 0; v < flat.vertices.size(); ++v)
    ASSERT_EQ(dragged.paper().vertices[v].folded, last_preview.vertices[v].folded) << "vertex " << v;
  ASSERT_TRUE(at_once.rotate(request, true).ok());
  expectWithinOfTheSheet(dragged.paper(), at_once.paper(), 1e-9);
  Operation recorded = recordedLast(dragged);
  ASSERT_EQ(recorded.kind, Operation::Kind::Rotate);
  ASSERT_TRUE(replay.apply(recorded).ok());
  EXPECT_TRUE(replay.paper() == dragged.paper());
  // Recorded positions of another paper are refused, the model untouched.
  recorded.folded.pop_back();
  Session wrong(flat);
  wrong.setSolver(makeSolver("newton"));
  const Status refused = wrong.apply(recorded);
  ASSERT_FALSE(refused);
  EXPECT_NE(refused.message().find("positions for"), std::string::npos) << refused.message();
  EXPECT_TRUE(wrong.paper() == flat);
}

/// A drag's first preview, started by the guide, is balanced to the solver's own tolerance even
/// where previews are looser: the later ones extrapolate from it. Left at the looser strain, a
/// 5,000-vertex Miura-ori's next previews took 3, 4 and 2 of Newton's steps; from a tight first
/// one they take at most one each (docs/SOLVERS.md "The drag's first preview balanced tight").
TEST(Session, ADragsFirstTurnPreviewIsBalancedToTheSolversToleranceForTheNextToFollow)
{
  MiuraCornerTurn turn;
  turn.flat = tessellationWithVertices(TessellationKind::Miura, 5000).value().paper;
  turn.request.axis_edge = test::slantedCreaseOf(turn.flat, 0);
  ASSERT_GE(turn.request.axis_edge, 0);
  Session session(turn.flat);
  equipForTurns(session);
  session.setTurnPreviewTolerance(1e-8);
  for (double degrees : { 0.5, 1.0, 1.5, 2.0 })
  {
    turn.request.angle = degrees * M_PI / 180;
    const Expected<RotateResult> preview = session.rotate(turn.request, false);
    ASSERT_TRUE(preview) << preview.message();
    if (degrees == 0.5)
      EXPECT_LE(preview->solve.max_strain, SolveLimits{}.tolerance);
    else
      EXPECT_LE(preview->solve.iterations, 1) << degrees << "°";
    EXPECT_LE(preview->solve.max_strain, 1e-8) << degrees << "°";
  }
}

/// With a looser balance for previews (paper_model's turn_preview_tolerance), a drag's previews
/// converge at that strain in fewer of Newton's steps; the commit at the last preview's angle is
/// balanced from there to the solver's own tolerance, and its replay lands on it bit for bit.
TEST(Session, ALooselyBalancedTurnPreviewIsCommittedToTheSolversTolerance)
{
  MiuraCornerTurn turn;
  const int axis = turn.axis;
  RotateRequest& request = turn.request;
  ASSERT_GE(axis, 0);
  Session loose(turn.flat), tight(turn.flat), replay(turn.flat);
  for (Session* session : { &loose, &tight, &replay })
    equipForTurns(*session);
  loose.setTurnPreviewTolerance(1e-8);
  int loose_iterations = 0, tight_iterations = 0;
  for (int degrees : { 2, 4, 6, 8, 10 })
  {
    request.angle = degrees * M_PI / 180;
    const Expected<RotateResult> l = loose.rotate(request, false), t = tight.rotate(request, false);
    ASSERT_TRUE(l) << l.message();
    ASSERT_TRUE(t) << t.message();
    EXPECT_LE(l->solve.max_strain, 1e-8) << degrees << "°";
    EXPECT_LE(t->solve.max_strain, 1e-10) << degrees << "°";
    EXPECT_NEAR(loose.preview()->edges[axis].fold_angle, request.angle, 1e-12);
    loose_iterations += l->solve.iterations;
    tight_iterations += t->solve.iterations;
  }
  EXPECT_LT(loose_iterations, tight_iterations);
  const Expected<RotateResult> committed = loose.rotate(request, true);
  ASSERT_TRUE(committed) << committed.message();
  EXPECT_GT(committed->solve.iterations, 0);  // balanced further than the preview was
  EXPECT_LE(committed->solve.max_strain, 1e-10);
  EXPECT_LT(edgeStrain(loose.paper()).max, 1e-9);
  EXPECT_NEAR(loose.paper().edges[axis].fold_angle, request.angle, 1e-12);
  ASSERT_TRUE(replay.apply(recordedLast(loose)).ok());
  EXPECT_TRUE(replay.paper() == loose.paper());
}

/// A drag's loosely balanced previews start at the frame's lower damping floor
/// (NewtonOptions::frame_damping): near the flat sheet their steps at the solver's own floor creep
/// until the floor is lowered. On a drag in 1° steps the previews take fewer of Newton's steps
/// in all, each balanced to the preview's strain, and the commit is balanced to the solver's.
TEST(Session, ALooseTurnPreviewStartsAtTheFramesLowerDampingFloor)
{
  MiuraCornerTurn turn;
  RotateRequest& request = turn.request;
  ASSERT_GE(turn.axis, 0);
  int iterations[2] = { 0, 0 };
  for (int floor_kept : { 0, 1 })
  {
    NewtonOptions options;
    if (floor_kept)
      options.frame_damping = options.min_damping;
    auto solver = std::make_shared<NewtonSolver>(options);
    solver->setLimits(SolveLimits{ SolveLimits{}.tolerance, 1000, 0.0 });
    Session session(turn.flat);
    session.setSolver(solver);
    session.setCreaseDrivers(makeCreaseDriver("quasi_newton"));
    session.setTurnPreviewTolerance(1e-8);
    for (int degrees = 1; degrees <= 10; ++degrees)
    {
      request.angle = degrees * M_PI / 180;
      const Expected<RotateResult> preview = session.rotate(request, false);
      ASSERT_TRUE(preview) << preview.message();
      EXPECT_LE(preview->solve.max_strain, 1e-8) << degrees << "°";
      iterations[floor_kept] += preview->solve.iterations;
    }
    const Expected<RotateResult> committed = session.rotate(request, true);
    ASSERT_TRUE(committed) << committed.message();
    EXPECT_LT(edgeStrain(session.paper()).max, 1e-9);
  }
  EXPECT_LT(iterations[0], iterations[1]) << iterations[0] << " against " << iterations[1];
}

/// A commit at another angle than the drag's last preview goes on from it (the branch the user
/// saw) to the commit's angle; a replay with the positions it recorded lands on it bit for bit.
TEST(Session, ATurnCommittedPastItsLastPreviewGoesOnFromItAndReplaysBitForBit)
{
  MiuraCornerTurn turn;
  const int axis = turn.axis;
  RotateRequest& request = turn.request;
  ASSERT_GE(axis, 0);
  // Balanced to 1e-12, as in ATurnCommittedAfterItsPreviewsIsItsLastPreviewAndItsReplay.
  Session dragged(turn.flat), at_once(turn.flat), replay(turn.flat);
  for (Session* session : { &dragged, &at_once, &replay })
    equipForTurns(*session, 1e-12);
  for (int degrees : { 4, 6 })
  {
    request.angle = degrees * M_PI / 180;
    ASSERT_TRUE(dragged.rotate(request, false).ok());
  }
  request.angle = 9 * M_PI / 180;
  const Expected<RotateResult> committed = dragged.rotate(request, true);
  ASSERT_TRUE(committed) << committed.message();
  EXPECT_LT(edgeStrain(dragged.paper()).max, 1e-9);
  EXPECT_NEAR(dragged.paper().edges[axis].fold_angle, request.angle, 1e-12);
  ASSERT_TRUE(at_once.rotate(request, true).ok());
  expectWithinOfTheSheet(dragged.paper(), at_once.paper(), 1e-9);
  ASSERT_TRUE(replay.apply(recordedLast(dragged)).ok());
  EXPECT_TRUE(replay.paper() == dragged.paper());
}

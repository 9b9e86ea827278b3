// The session's fold on chosen creases (flat_fold) and drag of a vertex (drag_vertex): commits
// and previews, refusals that change nothing, undo/redo over them, the log re-applied, the
// journal, and the preview frames of a fold animated from the paper as it is.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>

#include "test_models.h"
#include "virtual_origami/core/flat_fold.h"
#include "virtual_origami/core/metrics.h"
#include "virtual_origami/core/session.h"
#include "virtual_origami/core/session_journal.h"
#include "virtual_origami/solvers/solver_factory.h"

using namespace virtual_origami::core;
using namespace virtual_origami::core::test;

namespace
{
const Vec2 kCentre(0.5, 0.5);

FlatFoldRequest diagonalFold(double angle = M_PI)
{
  return { { { v2(0, 0), v2(1, 1), angle } }, v2(0.9, 0.1) };
}

/// The creased square folded in half on both diagonals (a triangle of four layers), and the
/// squash of its top flap (the first squash of the crane's square base).
const Vec2 kSquashFixed(0.9, 0.3);
Paper fourLayerTriangle()
{
  Paper paper = creasedSquare();
  EXPECT_TRUE(flatFold(paper, { { { v2(0, 0), v2(1, 1), M_PI } }, kSquashFixed }).ok());
  EXPECT_TRUE(flatFold(paper, { { { v2(1, 0), kCentre, M_PI }, { kCentre, v2(0, 1), -M_PI } }, kSquashFixed }).ok());
  return paper;
}
FlatFoldRequest squash()
{
  return { { { v2(0, 0), kCentre, 0.0 }, { v2(1, 0), kCentre, 0.0 }, { v2(0.5, 0), kCentre, M_PI },
             { v2(0, 0.5), kCentre, M_PI } },
           kSquashFixed };
}

int faceAt(const Paper& paper, const Vec2& p)
{
  for (size_t f = 0; f < paper.faces.size(); ++f)
  {
    bool inside = true;
    const std::vector<int>& vs = paper.faces[f].vertices;
    for (size_t i = 0; i < vs.size(); ++i)
    {
      const Vec2 a = paper.vertices[vs[i]].crease_pattern, b = paper.vertices[vs[(i + 1) % vs.size()]].crease_pattern;
      const Vec2 ab = b - a, ap = p - a;
      inside = inside && ab.x() * ap.y() - ab.y() * ap.x() > 0;
    }
    if (inside)
      return static_cast<int>(f);
  }
  return -1;
}

double largestMove(const Paper& a, const Paper& b)
{
  double d = 0;
  for (size_t v = 0; v < a.vertices.size(); ++v)
    d = std::max(d, (a.vertices[v].folded - b.vertices[v].folded).norm());
  return d;
}

/// The corner (1, 0) swung by `angle` about the crease x = 0.5 (valley: up through +z).
Vec3 swung(double angle) { return { 0.5 + 0.5 * std::cos(angle), 0.0, 0.5 * std::sin(angle) }; }

std::string tempPath(const std::string& name)
{
  return (std::filesystem::temp_directory_path() / ("vo_fold_drag_" + std::to_string(::getpid()) + "_" + name)).string();
}
}  // namespace

TEST(FlatFoldSession, ACommitIsOneHistoryEntryThatUndoAndRedoStepOver)
{
  Session session(creasedSquare());
  const Paper before = session.paper();
  const Expected<FlatFoldResult> folded = session.flatFold(diagonalFold());
  ASSERT_TRUE(folded.ok()) << folded.message();
  EXPECT_EQ(session.revision(), 1u);
  ASSERT_EQ(session.log().size(), 1u);
  const Operation& op = session.log().back();
  EXPECT_EQ(op.kind, Operation::Kind::FlatFold);
  EXPECT_STREQ(kindName(op.kind), "flat_fold");
  ASSERT_EQ(op.flat_fold.creases.size(), 1u);
  EXPECT_EQ(op.flat_fold.creases[0].angle, M_PI);
  EXPECT_EQ(op.flat_fold.fixed_point, v2(0.9, 0.1));
  EXPECT_EQ(folded->moved_faces.size(), 4u);  // the upper-left half: two triangles of each quadrant it crosses
  // The corner (0, 1) lies on (1, 0); the lower-right half where it was.
  EXPECT_LT((session.paper().vertices[session.paper().vertexAt(v2(0, 1))].folded - p3(1, 0)).norm(), 1e-12);
  EXPECT_EQ(session.paper().vertices[session.paper().vertexAt(v2(1, 0))].folded, p3(1, 0));  // the fixed face, exactly
  expectValid(session.paper());
  const Paper after = session.paper();

  ASSERT_TRUE(session.undo().ok());
  EXPECT_TRUE(session.paper() == before);
  ASSERT_TRUE(session.redo().ok());
  EXPECT_TRUE(session.paper() == after);
  EXPECT_EQ(session.revision(), 3u);
}

TEST(FlatFoldSession, RefusalsKeepThePaperAndTheRevision)
{
  Session session(creasedSquare());
  ASSERT_TRUE(session.flatFold(diagonalFold()).ok());
  const Paper before = session.paper();
  const uint64_t revision = session.revision();
  const auto refused = [&](const FlatFoldRequest& request, const std::string& words, bool commit = true) {
    const Expected<FlatFoldResult> r = session.flatFold(request, commit, 0.5);
    EXPECT_FALSE(r.ok());
    EXPECT_NE(r.message().find(words), std::string::npos) << r.message();
    EXPECT_TRUE(session.paper() == before);
    EXPECT_EQ(session.revision(), revision);
    EXPECT_FALSE(session.preview().has_value());
  };
  for (bool commit : { true, false })
  {
    refused({ {}, v2(0.9, 0.1) }, "no creases", commit);
    refused({ { { v2(0.5, 0), kCentre, M_PI } }, v2(0.9, 0.1) }, "the chosen creases do not fold flat", commit);
    refused({ { { v2(0.1, 0.2), v2(0.2, 0.4), M_PI } }, v2(0.9, 0.1) }, "runs along no crease", commit);
    refused({ { { v2(0, 0), v2(1, 1), NAN } }, v2(0.9, 0.1) }, "non-finite", commit);
    refused({ { { v2(0, 0), v2(1, 1), 0.0 } }, v2(NAN, 0.1) }, "not a finite point", commit);
    refused({ { { v2(0, 0), v2(1, 1), 0.0 } }, v2(2, 2) }, "off the sheet", commit);
    refused({ { { v2(0, 0), v2(1, 1), 4.0 } }, v2(0.9, 0.1) }, "beyond", commit);
    refused(diagonalFold(), "moves nothing", commit);  // folded there already
  }
  const Expected<FlatFoldResult> r = session.flatFold(diagonalFold(0.0), false, 1.5);
  EXPECT_FALSE(r.ok());
  EXPECT_NE(r.message().find("from 0 to 1"), std::string::npos) << r.message();

  // A pin the fold would move: refused; a pin it leaves alone: folded.
  const int corner = session.paper().vertexAt(v2(0, 1));
  session.setHeldVertices({ corner });
  refused(diagonalFold(0.0), "pinned", true);
  session.setHeldVertices({ session.paper().vertexAt(v2(1, 0)) });
  EXPECT_TRUE(session.flatFold(diagonalFold(0.0)).ok());
}

TEST(FlatFoldSession, PreviewsStayOutOfHistoryAndShowTheWayFromThePaperNow)
{
  Session session(creasedSquare());
  const Paper before = session.paper();
  const Expected<FlatFoldResult> preview = session.flatFold(diagonalFold(), false, 0.5);
  ASSERT_TRUE(preview.ok()) << preview.message();
  EXPECT_EQ(session.revision(), 0u);
  EXPECT_TRUE(session.log().empty());
  EXPECT_TRUE(session.paper() == before);
  ASSERT_TRUE(session.preview().has_value());
  // Half way a single crease is at 90 degrees: the corner (0, 1) straight above the diagonal.
  const Paper& frame = *session.preview();
  EXPECT_LT((frame.vertices[frame.vertexAt(v2(0, 1))].folded - p3(0.5, 0.5, std::sqrt(0.5))).norm(), 1e-12);
  EXPECT_LT(edgeStrain(frame).max, 1e-12);  // one crease: every frame is rigid
  // A commit then folds the whole way from the committed paper, and drops the preview.
  ASSERT_TRUE(session.flatFold(diagonalFold()).ok());
  EXPECT_FALSE(session.preview().has_value());
  EXPECT_EQ(session.revision(), 1u);
}

TEST(FlatFoldFrame, IsThePaperAtZeroTheFoldAtOneAndNeverMovesTheFixedFace)
{
  const Paper paper = fourLayerTriangle();
  Paper folded = paper;
  ASSERT_TRUE(flatFold(folded, squash()).ok());

  const Expected<Paper> start = flatFoldFrame(paper, squash(), 0.0);
  ASSERT_TRUE(start.ok()) << start.message();
  EXPECT_TRUE(*start == paper);
  const Expected<Paper> end = flatFoldFrame(paper, squash(), 1.0);
  ASSERT_TRUE(end.ok()) << end.message();
  EXPECT_TRUE(*end == folded);

  const int fixed = faceAt(paper, kSquashFixed);
  ASSERT_GE(fixed, 0);
  Paper previous = paper;
  for (int k = 1; k < 20; ++k)
  {
    const double fraction = k / 20.0;
    SCOPED_TRACE(fraction);
    Expected<Paper> frame = flatFoldFrame(paper, squash(), fraction);
    ASSERT_TRUE(frame.ok()) << frame.message();
    for (int v : paper.faces[fixed].vertices)
      EXPECT_EQ(frame->vertices[v].folded, paper.vertices[v].folded);
    for (const Vertex& v : frame->vertices)
      EXPECT_TRUE(v.folded.allFinite());
    // The faces turn on the way: no vertex jumps between frames 1/20 apart (the flap's corner
    // sweeps a half turn of radius at most the sheet's half diagonal, π·0.71/20 ≈ 0.11 a frame).
    EXPECT_LT(largestMove(*frame, previous), 0.2);
    // Every crease the fold sets is on its way, the others where they were.
    for (size_t e = 0; e < paper.edges.size(); ++e)
      EXPECT_NEAR(frame->edges[e].fold_angle,
                  paper.edges[e].fold_angle + fraction * (folded.edges[e].fold_angle - paper.edges[e].fold_angle),
                  1e-9);
    previous = *frame;
  }
  // Continuous at both ends.
  EXPECT_LT(largestMove(*flatFoldFrame(paper, squash(), 1e-7), paper), 1e-6);
  EXPECT_LT(largestMove(*flatFoldFrame(paper, squash(), 1 - 1e-7), folded), 1e-6);
  // Refused as the fold is.
  EXPECT_FALSE(flatFoldFrame(paper, { { { v2(0.5, 0), kCentre, M_PI } }, kSquashFixed }, 0.5).ok());
  EXPECT_FALSE(flatFoldFrame(paper, squash(), NAN).ok());
  EXPECT_FALSE(flatFoldFrame(paper, squash(), -0.1).ok());
}

TEST(DragVertexSession, TheCornerSwingsAboutTheCreaseAndPinsHold)
{
  std::vector<int> left;
  Session session(creasedInHalf(left));
  session.setSolver(std::shared_ptr<ShapeSolver>(makeSolver("newton")));
  session.setHeldVertices(left);
  const int corner = session.paper().vertexAt(v2(1, 0)), other = session.paper().vertexAt(v2(1, 1));
  const Paper before = session.paper();

  // A preview: drawn, not in history.
  const Expected<PullResult> preview = session.dragVertex({ corner, swung(0.5) }, false);
  ASSERT_TRUE(preview.ok()) << preview.message();
  EXPECT_EQ(session.revision(), 0u);
  EXPECT_TRUE(session.paper() == before);
  ASSERT_TRUE(session.preview().has_value());
  EXPECT_LE((session.preview()->vertices[corner].folded - swung(0.5)).norm(), 1e-9);

  for (int k = 1; k <= 4; ++k)
  {
    const Expected<PullResult> dragged = session.dragVertex({ corner, swung(0.5 * k) });
    ASSERT_TRUE(dragged.ok()) << dragged.message();
    EXPECT_LE(dragged->residual, 1e-9);
  }
  EXPECT_EQ(session.revision(), 4u);
  EXPECT_FALSE(session.preview().has_value());
  const Operation& op = session.log().back();
  EXPECT_EQ(op.kind, Operation::Kind::DragVertex);
  EXPECT_STREQ(kindName(op.kind), "drag_vertex");
  EXPECT_EQ(op.drag.vertex, corner);
  EXPECT_EQ(op.drag.position, swung(2.0));
  const Paper& paper = session.paper();
  EXPECT_LE(edgeStrain(paper).max, 1e-9);
  EXPECT_LE((paper.vertices[other].folded - (swung(2.0) + Vec3(0, 1, 0))).norm(), 1e-8);  // the face turned rigidly
  for (int v : left)
    EXPECT_EQ(paper.vertices[v].folded, before.vertices[v].folded);  // the pins held

  const Paper after = session.paper();
  ASSERT_TRUE(session.undo().ok());
  ASSERT_TRUE(session.undo().ok());
  EXPECT_LE((session.paper().vertices[corner].folded - swung(1.0)).norm(), 1e-9);
  ASSERT_TRUE(session.redo().ok());
  ASSERT_TRUE(session.redo().ok());
  EXPECT_TRUE(session.paper() == after);
}

TEST(DragVertexSession, RefusalsKeepThePaperAndTheRevision)
{
  std::vector<int> left;
  Session session(creasedInHalf(left));
  session.setHeldVertices(left);
  const int corner = session.paper().vertexAt(v2(1, 0));
  const Paper before = session.paper();
  const auto refused = [&](const PullTarget& target, const std::string& words) {
    for (bool commit : { true, false })
    {
      const Expected<PullResult> r = session.dragVertex(target, commit);
      EXPECT_FALSE(r.ok());
      EXPECT_NE(r.message().find(words), std::string::npos) << r.message();
      EXPECT_TRUE(session.paper() == before);
      EXPECT_EQ(session.revision(), 0u);
      EXPECT_FALSE(session.preview().has_value());
    }
  };
  refused({ corner, swung(0.5) }, "solver");  // none set yet
  session.setSolver(std::shared_ptr<ShapeSolver>(makeSolver("newton")));
  refused({ 99, swung(0.5) }, "vertex 99 does not exist");
  refused({ -1, swung(0.5) }, "does not exist");
  refused({ corner, Vec3(NAN, 0, 0) }, "not a finite point");
  refused({ corner, Vec3(0.5, std::numeric_limits<double>::infinity(), 0) }, "not a finite point");
  refused({ left.front(), p3(0.2, 0.2, 0.3) }, "pinned");
  refused({ corner, p3(1.5, 0, 0) }, "no shape of the faces follows");  // the face would stretch
  EXPECT_TRUE(session.log().empty());
}

TEST(FoldAndDragSession, ReplayingTheLogReproducesThePaperAndTheJournalKeepsEveryField)
{
  const auto solver = std::shared_ptr<ShapeSolver>(makeSolver("newton"));
  Session session(creasedSquare());
  session.setSolver(solver);
  const std::string path = tempPath("journal.jsonl");
  SessionJournal journal;
  ASSERT_TRUE(journal.start(path, session).ok());
  const auto record = [&] { ASSERT_TRUE(journal.record(session).ok()); };

  ASSERT_TRUE(session.flatFold({ { { v2(0, 0), v2(1, 1), M_PI } }, kSquashFixed }).ok());
  record();
  ASSERT_TRUE(session.flatFold({ { { v2(1, 0), kCentre, M_PI }, { kCentre, v2(0, 1), -M_PI } }, kSquashFixed }).ok());
  record();
  ASSERT_TRUE(session.flatFold(squash()).ok());
  record();
  ASSERT_TRUE(session.undo().ok());
  record();
  ASSERT_TRUE(session.redo().ok());
  record();
  // Open the squashed flap's free corner a little by hand (the corner (0, 0) lies on (1, 0)).
  const int corner = session.paper().vertexAt(v2(0, 0));
  const Vec3 at = session.paper().vertices[corner].folded;
  const Expected<PullResult> dragged = session.dragVertex({ corner, at + Vec3(0, 0, 0.05) });
  ASSERT_TRUE(dragged.ok()) << dragged.message();
  record();
  RotateRequest turn;
  turn.face = faceAt(session.paper(), v2(0.9, 0.7));
  turn.axis_edge = session.paper().findEdge(session.paper().vertexAt(kCentre), session.paper().vertexAt(v2(1, 1)));
  ASSERT_GE(turn.face, 0);
  ASSERT_GE(turn.axis_edge, 0);
  turn.angle = -0.5;
  turn.carry_stack = false;
  const Expected<RotateResult> turned = session.rotate(turn);
  ASSERT_TRUE(turned.ok()) << turned.message();
  record();
  EXPECT_FALSE(session.log().back().rotate.carry_stack);

  // The log applied again to the same start: the same paper, bit for bit.
  Session again(creasedSquare());
  again.setSolver(solver);
  for (const Operation& op : session.log())
    ASSERT_TRUE(again.apply(op).ok()) << kindName(op.kind);
  EXPECT_LE(largestMove(again.paper(), session.paper()), 1e-12);
  EXPECT_TRUE(again.paper() == session.paper());

  // The journal: the whole history, every field of the new operations.
  const Expected<History> read = readJournal(path);
  ASSERT_TRUE(read.ok()) << read.message();
  EXPECT_TRUE(read->paper == session.paper());
  ASSERT_EQ(read->log.size(), session.log().size());
  for (size_t i = 0; i < read->log.size(); ++i)
  {
    const Operation& a = read->log[i];
    const Operation& b = session.log()[i];
    EXPECT_EQ(a.kind, b.kind);
    EXPECT_EQ(a.revision, b.revision);
    ASSERT_EQ(a.flat_fold.creases.size(), b.flat_fold.creases.size());
    for (size_t k = 0; k < a.flat_fold.creases.size(); ++k)
    {
      EXPECT_EQ(a.flat_fold.creases[k].start, b.flat_fold.creases[k].start);
      EXPECT_EQ(a.flat_fold.creases[k].end, b.flat_fold.creases[k].end);
      EXPECT_EQ(a.flat_fold.creases[k].angle, b.flat_fold.creases[k].angle);
    }
    EXPECT_EQ(a.flat_fold.fixed_point, b.flat_fold.fixed_point);
    EXPECT_TRUE(a.drag == b.drag);
    EXPECT_EQ(a.rotate.carry_stack, b.rotate.carry_stack);
  }
  // And the session resumed from it goes on as the first: undo steps back over the drag.
  Session resumed(*read);
  resumed.setSolver(solver);
  ASSERT_TRUE(resumed.undo().ok());
  ASSERT_TRUE(resumed.undo().ok());
  EXPECT_LE(std::abs(resumed.paper().vertices[corner].folded.z() - at.z()), 1e-12);

  // A journal written before rotations recorded carry_stack reads them as carrying the stack.
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  in.close();
  std::string old = text.str();
  for (size_t at_key; (at_key = old.find("\"carry_stack\":false,")) != std::string::npos;)
    old.erase(at_key, std::string("\"carry_stack\":false,").size());
  for (size_t at_key; (at_key = old.find("\"carry_stack\":true,")) != std::string::npos;)
    old.erase(at_key, std::string("\"carry_stack\":true,").size());
  ASSERT_EQ(old.find("carry_stack"), std::string::npos);
  std::ofstream(path, std::ios::trunc) << old;
  const Expected<History> before_field = readJournal(path);
  std::filesystem::remove(path);
  ASSERT_TRUE(before_field.ok()) << before_field.message();
  ASSERT_EQ(before_field->log.back().kind, Operation::Kind::Rotate);
  EXPECT_TRUE(before_field->log.back().rotate.carry_stack);
}

// A paper of several separate pieces (test/data/patterns/two-pieces.fold: a square with a valley
// diagonal beside a plain square) folds: by assignment, and by turning a face.
#include <memory>
#include <string>

#include <gtest/gtest.h>

#include "virtual_origami/core/assignment_fold.h"
#include "virtual_origami/core/fold_io.h"
#include "virtual_origami/core/rotate.h"
#include "virtual_origami/core/session.h"
#include "virtual_origami/core/validity.h"
#include "virtual_origami/solvers/crease_driver_factory.h"
#include "virtual_origami/solvers/newton_solver.h"
#include "virtual_origami/solvers/solver_factory.h"

namespace virtual_origami::core
{
namespace
{
Paper twoPieces()
{
  const Expected<Paper> paper = loadPaper(std::string(VO_SOURCE_DIR) + "/test/data/patterns/two-pieces.fold");
  EXPECT_TRUE(paper.ok()) << paper.message();
  return paper.ok() ? *paper : Paper{};
}

int diagonalOf(const Paper& paper)
{
  for (size_t e = 0; e < paper.edges.size(); ++e)
    if (paper.edges[e].assignment == Assignment::Valley)
      return static_cast<int>(e);
  return -1;
}

/// Whether the piece's vertices (those with x >= 2 in the crease pattern) lie where they were
/// drawn, flat: as loaded.
bool rightPieceAsDrawn(const Paper& paper)
{
  for (const Vertex& v : paper.vertices)
    if (v.crease_pattern.x() >= 2 - 1e-12 &&
        !((v.folded - Vec3(v.crease_pattern.x(), v.crease_pattern.y(), 0)).norm() <= 1e-9))
      return false;
  return true;
}

TEST(SeveralPieces, FoldByAssignmentFoldsTheCreasedPiece)
{
  Paper paper = twoPieces();
  ASSERT_TRUE(checkValidity(paper).ok()) << checkValidity(paper).summary();
  const int diagonal = diagonalOf(paper);
  ASSERT_GE(diagonal, 0);
  const auto driver = makeCreaseDriver("quasi_newton");
  NewtonSolver rigid;
  AssignmentFoldRequest request;
  request.fraction = 0.5;
  const Expected<AssignmentFoldResult> result = foldByAssignment(paper, request, *driver, &rigid);
  ASSERT_TRUE(result) << result.message();
  EXPECT_TRUE(result->rigid);
  EXPECT_LE(result->max_strain, 1e-9);
  EXPECT_NEAR(M_PI / 2, paper.edges[diagonal].fold_angle, 1e-6);
  EXPECT_TRUE(checkValidity(paper).ok()) << checkValidity(paper).summary();
  // Each piece is held by its first face: the driver balances (no piece drifts with nothing to
  // hold it), and the piece without a crease stays as drawn.
  EXPECT_TRUE(result->solve.converged) << result->solve.message;
  EXPECT_TRUE(rightPieceAsDrawn(paper));
}

TEST(SeveralPieces, RotateTurnsAFaceAboutItsCrease)
{
  Paper paper = twoPieces();
  const int diagonal = diagonalOf(paper);
  ASSERT_GE(diagonal, 0);
  const std::unique_ptr<ShapeSolver> solver = makeSolver("newton");
  RotateRequest request;
  request.face = paper.edges[diagonal].faces[0];
  request.axis_edge = diagonal;
  request.angle = M_PI / 3;
  const Expected<RotateResult> result = rotate(paper, request, solver.get());
  ASSERT_TRUE(result) << result.message();
  EXPECT_NEAR(M_PI / 3, paper.edges[diagonal].fold_angle, 1e-9);
  EXPECT_TRUE(checkValidity(paper).ok()) << checkValidity(paper).summary();
  EXPECT_TRUE(rightPieceAsDrawn(paper));
}

TEST(SeveralPieces, ASessionLoadsFoldsTurnsAndUndoes)
{
  Session session;
  session.setSolver(makeSolver("newton"));
  session.setCreaseDrivers(makeCreaseDriver("quasi_newton"));
  const Paper loaded = twoPieces();
  ASSERT_TRUE(session.load(loaded, "two-pieces.fold"));
  const Expected<AssignmentFoldResult> folded = session.foldByAssignment(0.5);
  ASSERT_TRUE(folded) << folded.message();
  const int diagonal = diagonalOf(session.paper());
  EXPECT_NEAR(M_PI / 2, session.paper().edges[diagonal].fold_angle, 1e-6);
  RotateRequest turn;
  turn.face = session.paper().edges[diagonal].faces[1];
  turn.axis_edge = diagonal;
  turn.angle = -M_PI / 6;
  const Expected<RotateResult> turned = session.rotate(turn);
  ASSERT_TRUE(turned) << turned.message();
  EXPECT_NEAR(M_PI / 3, session.paper().edges[diagonal].fold_angle, 1e-6);
  EXPECT_TRUE(checkValidity(session.paper()).ok()) << checkValidity(session.paper()).summary();
  ASSERT_TRUE(session.undo());
  ASSERT_TRUE(session.undo());
  EXPECT_EQ(loaded, session.paper());
}

}  // namespace
}  // namespace virtual_origami::core

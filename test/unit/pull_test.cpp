// Pulling vertices to points (pins following frames): closed-form folds, refusals that
// change nothing, the operation in the session's log and journal.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <limits>
#include <memory>

#include "test_models.h"
#include "virtual_origami/core/face_orders.h"
#include "virtual_origami/core/metrics.h"
#include "virtual_origami/core/pull.h"
#include "virtual_origami/core/session.h"
#include "virtual_origami/core/session_journal.h"
#include "virtual_origami/solvers/solver_factory.h"

using namespace virtual_origami::core;
using namespace virtual_origami::core::test;

namespace
{
/// The corner (1, 0) swung by `angle` about the crease x = 0.5 (valley: up through +z).
Vec3 swung(double angle)
{
  return { 0.5 + 0.5 * std::cos(angle), 0.0, 0.5 * std::sin(angle) };
}
}  // namespace

TEST(Pull, ACornerSwungAboutTheCreaseTurnsItsFaceRigidly)
{
  for (const std::string name : { "newton", "rigid_kinematics" })
  {
    std::vector<int> held;
    Paper paper = creasedInHalf(held);
    const int corner = paper.vertexAt(Vec2(1, 0)), other = paper.vertexAt(Vec2(1, 1));
    std::unique_ptr<ShapeSolver> solver = makeSolver(name);
    const double angle = 2.0;
    // In small steps, as a pin following a frame does.
    for (int k = 1; k <= 20; ++k)
    {
      const auto result = pull(paper, { { corner, swung(angle * k / 20) } }, solver.get(), held);
      ASSERT_TRUE(result) << name << ": " << result.message();
      EXPECT_LE(result->residual, 1e-9) << name;
    }
    EXPECT_LE(edgeStrain(paper).max, 1e-9) << name;
    // Closed form: the far corner turns the same way about the crease.
    EXPECT_LE((paper.vertices[other].folded - (swung(angle) + Vec3(0, 1, 0))).norm(), 1e-8) << name;
    const int crease = paper.findEdge(paper.vertexAt(Vec2(0.5, 0)), paper.vertexAt(Vec2(0.5, 1)));
    EXPECT_NEAR(paper.edges[crease].fold_angle, angle, 1e-8) << name;
    for (int v : held)
      EXPECT_LE((paper.vertices[v].folded -
                 Vec3(paper.vertices[v].crease_pattern.x(), paper.vertices[v].crease_pattern.y(), 0))
                    .norm(),
                1e-12);
  }
}

TEST(Pull, FoldedFlatTheHalvesGetTheLayerOrderTheyCameFrom)
{
  std::vector<int> held;
  Paper paper = creasedInHalf(held);
  const int corner = paper.vertexAt(Vec2(1, 0));
  std::unique_ptr<ShapeSolver> solver = makeSolver("newton");
  for (int k = 1; k <= 30; ++k)
    ASSERT_TRUE(pull(paper, { { corner, swung(M_PI * k / 30) } }, solver.get(), held).ok());
  const int crease = paper.findEdge(paper.vertexAt(Vec2(0.5, 0)), paper.vertexAt(Vec2(0.5, 1)));
  EXPECT_NEAR(paper.edges[crease].fold_angle, M_PI, 1e-9);
  const Edge& hinge = paper.edges[crease];
  const int carried = paper.faceCentroid(hinge.faces[0]).z() == 0.0 ? hinge.faces[1] : hinge.faces[0];
  const int staying = hinge.otherFace(carried);
  ASSERT_EQ(paper.face_orders.size(), 1u);
  EXPECT_EQ(faceOrder(paper, staying, carried), 1) << "the carried half came down onto the front of the other";
}

TEST(Pull, RefusalsLeaveThePaperAsItWas)
{
  std::vector<int> held;
  Paper paper = creasedInHalf(held);
  const Paper before = paper;
  const int corner = paper.vertexAt(Vec2(1, 0));
  std::unique_ptr<ShapeSolver> solver = makeSolver("newton");
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_NE(pull(paper, { { 99, swung(0.1) } }, solver.get(), held).message().find("does not exist"),
            std::string::npos);
  EXPECT_NE(pull(paper, { { corner, Vec3(nan, 0, 0) } }, solver.get(), held).message().find("not a finite"),
            std::string::npos);
  EXPECT_NE(pull(paper, { { corner, swung(0.1) }, { corner, swung(0.2) } }, solver.get(), held).message().find("twice"),
            std::string::npos);
  EXPECT_NE(pull(paper, { { corner, swung(0.1) } }, nullptr, held).message().find("solver"), std::string::npos);
  // Out of reach: the face would have to stretch to 1.5 times its width.
  const auto stretched = pull(paper, { { corner, Vec3(1.5, 0, 0) } }, solver.get(), held);
  EXPECT_FALSE(stretched);
  EXPECT_NE(stretched.message().find("unchanged"), std::string::npos) << stretched.message();
  EXPECT_TRUE(paper == before);
}

TEST(Pull, IsAnOperationTheLogReplaysAndTheJournalKeeps)
{
  std::vector<int> held;
  Session session(creasedInHalf(held));
  session.setSolver(std::shared_ptr<ShapeSolver>(makeSolver("newton")));
  session.setHeldVertices(held);
  const int corner = session.paper().vertexAt(Vec2(1, 0));
  const std::string path =
      (std::filesystem::temp_directory_path() / ("vo_pull_" + std::to_string(::getpid()) + ".jsonl")).string();
  SessionJournal journal;
  ASSERT_TRUE(journal.start(path, session).ok());
  for (int k = 1; k <= 5; ++k)
  {
    ASSERT_TRUE(session.pull({ { corner, swung(0.3 * k) } }).ok());
    ASSERT_TRUE(journal.record(session).ok());
  }
  EXPECT_EQ(session.revision(), 5u);
  ASSERT_EQ(session.log().back().kind, Operation::Kind::Pull);
  EXPECT_STREQ(kindName(Operation::Kind::Pull), "pull");

  const Expected<History> read = readJournal(path);
  std::filesystem::remove(path);
  ASSERT_TRUE(read) << read.message();
  EXPECT_TRUE(read->paper == session.paper());
  ASSERT_EQ(read->log.size(), session.log().size());
  for (size_t i = 0; i < read->log.size(); ++i)
    EXPECT_TRUE(read->log[i].pull == session.log()[i].pull) << i;

  // Re-applying the log to the same start reproduces the state exactly.
  Session again(creasedInHalf(held));
  again.setSolver(std::shared_ptr<ShapeSolver>(makeSolver("newton")));
  again.setHeldVertices(held);
  for (const Operation& op : session.log())
    ASSERT_TRUE(again.apply(op).ok());
  EXPECT_TRUE(again.paper() == session.paper());
  ASSERT_TRUE(again.undo().ok());
  EXPECT_LE((again.paper().vertices[corner].folded - swung(1.2)).norm(), 1e-12);
}

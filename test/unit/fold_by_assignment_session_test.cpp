// Folding by assignment as a session operation: a transaction like every other, previewed
// without history, undone and redone, applied again from the log, journaled.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <limits>

#include "virtual_origami/core/session.h"
#include "virtual_origami/core/session_journal.h"
#include "virtual_origami/core/tessellations.h"
#include "virtual_origami/solvers/crease_driver_factory.h"
#include "virtual_origami/solvers/solver_factory.h"

using namespace virtual_origami::core;

namespace
{
/// A small Miura-ori whose creases carry their flat-folded targets as a file would give them.
Paper miuraWithTargets()
{
  const Expected<Tessellation> miura = miuraTessellation(4, 3);
  EXPECT_TRUE(miura.ok()) << miura.message();
  Paper paper = miura->paper;
  for (size_t e = 0; e < paper.edges.size(); ++e)
    if (paper.edges[e].isCrease())
      paper.edges[e].target_angle = miura->target_fold_angle[e];
  return paper;
}

Session foldingSession(Paper paper)
{
  Session session(std::move(paper));
  session.setSolver(makeSolver("newton"));
  session.setCreaseDrivers(makeCreaseDriver());
  return session;
}

/// Creases with a target, each folded the way its target says and no further than it.
void expectFoldedTowardsTargets(const Paper& paper)
{
  int driven = 0;
  for (const Edge& e : paper.edges)
    if (e.isCrease() && e.target_angle)
    {
      ++driven;
      EXPECT_GT(e.fold_angle * *e.target_angle, 0.0) << "a crease folded against its target";
      EXPECT_LT(std::abs(e.fold_angle), std::abs(*e.target_angle));
    }
  EXPECT_GT(driven, 0);
}

/// A crease driver that drives with the one it wraps, counting the clones made of it and its
/// clones, and recording each call's time budget (a commit's limits have none).
class WatchedDriver : public CreaseDriver
{
public:
  WatchedDriver(std::unique_ptr<CreaseDriver> inner, std::shared_ptr<int> clones)
    : inner_(std::move(inner)), clones_(std::move(clones))
  {
    limits_ = inner_->limits();
    face_stiffness_ = inner_->faceStiffness();
  }
  std::string name() const override { return inner_->name(); }
  SolveReport drive(Paper& paper, const std::vector<double>& target, const std::vector<char>& fixed) override
  {
    budgets.push_back(limits_.max_seconds);
    inner_->setLimits(limits_);
    inner_->setFaceStiffness(face_stiffness_);
    return inner_->drive(paper, target, fixed);
  }
  std::unique_ptr<CreaseDriver> clone() const override
  {
    ++*clones_;
    auto copy = std::make_unique<WatchedDriver>(inner_->clone(), clones_);
    copy->setLimits(limits_);
    copy->setFaceStiffness(face_stiffness_);
    return copy;
  }
  void prepare(const Paper& paper, const std::vector<double>& target, const std::vector<char>& fixed) override
  {
    inner_->prepare(paper, target, fixed);
  }
  void setFramesAside() override { inner_->setFramesAside(); }
  void putFramesBack() override { inner_->putFramesBack(); }

  std::vector<double> budgets;

private:
  std::unique_ptr<CreaseDriver> inner_;
  std::shared_ptr<int> clones_;
};

std::string tempPath(const std::string& name)
{
  return (std::filesystem::temp_directory_path() /
          ("vo_fold_by_assignment_" + std::to_string(::getpid()) + "_" + name))
      .string();
}
}  // namespace

TEST(FoldByAssignmentSession, ARefusedFoldLeavesThePaperAndTheRevision)
{
  Session session = foldingSession(miuraWithTargets());
  const Paper before = session.paper();
  for (double fraction : { std::numeric_limits<double>::quiet_NaN(), -1.01, 1.01,
                           std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity() })
  {
    const auto refused = session.foldByAssignment(fraction);
    ASSERT_FALSE(refused.ok()) << fraction;
    EXPECT_NE(refused.message().find("fraction"), std::string::npos) << refused.message();
    EXPECT_FALSE(session.foldByAssignment(fraction, false).ok()) << "preview at " << fraction;
  }
  EXPECT_TRUE(session.paper() == before);
  EXPECT_EQ(session.revision(), 0u);
  EXPECT_TRUE(session.log().empty());
  EXPECT_FALSE(session.preview().has_value());

  // An unfolded square has no crease for a target to drive.
  Session square = foldingSession(Paper::square(1.0));
  EXPECT_FALSE(square.foldByAssignment(0.5).ok());
  EXPECT_TRUE(square.paper() == Paper::square(1.0));
  EXPECT_EQ(square.revision(), 0u);

  Session without_driver(miuraWithTargets());
  const auto no_driver = without_driver.foldByAssignment(0.5);
  ASSERT_FALSE(no_driver.ok());
  EXPECT_NE(no_driver.message().find("driver"), std::string::npos) << no_driver.message();
  EXPECT_EQ(without_driver.revision(), 0u);
}

TEST(FoldByAssignmentSession, PreviewsStayOutOfHistoryAndTheCommitIsOneEntry)
{
  Session session = foldingSession(miuraWithTargets());
  const Paper flat = session.paper();
  for (double fraction : { 0.1, 0.2, 0.3 })
  {
    ASSERT_TRUE(session.foldByAssignment(fraction, false).ok());
    ASSERT_TRUE(session.preview().has_value());
    EXPECT_FALSE(*session.preview() == flat);
    EXPECT_TRUE(session.paper() == flat);
    EXPECT_EQ(session.revision(), 0u);
  }
  const auto folded = session.foldByAssignment(0.5);
  ASSERT_TRUE(folded.ok()) << folded.message();
  EXPECT_EQ(folded->fraction, 0.5);
  // A Miura-ori is a mechanism: the committed fold closes its faces exactly.
  EXPECT_TRUE(folded->rigid);
  EXPECT_LE(folded->max_strain, 1e-9);
  EXPECT_EQ(session.revision(), 1u);
  EXPECT_FALSE(session.preview().has_value());
  ASSERT_EQ(session.log().size(), 1u);
  EXPECT_EQ(session.log().back().kind, Operation::Kind::AssignmentFold);
  EXPECT_EQ(session.log().back().fraction, 0.5);
  EXPECT_STREQ(kindName(Operation::Kind::AssignmentFold), "fold_by_assignment");
  expectFoldedTowardsTargets(session.paper());
}

TEST(FoldByAssignmentSession, UndoAndRedoGoBackAndForthBitIdentically)
{
  Session session = foldingSession(miuraWithTargets());
  const Paper flat = session.paper();
  ASSERT_TRUE(session.foldByAssignment(0.4).ok());
  const Paper folded = session.paper();
  EXPECT_FALSE(folded == flat);
  ASSERT_TRUE(session.undo().ok());
  EXPECT_TRUE(session.paper() == flat);
  ASSERT_TRUE(session.redo().ok());
  EXPECT_TRUE(session.paper() == folded);
  EXPECT_EQ(session.revision(), 3u);
}

/// The operation as `operations` carries it: with the positions the commit ended at.
Operation recorded(const Session& session)
{
  Operation op = session.log().back();
  for (const Vertex& v : session.paper().vertices)
    op.folded.push_back(v.folded);
  return op;
}

TEST(FoldByAssignmentSession, ApplyingTheRecordedLogAgainReproducesThePaperBitForBit)
{
  Session session = foldingSession(miuraWithTargets());
  // Commits go on from the previews before them (the slide the user saw); the recording
  // carries where each ended, and a replay takes it.
  std::vector<Operation> recording;
  ASSERT_TRUE(session.foldByAssignment(0.7, false).ok());
  ASSERT_TRUE(session.foldByAssignment(0.3).ok());
  recording.push_back(recorded(session));
  ASSERT_TRUE(session.foldByAssignment(0.9, false).ok());
  ASSERT_TRUE(session.foldByAssignment(0.6).ok());
  recording.push_back(recorded(session));

  Session again = foldingSession(miuraWithTargets());
  for (const Operation& op : recording)
  {
    const Status applied = again.apply(op);
    ASSERT_TRUE(applied.ok()) << applied.message();
  }
  EXPECT_TRUE(again.paper() == session.paper());
  EXPECT_EQ(again.revision(), session.revision());
  // The log itself keeps no positions (the states hold them).
  for (const Operation& op : session.log())
    EXPECT_TRUE(op.folded.empty());
}

TEST(FoldByAssignmentSession, AReleaseAfterASlideCommitsFromTheLastPreviewBalancedAndRigid)
{
  Session slid = foldingSession(miuraWithTargets());
  for (int percent = 5; percent <= 60; percent += 5)
    ASSERT_TRUE(slid.foldByAssignment(0.01 * percent, false).ok());
  const Paper last_preview = *slid.preview();
  const auto released = slid.foldByAssignment(0.6);
  ASSERT_TRUE(released.ok()) << released.message();
  EXPECT_TRUE(released->rigid);
  EXPECT_LE(released->max_strain, 1e-9);
  // One branch (a Miura-ori is a mechanism of one degree of freedom): the slide's commit and one
  // call from flat end on the same shape, within the solver's tolerance (placed apart by a rigid
  // motion: no vertex is held, and each path leaves the sheet where its start had it).
  Session direct = foldingSession(miuraWithTargets());
  ASSERT_TRUE(direct.foldByAssignment(0.6).ok());
  double angles_apart = 0.0, from_preview = 0.0;
  for (size_t e = 0; e < slid.paper().edges.size(); ++e)
    angles_apart = std::max(angles_apart, std::abs(slid.paper().edges[e].fold_angle - direct.paper().edges[e].fold_angle));
  for (size_t v = 0; v < slid.paper().vertices.size(); ++v)
    from_preview = std::max(from_preview, (slid.paper().vertices[v].folded - last_preview.vertices[v].folded).norm());
  EXPECT_LE(angles_apart, 1e-6);
  // It went on from the preview: the slide's previews were balanced, the release polished them.
  EXPECT_LE(from_preview, 1e-3 * slid.paper().scale());
}

// The release goes on in the previews' driver (its set-up, made by the slide, serves the commit:
// at 10,000 vertices a fresh clone's was most of the release), under the commit driver's limits,
// cloning neither driver; the previews' own budget is theirs again after it.
TEST(FoldByAssignmentSession, AReleaseGoesOnInThePreviewsDriverUnderTheCommitsLimits)
{
  const auto clones = std::make_shared<int>(0);
  const auto commits = std::make_shared<WatchedDriver>(makeCreaseDriver(), clones);
  const auto previews = std::make_shared<WatchedDriver>(makeCreaseDriver(), clones);
  SolveLimits frame = previews->limits();
  frame.max_seconds = 0.5;
  previews->setLimits(frame);
  ASSERT_EQ(commits->limits().max_seconds, 0.0);
  Session session(miuraWithTargets());
  session.setSolver(makeSolver("newton"));
  session.setCreaseDrivers(commits, previews);
  for (int percent = 5; percent <= 30; percent += 5)
    ASSERT_TRUE(session.foldByAssignment(0.01 * percent, false).ok());
  ASSERT_FALSE(previews->budgets.empty());
  for (double budget : previews->budgets)
    EXPECT_EQ(budget, 0.5);
  const size_t preview_calls = previews->budgets.size();
  const int clones_before = *clones;

  const auto released = session.foldByAssignment(0.3);
  ASSERT_TRUE(released.ok()) << released.message();
  EXPECT_TRUE(released->rigid);
  EXPECT_LE(released->max_strain, 1e-9);
  EXPECT_EQ(*clones, clones_before);
  EXPECT_TRUE(commits->budgets.empty());
  ASSERT_GT(previews->budgets.size(), preview_calls);
  for (size_t k = preview_calls; k < previews->budgets.size(); ++k)
    EXPECT_EQ(previews->budgets[k], 0.0) << "call " << k;
  EXPECT_EQ(previews->limits().max_seconds, 0.5);

  // No preview on show: a commit from the committed paper runs in a fresh clone, as before.
  const auto further = session.foldByAssignment(0.4);
  ASSERT_TRUE(further.ok()) << further.message();
  EXPECT_GT(*clones, clones_before);
}

TEST(FoldByAssignmentSession, ARecordedFoldOfAnotherPaperIsRefusedAndChangesNothing)
{
  Session session = foldingSession(miuraWithTargets());
  ASSERT_TRUE(session.foldByAssignment(0.4).ok());
  Operation op = recorded(session);
  Session other = foldingSession(miuraTessellation(3, 3).value().paper);
  const Paper before = other.paper();
  const Status applied = other.apply(op);
  EXPECT_FALSE(applied.ok());
  EXPECT_NE(applied.message().find("another paper"), std::string::npos) << applied.message();
  EXPECT_TRUE(other.paper() == before);
  EXPECT_EQ(other.revision(), 0u);
  op.folded[3].x() = std::numeric_limits<double>::quiet_NaN();
  Session same = foldingSession(miuraWithTargets());
  const Status nan = same.apply(op);
  EXPECT_FALSE(nan.ok());
  EXPECT_NE(nan.message().find("not a number"), std::string::npos) << nan.message();
  EXPECT_EQ(same.revision(), 0u);
}

TEST(FoldByAssignmentSession, AnOperationRecordedWithoutItsResultIsSolvedAgain)
{
  // Recordings made before commits carried their result: the fold is solved from the paper.
  Session session = foldingSession(miuraWithTargets());
  ASSERT_TRUE(session.foldByAssignment(0.5).ok());
  Session again = foldingSession(miuraWithTargets());
  ASSERT_TRUE(again.apply(session.log().back()).ok());
  EXPECT_TRUE(again.paper() == session.paper());  // no preview on either: the same solve
}

TEST(FoldByAssignmentSession, TargetAnglesAndTheFractionSurviveTheJournal)
{
  Paper paper = miuraWithTargets();
  // Targets a file gave, not the ±π an assignment implies.
  for (Edge& e : paper.edges)
    if (e.target_angle)
      *e.target_angle *= 0.5;
  paper.edges.back().split = true;
  const Expected<Paper> back = parsePaperJson(formatPaperJson(paper));
  ASSERT_TRUE(back.ok()) << back.message();
  EXPECT_TRUE(*back == paper);  // operator== compares target_angle

  const std::string path = tempPath("journal");
  {
    Session session = foldingSession(paper);
    SessionJournal journal;
    ASSERT_TRUE(journal.start(path, session).ok());
    ASSERT_TRUE(session.foldByAssignment(0.25).ok());
    ASSERT_TRUE(journal.record(session).ok());
    const Expected<History> read = readJournal(path);
    ASSERT_TRUE(read.ok()) << read.message();
    EXPECT_TRUE(read->paper == session.paper());
    ASSERT_EQ(read->undo.size(), 1u);
    EXPECT_TRUE(read->undo[0] == paper);
    ASSERT_EQ(read->log.size(), 1u);
    EXPECT_EQ(read->log[0].kind, Operation::Kind::AssignmentFold);
    EXPECT_EQ(read->log[0].fraction, 0.25);
  }
  std::filesystem::remove(path);
}

TEST(FoldByAssignmentSession, PapersJournaledBeforeTargetAnglesStillLoad)
{
  // An edge as journals wrote them before target angles: [v0, v1, assignment, angle(, split)].
  const std::string old = R"({"vertices_crease_pattern": [[0,0],[1,0],[1,1],[0,1]],
      "vertices_folded": [[0,0,0],[1,0,0],[1,1,0],[0,1,0]],
      "edges": [[0,1,"B",0],[1,2,"B",0],[2,3,"B",0],[3,0,"B",0],[0,2,"V",0,false]],
      "faces": [[0,1,2],[0,2,3]], "face_orders": [], "sheet_area": 1})";
  const Expected<Paper> paper = parsePaperJson(old);
  ASSERT_TRUE(paper.ok()) << paper.message();
  ASSERT_EQ(paper->edges.size(), 5u);
  for (const Edge& e : paper->edges)
    EXPECT_FALSE(e.target_angle.has_value());
  EXPECT_TRUE(paper->edges[4].isCrease());
}

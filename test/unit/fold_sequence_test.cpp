#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "crane_reference.h"
#include "test_models.h"
#include "virtual_origami/core/fold_sequence.h"
#include "virtual_origami/core/metrics.h"
#include "virtual_origami/solvers/solver_factory.h"

using namespace virtual_origami::core;

namespace
{
std::string readFile(const std::string& path)
{
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

void expectRefused(const std::string& text, const std::string& words)
{
  const Expected<FoldSequence> s = parseFoldSequence(text);
  EXPECT_FALSE(s.ok());
  EXPECT_NE(s.message().find(words), std::string::npos) << s.message();
}
}  // namespace

TEST(FoldSequence, EveryShippedSequenceFolds)
{
  int files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(std::string(VO_SOURCE_DIR) + "/sequences"))
  {
    if (entry.path().extension() != ".json")
      continue;
    ++files;
    SCOPED_TRACE(entry.path().string());
    const Expected<FoldSequence> sequence = parseFoldSequence(readFile(entry.path().string()));
    ASSERT_TRUE(sequence.ok()) << sequence.message();
    EXPECT_FALSE(sequence->title.empty());
    Session session;
    const Expected<std::vector<Paper>> states = foldSequence(*sequence, session, makeSolver(sequence->solver));
    ASSERT_TRUE(states.ok()) << states.message();
    size_t operations = 0;
    for (const FoldStep& step : sequence->steps)
      operations += static_cast<size_t>(step.repeat);
    EXPECT_EQ(states->size(), operations + 1);
    for (const Paper& state : *states)  // solver-moved states keep faces within its tolerance
    {
      const ValidityReport report = checkValidity(state, { 1e-7, 1e-9, 1e-12 });
      EXPECT_TRUE(report.ok()) << report.summary();
    }
    EXPECT_LT(edgeStrain(states->back()).max, 1e-7);
  }
  EXPECT_GE(files, 2);
}

TEST(FoldSequence, TheTriangleEndsWithItsLastFoldAtNinetyDegrees)
{
  const Expected<FoldSequence> sequence = parseFoldSequence(readFile(std::string(VO_SOURCE_DIR) + "/sequences/triangle.json"));
  ASSERT_TRUE(sequence.ok()) << sequence.message();
  Session session;
  const auto states = foldSequence(*sequence, session, makeSolver(sequence->solver));
  ASSERT_TRUE(states.ok()) << states.message();
  const Paper& paper = states->back();
  EXPECT_EQ(paper.faces.size(), 4u);
  int right_angles = 0, flat = 0;
  for (const Edge& e : paper.edges)
    if (e.isCrease())
    {
      right_angles += std::abs(std::abs(e.fold_angle) - M_PI / 2) < 1e-9 ? 1 : 0;
      flat += std::abs(std::abs(e.fold_angle) - M_PI) < 1e-9 ? 1 : 0;
    }
  EXPECT_EQ(right_angles, 2);  // the fold through both layers, opened
  EXPECT_EQ(flat, 2);          // the diagonal, still folded flat
}

TEST(FoldSequence, RepeatTurnsTheSameFaceAboutTheSameAxis)
{
  const std::string text = R"({"title": "t", "steps": [
    {"crease": {"start": [0.5, -0.1], "end": [0.5, 1.1]}},
    {"rotate": {"click": [0.8, 0.5], "angle_deg": 30, "repeat": 3}}]})";
  const Expected<FoldSequence> sequence = parseFoldSequence(text);
  ASSERT_TRUE(sequence.ok()) << sequence.message();
  Session session;
  const auto states = foldSequence(*sequence, session, makeSolver(sequence->solver));
  ASSERT_TRUE(states.ok()) << states.message();
  ASSERT_EQ(states->size(), 5u);
  const Operation& last = session.log().back();
  EXPECT_NEAR(states->back().edges[last.rotate.axis_edge].fold_angle, M_PI / 2, 1e-12);
}

TEST(FoldSequence, BadFilesAreRefusedWithTheStepAndField)
{
  expectRefused("{", "not valid JSON");
  expectRefused("{}", "steps");
  expectRefused(R"({"steps": [{"fly": {}}]})", "steps[0] names no operation");
  expectRefused(R"({"steps": [{"crease": {"start": [0], "end": [1, 1]}}]})", "steps[0].crease.start");
  expectRefused(R"({"steps": [{"crease": {"start": [0, "a"], "end": [1, 1]}}]})", "steps[0].crease.start[1]");
  expectRefused(R"({"steps": [{"rotate": {"click": [0, 0]}}]})", "angle_deg");
  expectRefused(R"({"size": -1, "steps": []})", "size");
  expectRefused(R"({"steps": [{"rotate": {"click": [0, 0], "angle_deg": 1, "repeat": 0}}]})", "repeat");
}

TEST(FoldSequence, AStepThatFailsIsNamed)
{
  const Expected<FoldSequence> sequence = parseFoldSequence(
      R"({"steps": [{"crease": {"start": [0, 0], "end": [1, 1]}}, {"crease": {"start": [5, 5], "end": [6, 6]}, "note": "off the paper"}]})");
  ASSERT_TRUE(sequence.ok());
  Session session;
  const auto states = foldSequence(*sequence, session, makeSolver(sequence->solver));
  EXPECT_FALSE(states.ok());
  EXPECT_NE(states.message().find("step 2 (off the paper)"), std::string::npos) << states.message();
  EXPECT_NE(states.message().find("misses"), std::string::npos) << states.message();
}

TEST(FoldSequence, AFlatFoldIsCommittedAsTheFlatFoldOperation)
{
  const std::string text = R"({"steps": [{"crease": {"start": [0, 0], "end": [1, 1]}},
      {"flat_fold": {"creases": [{"start": [0, 0], "end": [1, 1], "angle_deg": 180}], "fixed": [0.9, 0.1]}}]})";
  const Expected<FoldSequence> sequence = parseFoldSequence(text);
  ASSERT_TRUE(sequence.ok()) << sequence.message();
  EXPECT_FALSE(sequence->steps[0].flat_fold.has_value());
  ASSERT_TRUE(sequence->steps[1].flat_fold.has_value());
  EXPECT_EQ(sequence->steps[1].flat_fold->fixed_point, Vec2(0.9, 0.1));
  Session session;
  const auto states = foldSequence(*sequence, session, makeSolver(sequence->solver));
  ASSERT_TRUE(states.ok()) << states.message();
  ASSERT_EQ(session.log().size(), 3u);  // reset, crease, the fold
  const Operation& fold = session.log().back();
  EXPECT_EQ(fold.kind, Operation::Kind::FlatFold);
  ASSERT_EQ(fold.flat_fold.creases.size(), 1u);
  EXPECT_EQ(fold.flat_fold.creases[0].start, Vec2(0, 0));
  EXPECT_EQ(fold.flat_fold.creases[0].end, Vec2(1, 1));
  EXPECT_EQ(fold.flat_fold.creases[0].angle, M_PI);
  EXPECT_EQ(fold.flat_fold.fixed_point, Vec2(0.9, 0.1));
  // The corner (0, 1), onto (1, 0).
  EXPECT_LT((session.paper().vertices[session.paper().vertexAt(Vec2(0, 1))].folded - Vec3(1, 0, 0)).norm(), 1e-12);
  EXPECT_NEAR(std::abs(session.paper().edges[4].fold_angle), M_PI, 1e-12);

  // Replaying the log gives the same state.
  Session replayed;
  replayed.setSolver(std::shared_ptr<ShapeSolver>(makeSolver("newton")));
  for (const Operation& op : session.log())
    ASSERT_TRUE(replayed.apply(op).ok());
  EXPECT_TRUE(replayed.paper() == session.paper());

  expectRefused(R"({"steps": [{"flat_fold": {"fixed": [0, 0]}}]})", "flat_fold.creases");
  expectRefused(R"({"steps": [{"flat_fold": {"creases": [{"start": [0, 0], "end": [1, 1]}], "fixed": [0, 0]}}]})",
                "angle_deg");
  expectRefused(R"({"steps": [{"flat_fold": {"creases": [{"start": [0, 0], "end": [1, 1], "angle_deg": 90}]}}]})",
                "flat_fold.fixed");
}

// The crane of the script written before the mouse could fold it (test/data/crane_reference.json:
// one flat fold names whole crease lines) folds to where it folded when a flat fold was committed
// as the pull of every vertex it moved (before the flat_fold operation): the same vertices in the
// same places. sequences/crane.json, the mouse's operations, folds the same crane (rostest
// crane_by_mouse).
TEST(FoldSequence, TheCraneFoldsAsItDidWhenFlatFoldsWerePulls)
{
  const Expected<FoldSequence> sequence = test::craneReference();
  ASSERT_TRUE(sequence.ok()) << sequence.message();
  Session session;
  const auto states = foldSequence(*sequence, session, makeSolver(sequence->solver));
  ASSERT_TRUE(states.ok()) << states.message();

  // The old way, step by step: a flat fold computed on a copy, then pulled to.
  Session old;
  old.setSolver(std::shared_ptr<ShapeSolver>(makeSolver(sequence->solver)));
  ASSERT_TRUE(old.reset(sequence->size).ok());
  int flat_folds = 0;
  size_t state = 0;  // states[state]: the paper before the operation
  for (const FoldStep& step : sequence->steps)
  {
    Operation op = step.operation;
    for (int k = 0; k < step.repeat; ++k)
    {
      ++state;
      if (op.kind == Operation::Kind::FlatFold)
      {
        ++flat_folds;
        // Where the flat fold puts every vertex (a pull knows places, not which side of flat a
        // crease went to, so the fold is computed on the flat-fold path's own state).
        Paper folded = (*states)[state - 1];
        ASSERT_TRUE(flatFold(folded, op.flat_fold).ok()) << step.note;
        std::vector<PullTarget> targets;
        for (size_t v = 0; v < folded.vertices.size(); ++v)
          if ((folded.vertices[v].folded - old.paper().vertices[v].folded).norm() > 1e-12 * folded.scale())
            targets.push_back({ static_cast<int>(v), folded.vertices[v].folded });
        ASSERT_FALSE(targets.empty()) << step.note;
        const Expected<PullResult> pulled = old.pull(targets);
        ASSERT_TRUE(pulled.ok()) << step.note << ": " << pulled.message();
      }
      else
      {
        ASSERT_TRUE(old.apply(op).ok()) << step.note;
        op = old.log().back();
      }
    }
  }
  EXPECT_GE(flat_folds, 8);
  const Paper& now = session.paper();
  const Paper& before = old.paper();
  ASSERT_EQ(now.vertices.size(), before.vertices.size());
  ASSERT_EQ(now.faces.size(), before.faces.size());
  double largest = 0;
  for (size_t v = 0; v < now.vertices.size(); ++v)
    largest = std::max(largest, (now.vertices[v].folded - before.vertices[v].folded).norm());
  EXPECT_LE(largest, 1e-9);
}

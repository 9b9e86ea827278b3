// Regressions of what fuzzing and fault injection found in the core (issue 10; the inputs
// themselves are replayed from test/fuzz/crashes/ by the fuzz_replay tests).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cfloat>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "test_models.h"
#include "virtual_origami/core/fold_io.h"
#include "virtual_origami/core/session.h"
#include "virtual_origami/core/session_journal.h"
#include "virtual_origami/solvers/solver_factory.h"

using namespace virtual_origami::core;
using namespace virtual_origami::core::test;
using ::testing::HasSubstr;

namespace
{
/// The smallest corner angle of any face in the crease pattern.
double sharpestCorner(const Paper& paper)
{
  double sharpest = M_PI;
  for (const Face& f : paper.faces)
    for (size_t i = 0; i < f.vertices.size(); ++i)
    {
      const size_t n = f.vertices.size();
      const Vec2& p = paper.vertices[f.vertices[(i + n - 1) % n]].crease_pattern;
      const Vec2& q = paper.vertices[f.vertices[i]].crease_pattern;
      const Vec2& r = paper.vertices[f.vertices[(i + 1) % n]].crease_pattern;
      const Vec2 a = p - q, b = r - q;
      sharpest = std::min(sharpest, std::atan2(std::abs(a.x() * b.y() - a.y() * b.x()), a.dot(b)));
    }
  return sharpest;
}
}  // namespace

TEST(Reliability, ACreaseAHairOffAnEdgeRunsAlongIt)
{
  Paper paper = Paper::square(1.0);
  creaseLine(paper, p3(0, 0), p3(1, 1));
  const Paper before = paper;
  // From the corner, 1e-7 rad off the diagonal: a sliver of a face, refused as along the edge.
  CreaseRequest request;
  request.start = p3(0, 0);
  request.end = p3(1, 1 - 1e-7);
  const Expected<CreaseResult> result = crease(paper, request);
  ASSERT_FALSE(result.ok());
  EXPECT_THAT(result.message(), HasSubstr("along an existing edge"));
  EXPECT_TRUE(paper == before);
}

TEST(Reliability, ACreaseAHairFromAVertexGoesThroughIt)
{
  Paper paper = Paper::square(1.0);
  // Through (1e-9, 0) and (1, 1): the crossing on the bottom edge is the corner itself, so no
  // edge a nanometre long appears (no solver could measure its strain).
  const CreaseResult result = creaseLine(paper, p3(1e-9, 0), p3(1, 1));
  EXPECT_TRUE(result.new_vertices.empty());
  EXPECT_EQ(paper.vertices.size(), 4u);
  expectValid(paper);
  EXPECT_GT(sharpestCorner(paper), 1e-5);
}

TEST(Reliability, ACreaseNearACornerLeavesNoCrumb)
{
  Paper paper = Paper::square(1.0);
  const Paper before = paper;
  // Cutting off a corner triangle with legs of 1e-7: a face with (almost) no area.
  CreaseRequest request;
  request.start = p3(-0.05, 1e-7 + 0.05);
  request.end = p3(1e-7 + 0.05, -0.05);
  const Expected<CreaseResult> result = crease(paper, request);
  EXPECT_FALSE(result.ok());
  EXPECT_TRUE(paper == before);
}

TEST(Reliability, SheetSizesStayFarFromOverflow)
{
  Session session;
  for (double size : { DBL_MAX, 1e300, 1e-300, 0.0, -1.0, double(NAN), double(INFINITY) })
  {
    const Status status = session.reset(size);
    EXPECT_FALSE(status.ok()) << size;
    EXPECT_FALSE(status.message().empty());
  }
  EXPECT_EQ(session.revision(), 0u);
  EXPECT_TRUE(session.reset(1e-6).ok());
  EXPECT_TRUE(session.reset(1e6).ok());
  // A model whose area underflows is no sheet either.
  Paper crumb = Paper::square(1.0);
  for (Vertex& v : crumb.vertices)
  {
    v.crease_pattern *= 1e-200;
    v.folded *= 1e-200;
  }
  crumb.sheet_area = 0.0;
  EXPECT_FALSE(session.load(crumb, "crumb.fold").ok());
}

TEST(Reliability, ATurnOfMoreThanAWholeTurnIsRefusedNotFollowedWithoutEnd)
{
  // A finite angle of 1e300 rad once sent the staged solve of a turn the solver must follow
  // into ~1e300 stages (session_ops/rotate-angle-1e300-stages-without-end).
  Session session(creasedSquare());
  session.setSolver(makeSolver("shape_matching"));
  RotateRequest request;
  request.click = p3(0.9, 0.6);
  const uint64_t revision = session.revision();
  for (double angle : { 1e300, -1e300, 7.0, -2 * M_PI - 1e-6 })
  {
    request.angle = angle;
    const auto result = session.rotate(request, true);
    ASSERT_FALSE(result.ok()) << angle;
    EXPECT_NE(result.message().find("more than a whole turn"), std::string::npos) << result.message();
  }
  EXPECT_EQ(session.revision(), revision);
}

TEST(Reliability, LoadingADeviceOrADirectoryIsRefusedUnread)
{
  for (const std::string path : { "/dev/zero", "/dev/null", "/tmp" })
  {
    const Expected<Paper> paper = loadPaper(path);
    ASSERT_FALSE(paper.ok()) << path;
    EXPECT_THAT(paper.message(), HasSubstr("not a regular file")) << path;
  }
}

TEST(Reliability, RestartingAJournalNeverLeavesItTruncated)
{
  const std::string path = std::filesystem::temp_directory_path() / ("vo_reliability_journal_" +
                                                                     std::to_string(::getpid()) + ".jsonl");
  Session session;
  ASSERT_TRUE(session.crease({ p3(0.5, -0.1), p3(0.5, 1.1), std::nullopt, false }).ok());
  SessionJournal journal;
  ASSERT_TRUE(journal.start(path, session).ok());
  ASSERT_TRUE(session.crease({ p3(-0.1, 0.5), p3(1.1, 0.5), std::nullopt, false }).ok());
  ASSERT_TRUE(journal.record(session).ok());
  // A restart writes the new journal beside the old one and renames it over: no moment where
  // the file on disk holds less than a whole session, and nothing left beside it.
  SessionJournal again;
  ASSERT_TRUE(again.start(path, session).ok());
  EXPECT_FALSE(std::filesystem::exists(path + ".tmp"));
  ASSERT_TRUE(session.undo().ok());
  ASSERT_TRUE(again.record(session).ok());
  const Expected<History> history = readJournal(path);
  ASSERT_TRUE(history.ok()) << history.message();
  EXPECT_EQ(history->revision, session.revision());
  EXPECT_TRUE(history->paper == session.paper());
  EXPECT_EQ(history->log.size(), 3u);
  std::remove(path.c_str());
}

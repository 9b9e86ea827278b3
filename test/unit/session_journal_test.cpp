#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <random>

#include "test_models.h"
#include "virtual_origami/core/session_journal.h"

using namespace virtual_origami::core;
using namespace virtual_origami::core::test;

namespace
{
std::string tempPath(const std::string& name)
{
  return (std::filesystem::temp_directory_path() / ("vo_journal_" + std::to_string(::getpid()) + "_" + name)).string();
}

void expectSameHistory(const History& a, const History& b)
{
  EXPECT_TRUE(a.paper == b.paper);
  EXPECT_EQ(a.revision, b.revision);
  ASSERT_EQ(a.undo.size(), b.undo.size());
  ASSERT_EQ(a.redo.size(), b.redo.size());
  for (size_t i = 0; i < a.undo.size(); ++i)
    EXPECT_TRUE(a.undo[i] == b.undo[i]) << "undo " << i;
  for (size_t i = 0; i < a.redo.size(); ++i)
    EXPECT_TRUE(a.redo[i] == b.redo[i]) << "redo " << i;
  ASSERT_EQ(a.log.size(), b.log.size());
  for (size_t i = 0; i < a.log.size(); ++i)
  {
    EXPECT_EQ(a.log[i].kind, b.log[i].kind);
    EXPECT_EQ(a.log[i].revision, b.log[i].revision);
  }
}

std::vector<std::string> readLines(const std::string& path)
{
  std::ifstream in(path);
  std::vector<std::string> lines;
  for (std::string l; std::getline(in, l);)
    lines.push_back(l);
  return lines;
}

/// A short fold with undo and redo in it, recorded as it goes.
Session foldRecorded(SessionJournal& journal, const std::string& path)
{
  Session session;
  EXPECT_TRUE(journal.start(path, session).ok());
  const auto record = [&] { EXPECT_TRUE(journal.record(session).ok()); };
  CreaseRequest line;
  line.start = p3(0.5, -0.1);
  line.end = p3(0.5, 1.1);
  EXPECT_TRUE(session.crease(line).ok());
  record();
  RotateRequest turn;
  turn.click = p3(0.8, 0.5);
  turn.angle = 2.0;
  EXPECT_TRUE(session.rotate(turn).ok());
  record();
  EXPECT_TRUE(session.undo().ok());
  record();
  EXPECT_TRUE(session.redo().ok());
  record();
  EXPECT_TRUE(session.squash().ok());
  record();
  EXPECT_TRUE(session.undo().ok());
  record();
  return session;
}
}  // namespace

TEST(SessionJournal, ReadsBackTheWholeHistory)
{
  const std::string path = tempPath("whole");
  SessionJournal journal;
  const Session session = foldRecorded(journal, path);
  const Expected<History> read = readJournal(path);
  ASSERT_TRUE(read.ok()) << read.message();
  expectSameHistory(read.value(), session.history());
  // The restored session goes on where the first stopped: redo brings the squash back.
  Session restored(read.value());
  ASSERT_TRUE(restored.redo().ok());
  for (const Vertex& v : restored.paper().vertices)
    EXPECT_NEAR(v.folded.z(), 0.0, 1e-15);
  std::filesystem::remove(path);
}

TEST(SessionJournal, StartingOnAnOngoingSessionKeepsItsPast)
{
  const std::string first = tempPath("first"), second = tempPath("second");
  SessionJournal journal;
  Session session = foldRecorded(journal, first);
  SessionJournal fresh;
  ASSERT_TRUE(fresh.start(second, session).ok());
  ASSERT_TRUE(session.reset(2.0).ok());
  ASSERT_TRUE(fresh.record(session).ok());
  const Expected<History> read = readJournal(second);
  ASSERT_TRUE(read.ok()) << read.message();
  expectSameHistory(read.value(), session.history());
  std::filesystem::remove(first);
  std::filesystem::remove(second);
}

TEST(SessionJournal, ATornLastLineLosesOnlyThatEvent)
{
  const std::string path = tempPath("torn");
  SessionJournal journal;
  foldRecorded(journal, path);
  const std::vector<std::string> lines = readLines(path);
  {
    std::ofstream out(path, std::ios::trunc);
    for (size_t i = 0; i + 1 < lines.size(); ++i)
      out << lines[i] << '\n';
    out << lines.back().substr(0, lines.back().size() / 2);  // the crash cut the last write
  }
  const Expected<History> read = readJournal(path);
  ASSERT_TRUE(read.ok()) << read.message();
  EXPECT_EQ(read->log.size(), lines.size() - 2);  // header and the torn line
  std::filesystem::remove(path);
}

TEST(SessionJournal, DamageIsReportedWithItsLine)
{
  const std::string path = tempPath("damaged");
  SessionJournal journal;
  foldRecorded(journal, path);
  const std::vector<std::string> lines = readLines(path);
  {
    std::ofstream out(path, std::ios::trunc);
    for (size_t i = 0; i < lines.size(); ++i)
      out << (i == 2 ? "{\"operation\": {\"kind\": \"fly\", \"revision\": 2}}" : lines[i]) << '\n';
  }
  const Expected<History> read = readJournal(path);
  EXPECT_FALSE(read.ok());
  EXPECT_NE(read.message().find("line 3"), std::string::npos) << read.message();
  EXPECT_NE(read.message().find("fly"), std::string::npos) << read.message();
  EXPECT_FALSE(readJournal(tempPath("missing")).ok());
  std::filesystem::remove(path);
}

TEST(SessionJournal, PaperJsonIsBitExact)
{
  Paper paper = stackOfLayers(2);
  paper.face_orders.push_back({ 0, 1, -1 });
  const Expected<Paper> back = parsePaperJson(formatPaperJson(paper));
  ASSERT_TRUE(back.ok()) << back.message();
  EXPECT_TRUE(back.value() == paper);
  EXPECT_FALSE(parsePaperJson("{").ok());
  EXPECT_FALSE(parsePaperJson("{\"vertices_crease_pattern\": []}").ok());
}

// The journal writes what an operation changed (paper deltas) with snapshots every so often:
// restoring one gives the same session as a journal of whole states, bit for bit, journals
// written before deltas still restore, and a crash in the middle of a snapshot loses nothing.
#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <csignal>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>

#include <nlohmann/json.hpp>

#include "test_models.h"
#include "virtual_origami/core/paper_delta.h"
#include "virtual_origami/core/reference_patterns.h"
#include "virtual_origami/core/session_journal.h"
#include "virtual_origami/core/tessellations.h"
#include "virtual_origami/solvers/crease_driver_factory.h"
#include "virtual_origami/solvers/solver_factory.h"

using namespace virtual_origami::core;
using namespace virtual_origami::core::test;
using nlohmann::json;

namespace
{
std::string tempPath(const std::string& name)
{
  return (std::filesystem::temp_directory_path() / ("vo_delta_" + std::to_string(::getpid()) + "_" + name)).string();
}

std::vector<std::string> readLines(const std::string& path)
{
  std::ifstream in(path);
  std::vector<std::string> lines;
  for (std::string l; std::getline(in, l);)
    lines.push_back(l);
  return lines;
}

void writeLines(const std::string& path, const std::vector<std::string>& lines)
{
  std::ofstream out(path, std::ios::trunc | std::ios::binary);
  for (const std::string& line : lines)
    out << line << '\n';
}

/// Bit for bit: operator== compares doubles by value (0.0 == -0.0); the round-trip JSON of
/// every double tells the sign of a zero too.
void expectBitForBit(const Paper& a, const Paper& b, const std::string& what)
{
  EXPECT_TRUE(a == b) << what;
  EXPECT_EQ(formatPaperJson(a), formatPaperJson(b)) << what;
  EXPECT_EQ(paperFingerprint(a), paperFingerprint(b)) << what;
}

void expectSameHistory(const History& a, const History& b)
{
  expectBitForBit(a.paper, b.paper, "paper");
  EXPECT_EQ(a.revision, b.revision);
  ASSERT_EQ(a.undo.size(), b.undo.size());
  ASSERT_EQ(a.redo.size(), b.redo.size());
  for (size_t i = 0; i < a.undo.size(); ++i)
    expectBitForBit(a.undo[i], b.undo[i], "undo " + std::to_string(i));
  for (size_t i = 0; i < a.redo.size(); ++i)
    expectBitForBit(a.redo[i], b.redo[i], "redo " + std::to_string(i));
  ASSERT_EQ(a.log.size(), b.log.size());
  for (size_t i = 0; i < a.log.size(); ++i)
  {
    EXPECT_EQ(a.log[i].kind, b.log[i].kind) << "operation " << i;
    EXPECT_EQ(a.log[i].revision, b.log[i].revision) << "operation " << i;
  }
}

History recovered(const std::string& path)
{
  const Expected<JournalRecovery> read = recoverJournal(path);
  EXPECT_TRUE(read.ok()) << read.message();
  if (!read)
    return {};
  EXPECT_TRUE(read->dropped.empty()) << read->dropped.front();
  return read->history;
}

/// A small Miura-ori whose creases carry their flat-folded targets, to fold by assignment.
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

bool creaseDown(Session& s)
{
  return s.crease({ p3(0.5, -0.1), p3(0.5, 1.1), std::nullopt, false }).ok();
}
bool creaseAcross(Session& s)
{
  return s.crease({ p3(-0.1, 0.3), p3(1.1, 0.3), std::nullopt, false }).ok();
}
bool turnRight(Session& s)
{
  RotateRequest turn;
  turn.click = p3(0.8, 0.5);
  turn.angle = 2.0;
  return s.rotate(turn).ok();
}
bool undo(Session& s)
{
  return s.undo().ok();
}
bool redo(Session& s)
{
  return s.redo().ok();
}
bool loadMiura(Session& s)
{
  return s.load(miuraWithTargets(), "miura.fold").ok();
}
bool foldThird(Session& s)
{
  return s.foldByAssignment(0.3).ok();
}
bool foldTwoThirds(Session& s)
{
  return s.foldByAssignment(0.6).ok();
}
bool pressFlat(Session& s)
{
  return s.squash().ok();
}

/// The four ways an operation reaches a journal: as paper_model does (the event made outside
/// the lock, its delta written at the append), the delta made ahead from the state before,
/// the delta made at the append, and the whole state (every commit before deltas).
enum class Way
{
  EventAhead,
  DeltaAhead,
  DeltaAtAppend,
  Whole
};

Status journalWay(SessionJournal& journal, Way way, const Session& before, const Operation& op, const Paper* next)
{
  switch (way)
  {
    case Way::EventAhead:
      return journal.append(before, journalEvent(op, next));
    case Way::DeltaAhead:
      return journal.append(before, journalEvent(op, next, next ? &before.paper() : nullptr));
    case Way::DeltaAtAppend:
      return journal.append(before, op, next);
    case Way::Whole:
      return journal.append(op, next);
  }
  return failure("no such way");
}

/// Runs `changes` on a session, journaling each (before it is committed, as paper_model does)
/// the four ways, each in a journal of its own at `paths[way]`.
Session journalEveryWay(const std::vector<std::function<bool(Session&)>>& changes,
                        const std::vector<std::string>& paths, std::vector<SessionJournal>* kept = nullptr)
{
  Session session;
  session.setSolver(makeSolver("newton"));
  session.setCreaseDrivers(makeCreaseDriver());
  std::vector<SessionJournal> journals(4);
  for (size_t w = 0; w < 4; ++w)
    EXPECT_TRUE(journals[w].start(paths[w], session).ok());
  for (size_t i = 0; i < changes.size(); ++i)
  {
    Session next = session;
    EXPECT_TRUE(changes[i](next)) << "change " << i;
    const Operation& op = next.log().back();
    const bool step = op.kind == Operation::Kind::Undo || op.kind == Operation::Kind::Redo;
    for (size_t w = 0; w < 4; ++w)
    {
      const Status appended = journalWay(journals[w], Way(w), session, op, step ? nullptr : &next.paper());
      EXPECT_TRUE(appended.ok()) << "change " << i << " way " << w << ": " << appended.message();
    }
    session = std::move(next);
  }
  if (kept)
    *kept = std::move(journals);
  return session;
}

const std::vector<std::function<bool(Session&)>> kMixed{ creaseDown, turnRight, undo,      redo,      creaseAcross,
                                                         pressFlat,  undo,      loadMiura, foldThird, foldTwoThirds,
                                                         undo,       redo,      undo,      undo,      redo };

std::vector<std::string> wayPaths(const std::string& name)
{
  return { tempPath(name + "_event"), tempPath(name + "_ahead"), tempPath(name + "_append"),
           tempPath(name + "_whole") };
}

void removeAll(const std::vector<std::string>& paths)
{
  for (const std::string& p : paths)
    std::filesystem::remove(p);
}
}  // namespace

TEST(JournalDelta, DeltasRestoreTheSameStateAsWholeStatesBitForBit)
{
  const std::vector<std::string> paths = wayPaths("mixed");
  const Session session = journalEveryWay(kMixed, paths);
  ASSERT_EQ(session.revision(), kMixed.size());
  // The last undo made a redo state and kept undo states: both stacks are read back.
  ASSERT_FALSE(session.history().undo.empty());
  ASSERT_FALSE(session.history().redo.empty());
  for (const std::string& path : paths)
  {
    SCOPED_TRACE(path);
    expectSameHistory(recovered(path), session.history());
  }
  // The delta journals write what changed; the whole one the state. A load writes its paper
  // whole either way (it shares nothing with the paper before it).
  std::vector<uintmax_t> event_bytes;
  for (size_t w = 0; w < paths.size(); ++w)
  {
    const std::vector<std::string> lines = readLines(paths[w]);
    ASSERT_EQ(lines.size(), kMixed.size() + 1);
    uintmax_t bytes = 0;
    for (size_t i = 1; i < lines.size(); ++i)
    {
      const json event = json::parse(lines[i]);
      const Operation::Kind kind = session.log()[i - 1].kind;
      const bool step = kind == Operation::Kind::Undo || kind == Operation::Kind::Redo;
      const bool whole = w == size_t(Way::Whole) || kind == Operation::Kind::Load;
      EXPECT_EQ(event.contains("paper"), !step && whole) << "way " << w << " line " << i + 1;
      EXPECT_EQ(event.contains("delta"), !step && !whole) << "way " << w << " line " << i + 1;
      bytes += lines[i].size();
    }
    event_bytes.push_back(bytes);
  }
  for (size_t w = 0; w < size_t(Way::Whole); ++w)
  {
    EXPECT_EQ(event_bytes[w], event_bytes[0]) << "the same deltas whichever way they were made";
    EXPECT_LT(event_bytes[w], event_bytes[size_t(Way::Whole)]);
  }
  removeAll(paths);
}

TEST(JournalDelta, UndoAndRedoGoOnAcrossARestartAndASnapshot)
{
  const std::vector<std::string> paths = wayPaths("restart");
  Session session = journalEveryWay(kMixed, paths);
  // The restart: a session from the journal, whose own journal starts with a snapshot of it
  // (the undo and redo states as delta chains) and goes on with deltas.
  Session restored(recovered(paths[0]));
  restored.setSolver(makeSolver("newton"));
  restored.setCreaseDrivers(makeCreaseDriver());
  const std::string resumed = tempPath("resumed");
  SessionJournal journal;
  ASSERT_TRUE(journal.start(resumed, restored).ok());
  expectSameHistory(recovered(resumed), session.history());
  const std::vector<std::function<bool(Session&)>> after{ undo, undo, redo, redo, redo, undo, foldTwoThirds, undo };
  for (size_t i = 0; i < after.size(); ++i)
  {
    ASSERT_TRUE(after[i](session)) << "original, step " << i;
    Session next = restored;
    ASSERT_TRUE(after[i](next)) << "restored, step " << i;
    const Operation& op = next.log().back();
    const bool step = op.kind == Operation::Kind::Undo || op.kind == Operation::Kind::Redo;
    ASSERT_TRUE(journal.append(restored, journalEvent(op, step ? nullptr : &next.paper())).ok());
    restored = std::move(next);
    SCOPED_TRACE("step " + std::to_string(i));
    expectBitForBit(restored.paper(), session.paper(), "the paper after the restart");
    expectSameHistory(recovered(resumed), session.history());
    if (i == 3)
    {
      // A snapshot in between: what follows is read on top of it.
      ASSERT_TRUE(journal.snapshot(restored).ok());
      EXPECT_EQ(readLines(resumed).size(), 1u);
      expectSameHistory(recovered(resumed), session.history());
    }
  }
  removeAll(paths);
  std::filesystem::remove(resumed);
}

TEST(JournalDelta, ASnapshotHoldsTheUndoStatesAsDeltasAndIsSmallerThanThemWhole)
{
  const std::vector<std::string> paths = wayPaths("chain");
  const Session session = journalEveryWay(kMixed, paths);
  const std::string path = tempPath("chain_snapshot");
  SessionJournal journal;
  ASSERT_TRUE(journal.start(path, session).ok());
  const json header = json::parse(readLines(path).at(0));
  EXPECT_EQ(header.at("version"), 2);
  const History& h = session.history();
  ASSERT_EQ(header.at("undo").size(), h.undo.size());
  ASSERT_EQ(header.at("redo").size(), h.redo.size());
  size_t whole = 0, chained = 0;
  for (size_t k = 0; k < h.undo.size(); ++k)
  {
    EXPECT_TRUE(header["undo"][k].contains("fingerprint"));
    whole += formatPaperJson(h.undo[k]).size();
    chained += header["undo"][k].dump().size();
  }
  EXPECT_LT(chained, whole);
  expectSameHistory(recovered(path), h);
  removeAll(paths);
  std::filesystem::remove(path);
}

TEST(JournalDelta, AJournalWrittenBeforeDeltasStillRestores)
{
  // test/data/journal_v1.jsonl was written by the journal before deltas (version 1): a header
  // holding the paper, two undo and one redo state whole after crease, turn, crease, undo; then
  // redo, squash, crease, undo, undo, redo, each commit with its state whole.
  const std::vector<std::string> lines = readLines(std::string(VO_SOURCE_DIR) + "/test/data/journal_v1.jsonl");
  ASSERT_EQ(lines.size(), 7u);
  const json header = json::parse(lines[0]);
  ASSERT_EQ(header.at("version"), 1);
  const auto paperOf = [](const json& j) {
    const Expected<Paper> paper = parsePaperJson(j.dump());
    EXPECT_TRUE(paper.ok()) << paper.message();
    return paper ? *paper : Paper();
  };
  const Paper p0 = paperOf(header["undo"][0]), p1 = paperOf(header["undo"][1]), p2 = paperOf(header["paper"]),
              p3_ = paperOf(header["redo"][0]);
  const Paper squashed = paperOf(json::parse(lines[2])["paper"]), creased = paperOf(json::parse(lines[3])["paper"]);
  // A whole paper is still written as that version wrote it, to the byte.
  EXPECT_EQ(formatPaperJson(squashed), json::parse(lines[2])["paper"].dump());
  EXPECT_EQ(formatPaperJson(p2), header["paper"].dump());

  const std::string path = tempPath("v1");
  std::filesystem::copy_file(std::string(VO_SOURCE_DIR) + "/test/data/journal_v1.jsonl", path);
  const Expected<JournalRecovery> read = recoverJournal(path);
  ASSERT_TRUE(read.ok()) << read.message();
  EXPECT_TRUE(read->dropped.empty());
  EXPECT_EQ(read->run_id, "fixture-run");
  const History& h = read->history;
  EXPECT_EQ(h.revision, 10u);
  EXPECT_EQ(h.log.size(), 10u);
  expectBitForBit(h.paper, squashed, "paper: the squash, redone");
  ASSERT_EQ(h.undo.size(), 4u);
  expectBitForBit(h.undo[0], p0, "undo 0");
  expectBitForBit(h.undo[1], p1, "undo 1");
  expectBitForBit(h.undo[2], p2, "undo 2");
  expectBitForBit(h.undo[3], p3_, "undo 3");
  ASSERT_EQ(h.redo.size(), 1u);
  expectBitForBit(h.redo[0], creased, "redo 0");

  // It goes on in the new format: a snapshot of it, deltas after, all read back.
  Session session(h);
  SessionJournal journal;
  ASSERT_TRUE(journal.start(path, session, read->run_id).ok());
  for (const auto& change : { undo, redo, redo, undo })
  {
    Session next = session;
    ASSERT_TRUE(change(next));
    ASSERT_TRUE(journal.append(session, next.log().back(), nullptr).ok());
    session = std::move(next);
  }
  Session next = session;
  ASSERT_TRUE(next.crease({ p3(0.25, -0.1), p3(0.25, 1.1), std::nullopt, false }).ok());
  ASSERT_TRUE(journal.append(session, journalEvent(next.log().back(), &next.paper())).ok());
  session = std::move(next);
  EXPECT_EQ(json::parse(readLines(path)[0]).at("version"), 2);
  expectSameHistory(recovered(path), session.history());
  std::filesystem::remove(path);
}

TEST(JournalDelta, AJournalNewerThanThisVersionIsRefusedSayingSo)
{
  const std::string path = tempPath("v3");
  SessionJournal journal;
  ASSERT_TRUE(journal.start(path, Session()).ok());
  std::vector<std::string> lines = readLines(path);
  json header = json::parse(lines[0]);
  header["version"] = 3;
  lines[0] = header.dump();
  writeLines(path, lines);
  const Expected<JournalRecovery> read = recoverJournal(path);
  ASSERT_FALSE(read.ok());
  EXPECT_NE(read.message().find("journal version 3, which this version of virtual_origami does not read (it reads "
                                "versions 1 to 2)"),
            std::string::npos)
      << read.message();
  std::filesystem::remove(path);
}

TEST(JournalDelta, ADeltaThatDoesNotGiveItsStateIsDropped)
{
  const std::vector<std::string> paths = wayPaths("tampered");
  const Session session = journalEveryWay({ creaseDown, turnRight, pressFlat }, paths);
  std::vector<std::string> lines = readLines(paths[0]);
  ASSERT_EQ(lines.size(), 4u);
  // The turn's line: one moved coordinate off by its last bit.
  json event = json::parse(lines[2]);
  json& folded = event.at("delta").at("folded");
  ASSERT_GE(folded.size(), 4u);
  folded[1] = std::nextafter(folded[1].get<double>(), 10.0);
  lines[2] = event.dump();
  writeLines(paths[0], lines);
  const Expected<JournalRecovery> read = recoverJournal(paths[0]);
  ASSERT_TRUE(read.ok()) << read.message();
  ASSERT_EQ(read->dropped.size(), 1u);
  EXPECT_EQ(read->dropped[0], "line 3: a paper delta that does not give the state it was made for; dropped lines "
                              "3\u20134 (2 lines)");
  EXPECT_EQ(read->history.revision, 1u);
  expectBitForBit(read->history.paper, session.history().undo[1], "the crease before the damaged turn");
  removeAll(paths);
}

TEST(JournalDelta, ADeltaMadeFromAnotherStateIsRefusedAndChangesNothing)
{
  const std::string path = tempPath("other_base");
  Session session;
  ASSERT_TRUE(creaseDown(session));
  SessionJournal journal;
  ASSERT_TRUE(journal.start(path, session).ok());
  const std::vector<std::string> before = readLines(path);
  Session next = session;
  ASSERT_TRUE(turnRight(next));
  const Paper other = Paper::square(1.0);  // not the state the journal is at
  const Status refused = journal.append(journalEvent(next.log().back(), &next.paper(), &other));
  ASSERT_FALSE(refused.ok());
  EXPECT_NE(refused.message().find("computed from another state than the one the journal is at"), std::string::npos)
      << refused.message();
  EXPECT_EQ(readLines(path), before);
  EXPECT_TRUE(journal.healthy());
  // From the right state it is taken.
  ASSERT_TRUE(journal.append(journalEvent(next.log().back(), &next.paper(), &session.paper())).ok());
  expectSameHistory(recovered(path), next.history());
  std::filesystem::remove(path);
}

TEST(JournalDelta, APaperDeltaCarriesOnlyWhatChangedWithItsExactDoubles)
{
  Paper before = Paper::square(1.0);
  Paper after = before;
  after.vertices[2].folded.z() = 0.1 + 0.2;  // not 0.3: the last bit must survive
  after.vertices[1].folded.x() = -0.0;
  const json delta = json::parse(formatPaperDelta(before, after));
  EXPECT_FALSE(delta.contains("crease_pattern"));
  EXPECT_FALSE(delta.contains("edge_changes"));
  EXPECT_FALSE(delta.contains("face_changes"));
  ASSERT_TRUE(delta.contains("folded"));
  // Two vertices moved: [index, x, y, z] each.
  EXPECT_EQ(delta["folded"].size(), 8u);
  const Expected<Paper> back = applyPaperDelta(before, json::parse(delta.dump()));
  ASSERT_TRUE(back.ok()) << back.message();
  expectBitForBit(*back, after, "applied");
  EXPECT_TRUE(std::signbit(back->vertices[1].folded.x()));
  // A zero turned negative is a change too.
  Paper signed_zero = before;
  signed_zero.vertices[0].folded.z() = -0.0;
  const json sign = json::parse(formatPaperDelta(before, signed_zero));
  ASSERT_TRUE(sign.contains("folded"));
  const Expected<Paper> sign_back = applyPaperDelta(before, json::parse(sign.dump()));
  ASSERT_TRUE(sign_back.ok()) << sign_back.message();
  EXPECT_TRUE(std::signbit(sign_back->vertices[0].folded.z()));
  // Applied to another state it is refused.
  EXPECT_FALSE(applyPaperDelta(Paper::square(2.0), delta).ok());
  // Malformed ones are refused with why, never thrown.
  for (const char* bad : { R"({})", R"([])", R"({"vertices": 4, "edges": 4, "faces": 1, "face_orders": 0,
                           "folded": [9, 0.0, 0.0, 0.0], "fingerprint": 1})",
                           R"({"vertices": -1, "edges": 4, "faces": 1, "face_orders": 0, "fingerprint": 1})",
                           R"({"vertices": 4, "edges": 4, "faces": 1, "face_orders": 0, "folded": [0, 1.0],
                           "fingerprint": 1})",
                           R"({"vertices": 4, "edges": 4, "faces": 1, "face_orders": 0, "fingerprint": "x"})" })
  {
    const Expected<Paper> refused = applyPaperDelta(before, json::parse(bad));
    EXPECT_FALSE(refused.ok()) << bad;
    EXPECT_FALSE(refused.message().empty()) << bad;
  }
}

// A snapshot rewrites the journal whole: a failing disk or a kill in the middle of it must
// leave the journal as it was, every acknowledged operation in it.
TEST(JournalDelta, ASnapshotThatFailsHalfWayLeavesTheJournalAsItWas)
{
  const std::vector<std::string> paths = wayPaths("failing");
  Session session = journalEveryWay(kMixed, paths);
  const std::string path = tempPath("failing_snapshot");
  SessionJournal journal;
  ASSERT_TRUE(journal.start(path, Session()).ok());
  ASSERT_TRUE(journal.record(session).ok());  // started again: the session as its header
  ASSERT_TRUE(foldTwoThirds(session));
  ASSERT_TRUE(journal.record(session).ok());
  const std::vector<std::string> before = readLines(path);
  ASSERT_EQ(before.size(), 2u);
  uint64_t cut_at = 0, total = 0;
  journal.setHeaderWriteObserver(
      [&](uint64_t written, uint64_t size) {
        total = size;
        cut_at = written;
        return false;  // the disk is full after the first chunk
      },
      256);
  const Status snapped = journal.snapshot(session);
  ASSERT_FALSE(snapped.ok());
  EXPECT_NE(snapped.message().find(std::strerror(ENOSPC)), std::string::npos) << snapped.message();
  EXPECT_EQ(cut_at, 256u);
  EXPECT_GT(total, 256u);
  EXPECT_EQ(readLines(path), before);
  expectSameHistory(recovered(path), session.history());
  // Nothing left beside it, and the next operation starts the journal again.
  for (const auto& entry : std::filesystem::directory_iterator(std::filesystem::path(path).parent_path()))
    EXPECT_NE(entry.path().filename().string().rfind(std::filesystem::path(path).filename().string() + ".tmp.", 0), 0u)
        << entry.path();
  journal.setHeaderWriteObserver(nullptr, 1);
  Session next = session;
  ASSERT_TRUE(undo(next));
  ASSERT_TRUE(journal.append(session, next.log().back(), nullptr).ok());
  session = std::move(next);
  expectSameHistory(recovered(path), session.history());
  removeAll(paths);
  std::filesystem::remove(path);
}

TEST(JournalDelta, AKillInTheMiddleOfASnapshotRestoresTheLastCompleteState)
{
  const std::vector<std::string> paths = wayPaths("killed");
  std::vector<SessionJournal> journals;
  Session session = journalEveryWay(kMixed, paths, &journals);
  const std::string path = paths[0];  // a header and fifteen events, deltas
  SessionJournal& journal = journals[0];
  const std::vector<std::string> before = readLines(path);
  Session snapshotted = session;
  ASSERT_TRUE(redo(snapshotted));

  const pid_t child = ::fork();
  ASSERT_GE(child, 0) << std::strerror(errno);
  if (child == 0)
  {
    // The child, with the journal as it stands, journals one more operation (the redo) and is
    // killed -9 half-way through the snapshot that follows it.
    if (!journal.append(session, snapshotted.log().back(), nullptr).ok())
      ::_exit(3);
    journal.setHeaderWriteObserver(
        [](uint64_t written, uint64_t size) {
          if (written * 2 >= size)
            ::raise(SIGKILL);
          return true;
        },
        512);
    journal.snapshot(snapshotted);
    ::_exit(4);  // never reached: the kill came first
  }
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFSIGNALED(status)) << "the child exited with " << WEXITSTATUS(status);
  EXPECT_EQ(WTERMSIG(status), SIGKILL);

  // The half-written header is beside the journal, which holds the last complete state.
  const std::string temporary = path + ".tmp." + std::to_string(child) + ".0";
  ASSERT_TRUE(std::filesystem::exists(temporary));
  const std::vector<std::string> torn = readLines(temporary);
  ASSERT_EQ(torn.size(), 1u);
  EXPECT_FALSE(json::accept(torn[0])) << "the header was cut short";
  expectSameHistory(recovered(path), snapshotted.history());
  EXPECT_NE(readLines(path), before);  // the redo, journaled before the kill

  // The restart: restored, journaled again from it, and the dead child's temporary removed.
  Session restored(recovered(path));
  SessionJournal restarted;
  ASSERT_TRUE(restarted.start(path, restored).ok());
  EXPECT_FALSE(std::filesystem::exists(temporary));
  expectSameHistory(recovered(path), snapshotted.history());
  removeAll(paths);
}

// Found while measuring: a crease's delta is a few kB, so by bytes alone thousands of them
// would pass before a snapshot, and a restart would hold a state for each (at 100,000 vertices,
// gigabytes). Every commit weighs the state a restart makes of it.
TEST(JournalDelta, SmallDeltasStillBoundTheStatesARestartHolds)
{
  const std::string path = tempPath("small_deltas");
  // A sheet of 20 × 20 squares, every inner edge a flat crease: a crease across it splits a
  // column of them, a small part of the paper.
  std::vector<Vec2> corners;
  std::vector<std::vector<int>> squares;
  for (int j = 0; j <= 20; ++j)
    for (int i = 0; i <= 20; ++i)
      corners.emplace_back(i / 20.0, j / 20.0);
  for (int j = 0; j < 20; ++j)
    for (int i = 0; i < 20; ++i)
      squares.push_back({ j * 21 + i, j * 21 + i + 1, (j + 1) * 21 + i + 1, (j + 1) * 21 + i });
  Expected<Paper> grid = patternPaper(corners, squares);
  ASSERT_TRUE(grid.ok()) << grid.message();
  for (Edge& e : grid->edges)
    if (e.isCrease())
      e.assignment = Assignment::Flat;
  Session session(*grid);
  session.setHistoryLimit(3 * approximateBytes(session.paper()) + 1);
  SessionJournal journal;
  ASSERT_TRUE(journal.start(path, session).ok());
  size_t states_in_header = 1, commits_since = 0, snapshots = 0;
  for (int i = 0; i < 40; ++i)
  {
    const double x = (i + 0.5) / 40.0;  // between the grid's lines
    Expected<Computed<CreaseResult>> creased =
        computeCrease(session.workspace(), { p3(x, -0.1), p3(x, 1.1), std::nullopt, false });
    ASSERT_TRUE(creased) << creased.message();
    ASSERT_TRUE(journal.append(session, journalEvent(creased->change.operation, &*creased->change.next)).ok());
    ASSERT_TRUE(session.commit(std::move(creased->change)));
    ++commits_since;
    // Its line is a small part of the state it makes, yet counts as that state.
    EXPECT_LT(readLines(path).back().size() * 4, formatPaperJson(session.paper()).size());
    // A restart holds the header's states and one per commit after it: never more than twice
    // the header's, and the one that tipped the balance.
    EXPECT_LE(commits_since, 2 * states_in_header + 1) << "crease " << i;
    if (journal.wantsSnapshot(0))
    {
      ASSERT_TRUE(journal.snapshot(session).ok());
      ++snapshots;
      commits_since = 0;
      states_in_header = 1 + session.history().undo.size() + session.history().redo.size();
    }
  }
  EXPECT_GE(snapshots, 5u);
  // The same paper, revision and log; undo states as deep as the session's at least (the
  // session forgets the oldest by its memory limit, the journal since its last snapshot).
  const History read = recovered(path), &kept = session.history();
  expectBitForBit(read.paper, kept.paper, "paper");
  EXPECT_EQ(read.revision, kept.revision);
  EXPECT_EQ(read.log.size(), kept.log.size());
  ASSERT_GE(read.undo.size(), kept.undo.size());
  for (size_t i = 1; i <= kept.undo.size(); ++i)
    expectBitForBit(read.undo[read.undo.size() - i], kept.undo[kept.undo.size() - i], "undo");
  std::filesystem::remove(path);
}

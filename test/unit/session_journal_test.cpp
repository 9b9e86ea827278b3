#include <gtest/gtest.h>

#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <csignal>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <random>
#include <regex>

#include <nlohmann/json.hpp>

#include "test_models.h"
#include "virtual_origami/core/fold_io.h"
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
  const Expected<JournalRecovery> read = recoverJournal(path);
  ASSERT_TRUE(read.ok()) << read.message();
  EXPECT_EQ(read->history.log.size(), lines.size() - 2);  // header and the torn line
  // The torn line is not skipped in silence.
  EXPECT_EQ(read->dropped, std::vector<std::string>{ "line " + std::to_string(lines.size()) +
                                                     ": torn (a write cut short); dropped line " +
                                                     std::to_string(lines.size()) + " (1 line)" });
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
  const Expected<JournalRecovery> read = recoverJournal(path);
  ASSERT_TRUE(read.ok()) << read.message();
  ASSERT_EQ(read->dropped.size(), 1u);
  EXPECT_NE(read->dropped[0].find("line 3"), std::string::npos) << read->dropped[0];
  EXPECT_NE(read->dropped[0].find("fly"), std::string::npos) << read->dropped[0];
  EXPECT_EQ(read->history.revision, 1u);
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

TEST(SessionJournal, EdgesThatSplitAConcaveFaceStaySplit)
{
  const Expected<Paper> loaded = [] {
    const Expected<FoldDocument> doc = parseFold(R"({"vertices_coords": [[0,0],[2,0],[2,1],[1,1],[1,2],[0,2]],
        "faces_vertices": [[0,1,2,3,4,5]]})");
    return doc ? Expected<Paper>(doc->frames.back()) : Expected<Paper>::failure(doc.message());
  }();
  ASSERT_TRUE(loaded) << loaded.message();
  ASSERT_TRUE(std::any_of(loaded->edges.begin(), loaded->edges.end(), [](const Edge& e) { return e.split; }));
  const Expected<Paper> back = parsePaperJson(formatPaperJson(*loaded));
  ASSERT_TRUE(back.ok()) << back.message();
  EXPECT_TRUE(back.value() == *loaded);  // operator== compares the flag
}

namespace
{
/// Runs `change` on a copy of `session`, journals the operation it logged before committing it
/// (as paper_model does) and commits it only when the journal took it.
Status journaled(SessionJournal& journal, Session& session, const std::function<bool(Session&)>& change)
{
  Session next = session;
  if (!change(next))
    return failure("the change itself failed");
  const Operation& op = next.log().back();
  const bool step = op.kind == Operation::Kind::Undo || op.kind == Operation::Kind::Redo;
  const Status appended = journal.append(session, op, step ? nullptr : &next.paper());
  if (appended)
    session = std::move(next);
  return appended;
}

bool creaseDown(Session& s) { return s.crease({ p3(0.5, -0.1), p3(0.5, 1.1), std::nullopt, false }).ok(); }
bool creaseAcross(Session& s) { return s.crease({ p3(-0.1, 0.5), p3(1.1, 0.5), std::nullopt, false }).ok(); }
bool turnRight(Session& s)
{
  RotateRequest turn;
  turn.click = p3(0.8, 0.5);
  turn.angle = 2.0;
  return s.rotate(turn).ok();
}
bool undo(Session& s) { return s.undo().ok(); }
bool redo(Session& s) { return s.redo().ok(); }

/// A journal whose lines 2–7 are crease, undo, redo, rotate, undo, undo (the undo stack is
/// empty after lines 3 and 7, the redo stack after lines 2, 4 and 5), with the session's
/// history after each: states[k] after k operations, that is after line k + 1.
struct Steps
{
  std::vector<std::string> lines;
  std::vector<History> states;
};

Steps journalSteps(const std::string& path)
{
  Steps steps;
  SessionJournal journal;
  Session session;
  EXPECT_TRUE(journal.start(path, session).ok());
  steps.states.push_back(session.history());
  for (const auto& change : { creaseDown, undo, redo, turnRight, undo, undo })
  {
    const Status appended = journaled(journal, session, change);
    EXPECT_TRUE(appended.ok()) << appended.message();
    steps.states.push_back(session.history());
  }
  steps.lines = readLines(path);
  EXPECT_EQ(steps.lines.size(), 7u);
  return steps;
}

void writeLines(const std::string& path, const std::vector<std::string>& lines, bool last_torn = false)
{
  std::ofstream out(path, std::ios::trunc | std::ios::binary);
  for (size_t i = 0; i < lines.size(); ++i)
    out << lines[i] << (last_torn && i + 1 == lines.size() ? "" : "\n");
}

std::vector<std::string> firstLines(const std::vector<std::string>& lines, size_t count)
{
  return { lines.begin(), lines.begin() + count };
}

/// A journal damaged from line `bad` on: the lines before it, `damage` at it, and after it
/// `rest` (the original lines, or none when the damage is the last line).
struct Damage
{
  const char* what;
  size_t bad;          // the bad line's number
  std::string line;    // what stands there
  bool keep_rest;      // the original lines after it follow
  bool torn;           // it lacks its newline (only as the last line)
  std::string reason;  // the words `dropped` gives for it
};

void expectRecoversBefore(const Steps& steps, const Damage& damage)
{
  SCOPED_TRACE(damage.what);
  const std::string path = tempPath("damage");
  std::vector<std::string> lines = firstLines(steps.lines, damage.bad - 1);
  lines.push_back(damage.line);
  if (damage.keep_rest)
    lines.insert(lines.end(), steps.lines.begin() + damage.bad, steps.lines.end());
  writeLines(path, lines, damage.torn);

  const Expected<JournalRecovery> read = recoverJournal(path);
  ASSERT_TRUE(read.ok()) << read.message();
  // Everything before the bad line, bit-exact as the session that wrote it had it.
  expectSameHistory(read->history, steps.states[damage.bad - 2]);
  EXPECT_EQ(read->history.revision, damage.bad - 2);
  EXPECT_EQ(read->lines_read, damage.bad - 1);
  const size_t last = lines.size(), count = last - damage.bad + 1;
  const std::string range = count == 1 ? "line " + std::to_string(last) + " (1 line)" :
                                         "lines " + std::to_string(damage.bad) + "\u2013" + std::to_string(last) +
                                             " (" + std::to_string(count) + " lines)";
  ASSERT_EQ(read->dropped.size(), 1u);
  const std::string& dropped = read->dropped[0];
  EXPECT_EQ(dropped.rfind("line " + std::to_string(damage.bad) + ": ", 0), 0u) << dropped;
  EXPECT_NE(dropped.find(damage.reason), std::string::npos) << dropped;
  const std::string tail = "; dropped " + range;
  EXPECT_TRUE(dropped.size() > tail.size() && dropped.compare(dropped.size() - tail.size(), tail.size(), tail) == 0)
      << dropped << " should end in " << tail;
  // The thin reader gives the same history.
  const Expected<History> history = readJournal(path);
  ASSERT_TRUE(history.ok()) << history.message();
  expectSameHistory(*history, steps.states[damage.bad - 2]);
  std::filesystem::remove(path);
}

/// A commit's line without the state it carries (whole or as what it changed).
std::string withoutPaper(const std::string& line)
{
  nlohmann::json event = nlohmann::json::parse(line);
  EXPECT_TRUE(event.contains("paper") || event.contains("delta")) << line;
  event.erase("paper");
  event.erase("delta");
  return event.dump();
}

/// Whether this process may write where permissions say it may not (root, CAP_DAC_OVERRIDE).
bool permissionsAreIgnored(const std::filesystem::path& read_only_folder)
{
  const std::filesystem::path probe = read_only_folder / "probe";
  std::ofstream out(probe);
  const bool written = out.good();
  out.close();
  std::filesystem::remove(probe);
  return written;
}

/// Caps the size of files this process writes (setrlimit applies to root too) and puts the
/// cap back when it goes; a write past it fails with EFBIG instead of raising SIGXFSZ.
class FileSizeCap
{
public:
  explicit FileSizeCap(rlim_t bytes)
  {
    getrlimit(RLIMIT_FSIZE, &saved_);
    previous_handler_ = std::signal(SIGXFSZ, SIG_IGN);
    rlimit capped = saved_;
    capped.rlim_cur = bytes;
    EXPECT_EQ(setrlimit(RLIMIT_FSIZE, &capped), 0) << std::strerror(errno);
  }
  ~FileSizeCap() { lift(); }
  void lift()
  {
    if (lifted_)
      return;
    setrlimit(RLIMIT_FSIZE, &saved_);
    std::signal(SIGXFSZ, previous_handler_);
    lifted_ = true;
  }

private:
  rlimit saved_{};
  void (*previous_handler_)(int) = SIG_DFL;
  bool lifted_ = false;
};

void expectJournalHolds(const std::string& path, const Session& session, const std::string& run_id)
{
  const Expected<JournalRecovery> read = recoverJournal(path);
  ASSERT_TRUE(read.ok()) << read.message();
  EXPECT_TRUE(read->dropped.empty()) << read->dropped.front();
  EXPECT_EQ(read->run_id, run_id);
  expectSameHistory(read->history, session.history());
}
}  // namespace

TEST(SessionJournal, TheHeaderCarriesTheRunId)
{
  const std::string path = tempPath("run_id");
  Session session;
  ASSERT_TRUE(creaseDown(session));
  SessionJournal journal;
  ASSERT_TRUE(journal.start(path, session, "4d9f0a3e-run").ok());
  EXPECT_EQ(journal.runId(), "4d9f0a3e-run");
  ASSERT_TRUE(undo(session));
  ASSERT_TRUE(journal.record(session).ok());
  expectJournalHolds(path, session, "4d9f0a3e-run");
  // Without one (and in journals from before run ids) it reads back empty.
  ASSERT_TRUE(journal.start(path, session).ok());
  expectJournalHolds(path, session, "");
  std::filesystem::remove(path);
}

TEST(SessionJournal, AppendJournalsAnOperationBeforeItIsCommitted)
{
  const std::string path = tempPath("append");
  SessionJournal journal;
  EXPECT_TRUE(journal.sync());
  EXPECT_FALSE(journal.healthy());
  Session session;
  EXPECT_FALSE(journal.append(session, Operation{}, &session.paper()).ok()) << "never started";
  ASSERT_TRUE(journal.start(path, session).ok());
  EXPECT_TRUE(journal.healthy());
  for (const auto& change : { creaseDown, turnRight, undo, redo, undo })
    ASSERT_TRUE(journaled(journal, session, change).ok());
  journal.setSync(false);  // the same lines, only not waited for
  ASSERT_TRUE(journaled(journal, session, creaseAcross).ok());
  expectJournalHolds(path, session, "");
  const size_t lines = readLines(path).size();

  // What the reader would drop is refused, and the journal stays as it was, healthy.
  Session next = session;
  ASSERT_TRUE(turnRight(next));
  Operation op = next.log().back();
  EXPECT_FALSE(journal.append(op, nullptr).ok()) << "a commit without its state";
  Operation skipping = op;
  skipping.revision += 1;
  EXPECT_FALSE(journal.append(skipping, &next.paper()).ok()) << "a revision skipped";
  Operation stepping;
  stepping.kind = Operation::Kind::Redo;
  stepping.revision = op.revision;
  EXPECT_FALSE(journal.append(stepping, nullptr).ok()) << "nothing to redo";
  stepping.kind = Operation::Kind::Undo;
  EXPECT_FALSE(journal.append(stepping, &next.paper()).ok()) << "an undo with a state";
  EXPECT_TRUE(journal.healthy());
  EXPECT_EQ(readLines(path).size(), lines);
  ASSERT_TRUE(journal.append(op, &next.paper()).ok());
  session = next;
  expectJournalHolds(path, session, "");
  std::filesystem::remove(path);
}

TEST(SessionJournal, RecordCatchesUpByStartingAgainWhenItFellBehind)
{
  const std::string path = tempPath("behind");
  SessionJournal journal;
  Session session;
  ASSERT_TRUE(journal.start(path, session, "run").ok());
  // Two commits unrecorded: the first one's state exists only in the undo stack now.
  ASSERT_TRUE(creaseDown(session));
  ASSERT_TRUE(creaseAcross(session));
  ASSERT_TRUE(journal.record(session).ok());
  expectJournalHolds(path, session, "run");
  ASSERT_TRUE(undo(session));
  ASSERT_TRUE(journal.record(session).ok());
  expectJournalHolds(path, session, "run");
  std::filesystem::remove(path);
}

TEST(SessionJournal, AFailedWriteIsRefusedUntilTheJournalIsWholeAgain)
{
  const std::string path = tempPath("full");
  SessionJournal journal;
  Session session;
  ASSERT_TRUE(creaseDown(session));
  ASSERT_TRUE(journal.start(path, session, "run").ok());
  const History before = session.history();
  {
    // The disk takes a few bytes of the event, then no more: a torn line.
    FileSizeCap cap(std::filesystem::file_size(path) + 20);
    const Status appended = journaled(journal, session, turnRight);
    cap.lift();
    ASSERT_FALSE(appended.ok());
    EXPECT_NE(appended.message().find(path), std::string::npos) << appended.message();
    EXPECT_NE(appended.message().find(std::strerror(EFBIG)), std::string::npos) << appended.message();
  }
  EXPECT_FALSE(journal.healthy());
  expectSameHistory(session.history(), before);  // refused, so not committed
  // Nothing acknowledged is lost and nothing refused is read back.
  expectJournalHolds(path, session, "run");
  {
    // Still refused while the disk refuses (the journal starts again, then the event fails).
    FileSizeCap cap(std::filesystem::file_size(path) + 20);
    const Status appended = journaled(journal, session, turnRight);
    cap.lift();
    EXPECT_FALSE(appended.ok());
  }
  EXPECT_FALSE(journal.healthy());
  expectJournalHolds(path, session, "run");
  // A bare append cannot start again: it has no session.
  Session next = session;
  ASSERT_TRUE(turnRight(next));
  EXPECT_FALSE(journal.append(next.log().back(), &next.paper()).ok());
  // Once the disk takes writes again the next append rewrites the journal, then appends.
  const Status appended = journaled(journal, session, turnRight);
  ASSERT_TRUE(appended.ok()) << appended.message();
  EXPECT_TRUE(journal.healthy());
  ASSERT_TRUE(journaled(journal, session, undo).ok());
  expectJournalHolds(path, session, "run");
  for (const std::string& line : readLines(path))
    EXPECT_EQ(line.back(), '}');  // no torn line left inside
  std::filesystem::remove(path);
}

TEST(SessionJournal, AJournalThatCannotBeStartedRecoversWhenItsFolderDoes)
{
  const std::filesystem::path folder = tempPath("folder");
  std::filesystem::create_directories(folder);
  const std::string path = (folder / "journal.jsonl").string();
  std::filesystem::permissions(folder, std::filesystem::perms::owner_read | std::filesystem::perms::owner_exec);
  // Root writes through permissions: take the folder away instead.
  const bool remove_folder = permissionsAreIgnored(folder);
  if (remove_folder)
    std::filesystem::remove_all(folder);

  SessionJournal journal;
  Session session;
  ASSERT_TRUE(creaseDown(session));
  const Status started = journal.start(path, session, "run");
  ASSERT_FALSE(started.ok());
  EXPECT_NE(started.message().find(path), std::string::npos) << started.message();
  EXPECT_FALSE(journal.healthy());
  EXPECT_EQ(journal.path(), path);
  const History before = session.history();
  EXPECT_FALSE(journaled(journal, session, turnRight).ok());
  expectSameHistory(session.history(), before);

  if (remove_folder)
    std::filesystem::create_directories(folder);
  std::filesystem::permissions(folder, std::filesystem::perms::owner_all);
  const Status appended = journaled(journal, session, turnRight);
  ASSERT_TRUE(appended.ok()) << appended.message();
  EXPECT_TRUE(journal.healthy());
  expectJournalHolds(path, session, "run");
  std::filesystem::remove_all(folder);
}

TEST(SessionJournal, StartNeverWritesThroughALinkAtItsTemporaryName)
{
  const std::filesystem::path folder = tempPath("links");
  std::filesystem::create_directories(folder);
  const std::string path = (folder / "journal.jsonl").string();
  const std::filesystem::path victim = folder / "victim", absent = folder / "absent";
  writeLines(victim.string(), { "precious" });
  // Links at the first temporary names it would take, to a file and to where none is yet.
  const std::string stem = path + ".tmp." + std::to_string(::getpid()) + ".";
  std::filesystem::create_symlink(victim, stem + "0");
  std::filesystem::create_symlink(absent, stem + "1");

  const mode_t mask = ::umask(022);
  ::umask(mask);
  SessionJournal journal;
  Session session;
  ASSERT_TRUE(creaseDown(session));
  ASSERT_TRUE(journal.start(path, session).ok());
  EXPECT_EQ(readLines(victim.string()), std::vector<std::string>{ "precious" });
  EXPECT_FALSE(std::filesystem::exists(std::filesystem::symlink_status(absent)));
  EXPECT_TRUE(std::filesystem::is_symlink(stem + "0"));
  EXPECT_TRUE(std::filesystem::is_symlink(stem + "1"));
  EXPECT_FALSE(std::filesystem::is_symlink(path));
  struct stat journal_stat;
  ASSERT_EQ(::stat(path.c_str(), &journal_stat), 0);
  EXPECT_EQ(journal_stat.st_mode & 0777, 0644 & ~mask);
  expectJournalHolds(path, session, "");
  // Nothing else left beside it.
  size_t files = 0;
  for ([[maybe_unused]] const auto& entry : std::filesystem::directory_iterator(folder))
    ++files;
  EXPECT_EQ(files, 4u);  // the journal, the victim and the two links
  std::filesystem::remove_all(folder);
}

TEST(SessionJournal, KeptAsideNamesAreNeverTakenTwice)
{
  const std::string path = tempPath("kept");
  const std::string first = keepAsideName(path);
  writeLines(first, { "an old journal" });
  const std::string second = keepAsideName(path);
  EXPECT_NE(first, second);
  EXPECT_FALSE(std::filesystem::exists(second));
  const std::regex form(std::regex_replace(path, std::regex(R"([.^$|()\[\]{}*+?\\])"), R"(\$&)") +
                        R"(\.\d{8}T\d{6}\.\d{9}\.)" + std::to_string(::getpid()) + R"((\.\d+)?\.old)");
  EXPECT_TRUE(std::regex_match(first, form)) << first;
  EXPECT_TRUE(std::regex_match(second, form)) << second;
  std::filesystem::remove(first);
}

TEST(SessionJournal, RecoveryKeepsEverythingBeforeABadLineInTheMiddle)
{
  const Steps steps = journalSteps(tempPath("steps"));
  const std::vector<std::string>& l = steps.lines;
  for (const Damage& damage : std::vector<Damage>{
           { "torn, not JSON", 4, R"({"operation": {"kind": "redo", "revis)", true, false, "not JSON" },
           { "an empty line", 4, "", true, false, "empty" },
           { "no operation", 3, R"({"paper": {}})", true, false, "no operation" },
           { "no revision", 4, R"({"operation": {"kind": "redo"}})", true, false, "revision" },
           { "a commit without its state", 5, withoutPaper(l[4]), true, false, "a commit without its state" },
           { "nothing to undo", 4, R"({"operation": {"kind": "undo", "revision": 3}})", true, false,
             "nothing to undo" },
           { "nothing to redo", 3, R"({"operation": {"kind": "redo", "revision": 2}})", true, false,
             "nothing to redo" },
           { "a revision out of range", 4, R"({"operation": {"kind": "redo", "revision": 1e308}})", true, false,
             "1e+308 is not an integer in range" },
           { "a revision skipped", 4, R"({"operation": {"kind": "redo", "revision": 4}})", true, false,
             "revision 4 does not follow revision 2" },
           { "a revision repeated", 4, l[2], true, false, "revision 2 does not follow revision 2" } })
    expectRecoversBefore(steps, damage);
  std::filesystem::remove(tempPath("steps"));
}

TEST(SessionJournal, RecoveryKeepsEverythingBeforeABadLastLine)
{
  const Steps steps = journalSteps(tempPath("steps"));
  const std::vector<std::string>& l = steps.lines;
  for (const Damage& damage : std::vector<Damage>{
           { "torn", 7, l[6].substr(0, l[6].size() / 2), false, true, "torn (a write cut short)" },
           { "torn just before its newline", 7, l[6], false, true, "torn (a write cut short)" },
           { "not JSON", 8, "\x01garbage", false, false, "not JSON" },
           { "a commit without its state", 5, withoutPaper(l[4]), false, false, "a commit without its state" },
           { "nothing to undo", 8, R"({"operation": {"kind": "undo", "revision": 7}})", false, false,
             "nothing to undo" },
           { "nothing to redo", 6, R"({"operation": {"kind": "redo", "revision": 5}})", false, false,
             "nothing to redo" },
           { "a revision out of range", 8, R"({"operation": {"kind": "redo", "revision": 1e308}})", false, false,
             "1e+308 is not an integer in range" },
           { "a revision skipped", 8, R"({"operation": {"kind": "redo", "revision": 9}})", false, false,
             "revision 9 does not follow revision 6" } })
    expectRecoversBefore(steps, damage);
  std::filesystem::remove(tempPath("steps"));
}

TEST(SessionJournal, DroppedLinesAreSaidInWords)
{
  const std::string path = tempPath("words");
  const Steps steps = journalSteps(path);
  std::vector<std::string> lines = steps.lines;
  lines[3] = R"({"operation": {"kind": "undo", "revision": 3}})";
  writeLines(path, lines);
  const Expected<JournalRecovery> read = recoverJournal(path);
  ASSERT_TRUE(read.ok()) << read.message();
  EXPECT_EQ(read->dropped, std::vector<std::string>{ "line 4: nothing to undo; dropped lines 4\u20137 (4 lines)" });
  std::filesystem::remove(path);
}

TEST(SessionJournal, ABadHeaderRecoversNothing)
{
  const std::string path = tempPath("header");
  const Steps steps = journalSteps(path);
  for (const std::string& header :
       { steps.lines[0].substr(0, steps.lines[0].size() / 2), std::string("5"), std::string("{}"), std::string("") })
  {
    std::vector<std::string> lines = steps.lines;
    lines[0] = header;
    writeLines(path, lines);
    const Expected<JournalRecovery> read = recoverJournal(path);
    ASSERT_FALSE(read.ok()) << header;
    EXPECT_NE(read.message().find("line 1"), std::string::npos) << read.message();
    EXPECT_FALSE(readJournal(path).ok());
  }
  writeLines(path, {});
  EXPECT_FALSE(recoverJournal(path).ok());
  std::filesystem::remove(path);
}

TEST(SessionJournal, ALoadedFileNameThatIsNotUtf8IsJournaledNotThrown)
{
  const std::string path = tempPath("utf8");
  SessionJournal journal;
  Session session;
  ASSERT_TRUE(journal.start(path, session).ok());
  // A sheet of another size: a load of the paper as it is makes no revision.
  ASSERT_TRUE(session.load(Paper::square(2.0), "/tmp/\xff\xfe.fold").ok());
  const Status recorded = journal.record(session);  // nlohmann's dump() threw on the name
  ASSERT_TRUE(recorded.ok()) << recorded.message();
  const Expected<JournalRecovery> read = recoverJournal(path);
  ASSERT_TRUE(read.ok()) << read.message();
  EXPECT_TRUE(read->dropped.empty());
  EXPECT_TRUE(read->history.paper == session.paper());
  std::filesystem::remove(path);
}

// Found by the round-3 probe: a respawn read back every state a large session had made (2
// minutes). Once the events outweigh the header they become a new header: a restart reads
// within twice a header, and reads back the same history.
TEST(SessionJournal, ASnapshotBoundsWhatARestartReads)
{
  const std::string path = tempPath("snapshot.jsonl");
  SessionJournal journal;
  Session session;
  ASSERT_TRUE(journal.start(path, session));
  session.setHistoryLimit(4 * approximateBytes(session.paper()) + 1);
  int snapshots = 0;
  for (int i = 0; i < 60; ++i)
  {
    CreaseRequest line;
    line.start = p3(0.01 + 0.98 * i / 60.0, -0.1);
    line.end = p3(0.01 + 0.98 * i / 60.0, 1.1);
    // As paper_model journals: the change appended before it is committed.
    Expected<Computed<CreaseResult>> creased = computeCrease(session.workspace(), line);
    ASSERT_TRUE(creased) << creased.message();
    const uint64_t before = journal.eventWeight();
    ASSERT_TRUE(journal.append(session, creased->change.operation, &*creased->change.next));
    ASSERT_TRUE(session.commit(std::move(creased->change)));
    const uint64_t event = journal.eventWeight() - before;
    // What a restart would read now: a header and events no heavier, but for the last one.
    EXPECT_EQ(std::filesystem::file_size(path), journal.headerBytes() + journal.eventBytes());
    EXPECT_LE(journal.eventBytes(), journal.eventWeight());
    EXPECT_LE(journal.headerBytes(), journal.headerWeight());
    EXPECT_LE(journal.eventWeight(), journal.headerWeight() + event);
    if (journal.wantsSnapshot(0))
    {
      ASSERT_TRUE(journal.snapshot(session));
      ++snapshots;
      EXPECT_EQ(std::filesystem::file_size(path), journal.headerBytes());
    }
  }
  EXPECT_GT(snapshots, 3);
  const Expected<History> read = readJournal(path);
  ASSERT_TRUE(read) << read.message();
  // The same paper, revision and log; undo states as deep as the session's at least (the
  // session forgets the oldest by its memory limit, the journal since its last snapshot).
  const History& kept = session.history();
  EXPECT_TRUE(read->paper == kept.paper);
  EXPECT_EQ(read->revision, kept.revision);
  EXPECT_EQ(read->log.size(), kept.log.size());
  ASSERT_GE(read->undo.size(), kept.undo.size());
  for (size_t i = 1; i <= kept.undo.size(); ++i)
    EXPECT_TRUE(read->undo[read->undo.size() - i] == kept.undo[kept.undo.size() - i]);
  std::filesystem::remove(path);
}

// The cost of journaling one operation (core::SessionJournal::append) against model size: flat
// grid sheets of about 100, 1k, 10k and 100k vertices.
//
// journal.csv: each append carries the whole state it makes (a load; what every commit wrote
// before the journal wrote deltas), with fsync on and off. Every append is timed on its own; so
// are, directly, the fsync of each unsynced append's line (through a second descriptor, right
// after it) and the JSON formatting of the same paper (formatPaperJson).
//
// journal_delta.csv: what paper_model journals now, for three kinds of change: a fold that
// moves every vertex and turns every crease (as folding by assignment does), a rotation of half
// the sheet about its middle line, and a crease across the sheet (new vertices, edges and faces).
// Each kind runs twice on the same changes: once journaled whole (the state per line, as before)
// and once as deltas as paper_model does it (core::journalEvent outside the lock, which copies
// the state; SessionJournal::append(session, event) under it, which writes what changed in the
// session's paper, synced). Then the journal is read back (recoverJournal, checked against the
// session bit for bit) and a snapshot taken (the session with its undo states as the header).
//   journal_bench OUT_DIR [TEMP_PARENT [SIDES]]
// SIDES: grid sides to run, comma-separated (default 9,31,99,315: 100 to 100k vertices). The
// journals go to a temporary folder made in TEMP_PARENT (the build folder from make bench: on
// disk, not tmpfs) and removed at the end.
#include <fcntl.h>
#include <sys/statfs.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <cmath>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "virtual_origami/core/paper_delta.h"
#include "virtual_origami/core/session.h"
#include "virtual_origami/core/session_journal.h"

#include "grid_paper.h"

using namespace virtual_origami::core;
namespace core = virtual_origami::core;

namespace
{
double now()
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

double percentile(std::vector<double> v, double p)
{
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, static_cast<size_t>(p * (v.size() - 1) + 0.5))];
}

std::string fileSystemOf(const std::string& path)
{
  struct statfs s
  {};
  if (::statfs(path.c_str(), &s) != 0)
    return "unknown";
  switch (static_cast<unsigned long>(s.f_type))
  {
    case 0xEF53:
      return "ext4";
    case 0x01021994:
      return "tmpfs";
    case 0x9123683E:
      return "btrfs";
    case 0x58465342:
      return "xfs";
    case 0x794C7630:
      return "overlayfs";
    default:
      return "other";
  }
}

enum class ChangeKind
{
  Fold,
  Rotate,
  Crease
};

const char* changeName(ChangeKind change)
{
  return change == ChangeKind::Fold ? "fold" : change == ChangeKind::Rotate ? "rotate" : "crease";
}

/// The `i`-th change of a kind on the session's paper, as paper_model would commit it.
core::Change nextChange(const Session& session, ChangeKind kind, int i, int w)
{
  core::Change change;
  change.base_revision = session.revision();
  change.operation.revision = session.revision() + 1;
  if (kind == ChangeKind::Crease)
  {
    // Through the middles of a column of faces: w new vertices' worth of faces split.
    const double x = (0.5 + (i * 7) % w) / w;
    Expected<Computed<CreaseResult>> creased =
        computeCrease(session.workspace(), CreaseRequest{ Vec3(x, -0.1, 0), Vec3(x, 1.1, 0), std::nullopt, false });
    if (!creased)
    {
      std::fprintf(stderr, "journal_bench: crease %d: %s\n", i, creased.message().c_str());
      std::exit(1);
    }
    return std::move(creased->change);
  }
  Paper next = session.paper();
  if (kind == ChangeKind::Fold)
  {
    change.operation.kind = Operation::Kind::AssignmentFold;
    change.operation.fraction = 0.01 * (i + 1);
    for (Vertex& v : next.vertices)
      v.folded.z() = 1e-3 * std::sin(7 * v.crease_pattern.x() + i) * std::cos(5 * v.crease_pattern.y());
    for (Edge& e : next.edges)
      if (e.isCrease())
        e.fold_angle = 0.01 * (i + 1);
  }
  else
  {
    // Half the sheet turned about x = 0.5 (a grid line for even sides, else near it).
    change.operation.kind = Operation::Kind::Rotate;
    const double angle = 0.1 + 0.01 * i;
    for (Vertex& v : next.vertices)
      if (v.crease_pattern.x() > 0.5)
      {
        const double r = v.crease_pattern.x() - 0.5;
        v.folded = Vec3(0.5 + r * std::cos(angle), v.crease_pattern.y(), r * std::sin(angle));
      }
    for (Edge& e : next.edges)
      if (e.isCrease() && next.vertices[e.vertices[0]].crease_pattern.x() == 0.5 &&
          next.vertices[e.vertices[1]].crease_pattern.x() == 0.5)
        e.fold_angle = angle;
    change.operation.rotate.angle = angle;
  }
  change.next = std::move(next);
  return change;
}

struct DeltaRun
{
  std::vector<double> ahead_ms, append_ms;
  uintmax_t line_bytes = 0;
  double restore_ms = 0, snapshot_ms = 0;
  uintmax_t snapshot_bytes = 0;
};

/// `appends` changes of `kind` journaled whole (`deltas` false) or as paper_model does.
DeltaRun journalChanges(const Paper& paper, int w, ChangeKind kind, int appends, bool deltas, const std::string& path)
{
  DeltaRun run;
  Session session(paper);
  // Four states' worth of undo history, as history_memory_mb bounds a large one.
  session.setHistoryLimit(4 * approximateBytes(paper) + 1);
  SessionJournal journal;
  if (const Status started = journal.start(path, session, "journal_bench"); !started)
  {
    std::fprintf(stderr, "journal_bench: %s\n", started.message().c_str());
    std::exit(1);
  }
  const uintmax_t header = std::filesystem::file_size(path);
  for (int i = 0; i < appends; ++i)
  {
    core::Change change = nextChange(session, kind, i, w);
    double t0 = now();
    Status appended = success();
    if (deltas)
    {
      const JournalEvent event = journalEvent(change.operation, &*change.next);
      run.ahead_ms.push_back(1e3 * (now() - t0));
      t0 = now();
      appended = journal.append(session, event);
    }
    else
    {
      // What every commit did before: the whole state, formatted and written.
      appended = journal.append(change.operation, &*change.next);
      run.ahead_ms.push_back(0);
    }
    run.append_ms.push_back(1e3 * (now() - t0));
    if (!appended || !session.commit(std::move(change)))
    {
      std::fprintf(stderr, "journal_bench: %s %d: %s\n", changeName(kind), i, appended.message().c_str());
      std::exit(1);
    }
  }
  run.line_bytes = (std::filesystem::file_size(path) - header) / appends;
  double t0 = now();
  const Expected<History> read = readJournal(path);
  run.restore_ms = 1e3 * (now() - t0);
  if (!read || !(read->paper == session.paper()) || read->revision != session.revision())
  {
    std::fprintf(stderr, "journal_bench: %s: the journal does not read back the session: %s\n", changeName(kind),
                 read ? "another state" : read.message().c_str());
    std::exit(1);
  }
  t0 = now();
  if (const Status snapped = journal.snapshot(session); !snapped)
  {
    std::fprintf(stderr, "journal_bench: snapshot: %s\n", snapped.message().c_str());
    std::exit(1);
  }
  run.snapshot_ms = 1e3 * (now() - t0);
  run.snapshot_bytes = std::filesystem::file_size(path);
  if (!deltas)
  {
    // What a version 1 header held: the paper and every undo state whole (the log aside).
    run.snapshot_bytes = formatPaperJson(session.paper()).size();
    for (const Paper& state : session.history().undo)
      run.snapshot_bytes += formatPaperJson(state).size();
  }
  std::filesystem::remove(path);
  ::sync();
  return run;
}

std::vector<int> sidesFrom(const char* text)
{
  std::vector<int> sides;
  std::stringstream in(text);
  for (std::string side; std::getline(in, side, ',');)
    sides.push_back(std::stoi(side));
  return sides;
}
}  // namespace

int main(int argc, char** argv)
{
  if (argc < 2)
  {
    std::fprintf(stderr, "usage: journal_bench OUT_DIR [TEMP_PARENT [SIDES]]\n");
    return 2;
  }
  const std::string out_dir = argv[1];
  const std::filesystem::path parent = argc > 2 ? argv[2] : std::filesystem::current_path().string();
  std::string pattern = (parent / "journal_bench.XXXXXX").string();
  if (!::mkdtemp(pattern.data()))
  {
    std::perror("journal_bench: mkdtemp");
    return 1;
  }
  const std::filesystem::path dir = pattern;
  const std::string fs = fileSystemOf(dir.string());
  if (fs == "tmpfs")
    std::fprintf(stderr, "journal_bench: warning: %s is on tmpfs, fsync costs nothing there\n", dir.c_str());

  std::ofstream csv(out_dir + "/journal.csv");
  csv << "vertices,edges,faces,appends,line_bytes,sync_median_ms,sync_p95_ms,sync_max_ms,nosync_median_ms,"
         "nosync_p95_ms,nosync_max_ms,fsync_median_ms,fsync_p95_ms,format_median_ms,filesystem\n";
  // Side of the grid (vertices (w + 1)²) and appends per setting.
  const std::vector<int> sides = argc > 3 ? sidesFrom(argv[3]) : std::vector<int>{ 9, 31, 99, 315 };
  for (const int w : sides)
  {
    const int appends = 50;
    const Paper paper = virtual_origami::bench::gridPaper(w, "journal_bench");
    // The formatting alone, timed directly (the JSON an append writes holds this and the operation).
    std::vector<double> format_ms;
    for (int i = 0; i < std::min(appends, 10); ++i)
    {
      const double t0 = now();
      const std::string text = formatPaperJson(paper);
      format_ms.push_back(1e3 * (now() - t0));
    }
    std::map<bool, std::vector<double>> append_ms;
    std::vector<double> fsync_ms;
    uintmax_t line = 0;
    for (const bool sync : { true, false })
    {
      const std::string path = (dir / ("journal_" + std::to_string(w) + (sync ? "_sync" : "_nosync") + ".jsonl"));
      SessionJournal journal;
      journal.setSync(sync);
      const Status started = journal.start(path, Session(paper), "journal_bench");
      if (!started)
      {
        std::fprintf(stderr, "journal_bench: %s\n", started.message().c_str());
        return 1;
      }
      // Without sync, the line each append leaves in the page cache is synced right after it
      // through a second descriptor and timed on its own: fsync's share, measured directly.
      const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
      const uintmax_t header = std::filesystem::file_size(path);
      for (int i = 1; i <= appends; ++i)
      {
        Operation op;
        op.kind = Operation::Kind::Load;  // a commit carrying a whole new state
        op.path = "grid.fold";
        op.revision = static_cast<uint64_t>(i);
        const double t0 = now();
        const Status appended = journal.append(op, &paper);
        append_ms[sync].push_back(1e3 * (now() - t0));
        if (!appended)
        {
          std::fprintf(stderr, "journal_bench: append %d: %s\n", i, appended.message().c_str());
          return 1;
        }
        if (!sync)
        {
          const double t1 = now();
          if (::fsync(fd) != 0)
          {
            std::perror("journal_bench: fsync");
            return 1;
          }
          fsync_ms.push_back(1e3 * (now() - t1));
        }
      }
      ::close(fd);
      line = (std::filesystem::file_size(path) - header) / appends;
      // Untimed: the next setting starts with no dirty pages of this one to write back.
      std::filesystem::remove(path);
      ::sync();
    }
    const std::vector<double>& on = append_ms[true];
    const std::vector<double>& off = append_ms[false];
    csv << paper.vertices.size() << ',' << paper.edges.size() << ',' << paper.faces.size() << ',' << appends << ','
        << line << ',' << percentile(on, 0.5) << ',' << percentile(on, 0.95) << ',' << percentile(on, 1.0) << ','
        << percentile(off, 0.5) << ',' << percentile(off, 0.95) << ',' << percentile(off, 1.0) << ','
        << percentile(fsync_ms, 0.5) << ',' << percentile(fsync_ms, 0.95) << ',' << percentile(format_ms, 0.5) << ','
        << fs << '\n';
    std::printf("%7zu vertices, %2d appends of %9ju bytes: sync on median %8.3f ms p95 %8.3f ms; off median "
                "%8.3f ms p95 %8.3f ms; fsync alone median %7.3f ms p95 %7.3f ms; formatting %8.3f ms\n",
                paper.vertices.size(), appends, line, percentile(on, 0.5), percentile(on, 0.95), percentile(off, 0.5),
                percentile(off, 0.95), percentile(fsync_ms, 0.5), percentile(fsync_ms, 0.95),
                percentile(format_ms, 0.5));
    std::fflush(stdout);
  }
  csv.close();

  std::ofstream deltas(out_dir + "/journal_delta.csv");
  deltas << "vertices,change,appends,whole_line_bytes,whole_append_median_ms,whole_append_p95_ms,whole_restore_ms,"
            "whole_snapshot_bytes,delta_line_bytes,delta_ahead_median_ms,delta_append_median_ms,delta_append_p95_ms,"
            "delta_restore_ms,delta_snapshot_bytes,delta_snapshot_ms,filesystem\n";
  for (const int w : sides)
  {
    const Paper paper = virtual_origami::bench::gridPaper(w, "journal_bench");
    // Fewer at 100k vertices: a whole line there takes half a second, and reading them back more.
    const int appends = paper.vertices.size() > 50000 ? 10 : 20;
    for (const ChangeKind kind : { ChangeKind::Fold, ChangeKind::Rotate, ChangeKind::Crease })
    {
      const std::string path = (dir / ("delta_" + std::to_string(w) + ".jsonl")).string();
      const DeltaRun whole = journalChanges(paper, w, kind, appends, false, path);
      const DeltaRun delta = journalChanges(paper, w, kind, appends, true, path);
      deltas << paper.vertices.size() << ',' << changeName(kind) << ',' << appends << ',' << whole.line_bytes << ','
             << percentile(whole.append_ms, 0.5) << ',' << percentile(whole.append_ms, 0.95) << ',' << whole.restore_ms
             << ',' << whole.snapshot_bytes << ',' << delta.line_bytes << ',' << percentile(delta.ahead_ms, 0.5) << ','
             << percentile(delta.append_ms, 0.5) << ',' << percentile(delta.append_ms, 0.95) << ',' << delta.restore_ms
             << ',' << delta.snapshot_bytes << ',' << delta.snapshot_ms << ',' << fs << '\n';
      std::printf("%7zu vertices, %-6s x%2d: whole %9ju B/op, append median %8.2f ms, restore %8.1f ms, snapshot "
                  "%9ju B | delta %9ju B/op, ahead %7.2f ms + append median %7.2f ms (p95 %7.2f), restore %8.1f ms, "
                  "snapshot %9ju B in %7.1f ms\n",
                  paper.vertices.size(), changeName(kind), appends, whole.line_bytes, percentile(whole.append_ms, 0.5),
                  whole.restore_ms, whole.snapshot_bytes, delta.line_bytes, percentile(delta.ahead_ms, 0.5),
                  percentile(delta.append_ms, 0.5), percentile(delta.append_ms, 0.95), delta.restore_ms,
                  delta.snapshot_bytes, delta.snapshot_ms);
      std::fflush(stdout);
    }
  }
  std::filesystem::remove_all(dir);
  std::printf("wrote %s/journal.csv and journal_delta.csv (journals in %s, %s, removed)\n", out_dir.c_str(),
              dir.c_str(), fs.c_str());
  return 0;
}

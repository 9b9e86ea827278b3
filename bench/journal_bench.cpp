// The cost of journaling one operation (core::SessionJournal::append) with fsync on and off,
// against model size: flat grid sheets of about 100, 1k, 10k and 100k vertices. Each append
// carries the whole state it makes (as every committed change does in paper_model), so its
// line grows with the model. Every append is timed on its own; so are, directly, the fsync of
// each unsynced append's line (through a second descriptor, right after it) and the JSON
// formatting of the same paper (formatPaperJson).
//   journal_bench OUT_DIR [TEMP_PARENT]
// Writes OUT_DIR/journal.csv. The journals go to a temporary folder made in TEMP_PARENT (the
// build folder from make bench: on disk, not tmpfs) and removed at the end.
#include <fcntl.h>
#include <sys/statfs.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include "virtual_origami/core/session.h"
#include "virtual_origami/core/session_journal.h"

#include "grid_paper.h"

using namespace virtual_origami::core;

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
}  // namespace

int main(int argc, char** argv)
{
  if (argc < 2)
  {
    std::fprintf(stderr, "usage: journal_bench OUT_DIR [TEMP_PARENT]\n");
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
  const std::vector<std::pair<int, int>> sizes{ { 9, 50 }, { 31, 50 }, { 99, 50 }, { 315, 50 } };
  for (const auto& [w, appends] : sizes)
  {
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
  std::filesystem::remove_all(dir);
  std::printf("wrote %s/journal.csv (journals in %s, %s, removed)\n", out_dir.c_str(), dir.c_str(), fs.c_str());
  return 0;
}

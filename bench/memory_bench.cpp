// Resident memory of a session against model size (flat grid sheets of about 1k, 10k and
// 100k vertices) and undo history length (0, 10, 50 commits of a whole new state: loads of the
// same paper), without a history limit and with one of 256 MB; and of a 100k-vertex FOLD file
// read through core::loadPaper. Each configuration runs in a child process of its own (fork),
// so none inherits another's heap; the parent builds nothing. Every figure is read in the
// child: resident set from /proc/self/statm before and after, the peak (VmHWM), the session's
// own count (approximateBytes, historyBytes), and the resident set again after malloc_trim(0),
// which hands glibc's free memory back to the system (what it returns was allocator slack).
//   memory_bench OUT_DIR [TEMP_PARENT]
// Writes OUT_DIR/memory.csv; the FOLD file goes to a temporary folder in TEMP_PARENT, removed.
#include <malloc.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "virtual_origami/core/fold_io.h"
#include "virtual_origami/core/session.h"

#include "grid_paper.h"

using namespace virtual_origami::core;

namespace
{
constexpr double kMB = 1e6;

/// Resident bytes now (/proc/self/statm, second field, in pages).
double residentBytes()
{
  std::ifstream statm("/proc/self/statm");
  long size = 0, resident = 0;
  statm >> size >> resident;
  return static_cast<double>(resident) * static_cast<double>(::sysconf(_SC_PAGESIZE));
}

/// The peak resident set of this process (VmHWM of /proc/self/status), bytes.
double peakBytes()
{
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line))
    if (line.rfind("VmHWM:", 0) == 0)
      return 1024.0 * std::stod(line.substr(6));
  return 0;
}

struct Measured
{
  std::string kind;
  size_t vertices = 0;
  int history = 0;
  double limit_mb = 0;
  double baseline = 0, resident = 0, trimmed = 0, peak = 0;
  double paper_bytes = 0, history_bytes = 0;
  size_t kept = 0, forgotten = 0;
  double file_bytes = 0;  // of the FOLD file read
};

std::string csvLine(const Measured& m)
{
  std::ostringstream s;
  s << m.kind << ',' << m.vertices << ',' << m.history << ',' << m.limit_mb << ',' << m.baseline / kMB << ','
    << m.resident / kMB << ',' << m.trimmed / kMB << ',' << m.peak / kMB << ',' << m.paper_bytes / kMB << ','
    << m.history_bytes / kMB << ',' << m.kept << ',' << m.forgotten << ',' << m.file_bytes / kMB << '\n';
  return s.str();
}

/// A session on a w × w grid after `history` loads of the same paper, limited or not.
Measured sessionCase(int w, int history, double limit_mb)
{
  Measured m;
  m.kind = "session";
  m.history = history;
  m.limit_mb = limit_mb;
  m.baseline = residentBytes();
  {
    // The paper the session is built from goes with the lambda: what is left is the session's.
    const Session session = [&] {
      const Paper paper = virtual_origami::bench::gridPaper(w, "memory_bench");
      Session s(paper);
      s.setHistoryLimit(static_cast<size_t>(limit_mb * kMB));
      for (int i = 0; i < history; ++i)
      {
        const Status loaded = s.load(paper, "grid.fold");
        if (!loaded)
        {
          std::fprintf(stderr, "memory_bench: load %d: %s\n", i, loaded.message().c_str());
          std::exit(1);
        }
      }
      return s;
    }();
    m.vertices = session.paper().vertices.size();
    m.paper_bytes = static_cast<double>(approximateBytes(session.paper()));
    m.history_bytes = static_cast<double>(session.historyBytes());
    m.kept = session.history().undo.size();
    m.forgotten = session.forgottenStates();
    m.resident = residentBytes();
    ::malloc_trim(0);
    m.trimmed = residentBytes();
    m.peak = peakBytes();
  }
  return m;
}

/// A paper read from a FOLD file through loadPaper.
Measured foldCase(const std::string& path)
{
  Measured m;
  m.kind = "fold_load";
  m.baseline = residentBytes();
  Expected<Paper> paper = loadPaper(path);
  if (!paper)
  {
    std::fprintf(stderr, "memory_bench: %s: %s\n", path.c_str(), paper.message().c_str());
    std::exit(1);
  }
  m.vertices = paper->vertices.size();
  m.paper_bytes = static_cast<double>(approximateBytes(*paper));
  m.resident = residentBytes();
  ::malloc_trim(0);
  m.trimmed = residentBytes();
  m.peak = peakBytes();
  return m;
}

/// Runs `body` in a child and returns what it wrote to the pipe.
template <class Body>
std::string inChild(const Body& body)
{
  int fds[2];
  if (::pipe(fds) != 0)
  {
    std::perror("memory_bench: pipe");
    std::exit(1);
  }
  std::fflush(stdout);
  const pid_t pid = ::fork();
  if (pid < 0)
  {
    std::perror("memory_bench: fork");
    std::exit(1);
  }
  if (pid == 0)
  {
    ::close(fds[0]);
    const std::string out = body();
    size_t done = 0;
    while (done < out.size())
    {
      const ssize_t n = ::write(fds[1], out.data() + done, out.size() - done);
      if (n <= 0)
        ::_exit(1);
      done += static_cast<size_t>(n);
    }
    ::_exit(0);
  }
  ::close(fds[1]);
  std::string out;
  char buffer[4096];
  for (ssize_t n; (n = ::read(fds[0], buffer, sizeof buffer)) > 0;)
    out.append(buffer, static_cast<size_t>(n));
  ::close(fds[0]);
  int status = 0;
  ::waitpid(pid, &status, 0);
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
  {
    std::fprintf(stderr, "memory_bench: a child failed\n");
    std::exit(1);
  }
  return out;
}
}  // namespace

int main(int argc, char** argv)
{
  if (argc < 2)
  {
    std::fprintf(stderr, "usage: memory_bench OUT_DIR [TEMP_PARENT]\n");
    return 2;
  }
  const std::string out_dir = argv[1];
  const std::filesystem::path parent = argc > 2 ? argv[2] : std::filesystem::current_path().string();
  std::string pattern = (parent / "memory_bench.XXXXXX").string();
  if (!::mkdtemp(pattern.data()))
  {
    std::perror("memory_bench: mkdtemp");
    return 1;
  }
  const std::filesystem::path dir = pattern;

  std::ofstream csv(out_dir + "/memory.csv");
  csv << "case,vertices,history,limit_mb,baseline_mb,rss_mb,rss_trimmed_mb,peak_mb,paper_approx_mb,"
         "history_approx_mb,undo_states_kept,forgotten,file_mb\n";
  const auto report = [&](const std::string& line) {
    csv << line;
    std::printf("%s", line.c_str());
  };
  for (const double limit : { 0.0, 256.0 })
    for (const int w : { 31, 99, 315 })
      for (const int history : { 0, 10, 50 })
        report(inChild([&] { return csvLine(sessionCase(w, history, limit)); }));

  // The FOLD file is written by a child too: the parent never holds a large heap to hand down.
  const std::string fold = (dir / "grid_100k.fold").string();
  inChild([&] {
    const Status written = writeTextFile(fold, formatFold(virtual_origami::bench::gridPaper(315, "memory_bench"), "memo"
                                                                                                                  "ry_"
                                                                                                                  "benc"
                                                                                                                  "h "
                                                                                                                  "gri"
                                                                                                                  "d"));
    if (!written)
    {
      std::fprintf(stderr, "memory_bench: %s\n", written.message().c_str());
      std::exit(1);
    }
    return std::string();
  });
  report(inChild([&] {
    Measured m = foldCase(fold);
    m.file_bytes = static_cast<double>(std::filesystem::file_size(fold));
    return csvLine(m);
  }));
  std::filesystem::remove_all(dir);
  std::printf("wrote %s/memory.csv\n", out_dir.c_str());
  return 0;
}

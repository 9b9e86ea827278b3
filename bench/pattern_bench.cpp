// Real crease patterns folded by assignment (make bench): every pattern under PATTERN_DIR (the
// example library of Origami Simulator, MIT, in bench/patterns/) loaded as `load` loads it,
// then folded as a new user would — commits at 25, 50, 75 and 100 %, and after a reload one call
// to 100 % — with paper_model's solvers (quasi_newton crease driver, newton rigid solver), one
// core. Each commit is kept whatever its figures so the steps go on, and the row says what the
// service would answer. A pattern runs in its own process, stopped when a call takes more than
// SECONDS of CPU (its row then says so). Writes one CSV row per call:
//   pattern_bench PATTERN_DIR OUT_CSV [SECONDS]
// PATTERN_DIR may also be one pattern file (its row named by the file's name).
#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "virtual_origami/core/assignment_fold.h"
#include "virtual_origami/core/model_file.h"
#include "virtual_origami/core/session.h"
#include "virtual_origami/solvers/crease_driver_factory.h"
#include "virtual_origami/solvers/solver_factory.h"

using namespace virtual_origami::core;
namespace fs = std::filesystem;

namespace
{
double cpuSeconds()
{
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

/// CPU seconds a child process has used (so that a call is stopped by its own CPU time, not by
/// the wall time a shared machine stretches).
double childCpuSeconds(pid_t child)
{
  clockid_t clock;
  timespec t{};
  if (clock_getcpuclockid(child, &clock) != 0 || clock_gettime(clock, &t) != 0)
    return 0.0;
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

/// Commas and line breaks out of a message, so that it stays one CSV field.
std::string field(std::string text)
{
  std::replace(text.begin(), text.end(), ',', ';');
  std::replace(text.begin(), text.end(), '\n', ' ');
  if (text.size() <= 160)
    return text;
  size_t cut = 160;
  while (cut > 0 && (static_cast<unsigned char>(text[cut]) & 0xC0) == 0x80)  // not inside a UTF-8 character
    --cut;
  return text.substr(0, cut);
}

/// Every vertex within 1e-6 of the sheet of the plane of face 0.
bool lyingFlat(const Paper& paper)
{
  if (paper.faces.empty())
    return true;
  const Vec3 n = paper.faceNormal(0);
  const Vec3 origin = paper.faceCentroid(0);
  for (const Vertex& v : paper.vertices)
    if (std::abs(n.dot(v.folded - origin)) > 1e-6 * paper.scale())
      return false;
  return true;
}

Session foldingSession()
{
  Session session;
  session.setSolver(makeSolver("newton"));
  session.setCreaseDrivers(makeCreaseDriver("quasi_newton"));
  return session;
}

Expected<Paper> loadPattern(const fs::path& path)
{
  const std::optional<ModelFormat> format = modelFormat(path.string());
  if (!format)
    return Expected<Paper>::failure("not a model file");
  std::ifstream file(path);
  std::stringstream text;
  text << file.rdbuf();
  const Status sized = checkModelSize(text.str(), *format, ModelLimits{});
  if (!sized)
    return Expected<Paper>::failure(sized.message());
  Expected<Paper> paper = parseModel(text.str(), *format, 1.0);
  if (paper)
  {
    const Status faces = checkFaceSizes(*paper, ModelLimits{});
    if (!faces)
      return Expected<Paper>::failure(faces.message());
  }
  return paper;
}

/// One call's row: the CPU seconds it took and the figures of what it committed.
std::string row(const std::string& head, const std::string& path_name, double seconds,
                const Expected<AssignmentFoldResult>& r, const Paper& paper)
{
  std::ostringstream out;
  out << head << ',' << path_name << ',' << seconds << ',';
  if (!r)
  {
    out << ",,,,,,,,failed: " << field(r.message());
    return out.str();
  }
  const std::string problems = assignmentFoldProblems(*r, AssignmentFoldAcceptance{});
  out << r->max_strain << ',' << r->angle_error << ',' << (r->rigid ? 1 : 0) << ',' << r->against_target << ','
      << r->crossings << ',' << r->ordered_pairs << ',' << (r->layer_problem.empty() ? 0 : 1) << ','
      << (lyingFlat(paper) ? 1 : 0) << ',' << (problems.empty() ? "success" : "refused: " + field(problems));
  return out.str();
}

/// Runs in the child: loads and folds one pattern, a line on `out` after each call.
void foldPattern(const fs::path& path, const std::string& name, FILE* out)
{
  const Expected<Paper> paper = loadPattern(path);
  Session probe = foldingSession();
  const Status loaded = paper ? probe.load(*paper, path.filename().string()) : failure(paper.message());
  if (!loaded)
  {
    std::fprintf(out, "%s,,,,load,0,,,,,,,,,refused at load: %s\n", name.c_str(), field(loaded.message()).c_str());
    std::fflush(out);
    return;
  }
  int driven = 0;
  for (double t : creaseTargets(probe.paper()))
    driven += std::isfinite(t) ? 1 : 0;
  std::ostringstream head;
  head << name << ',' << probe.paper().vertices.size() << ',' << probe.paper().faces.size() << ',' << driven;
  // For the parent: a call that times out after this is a fold's, on a pattern of this size.
  std::fprintf(out, "#loaded,%s\n", head.str().substr(name.size() + 1).c_str());
  std::fflush(out);
  AssignmentFoldAcceptance keep;
  keep.keep = true;
  for (double fraction : { 0.25, 0.5, 0.75, 1.0 })
  {
    const double start = cpuSeconds();
    const Expected<AssignmentFoldResult> r = probe.foldByAssignment(fraction, true, keep);
    const double seconds = cpuSeconds() - start;
    std::fprintf(
        out, "%s\n",
        row(head.str(), "step_" + std::to_string(static_cast<int>(100 * fraction)), seconds, r, probe.paper()).c_str());
    std::fflush(out);
  }
  Session once = foldingSession();
  if (!once.load(*paper, path.filename().string()))
    return;
  const double start = cpuSeconds();
  const Expected<AssignmentFoldResult> r = once.foldByAssignment(1.0, true, keep);
  std::fprintf(out, "%s\n", row(head.str(), "one_call_100", cpuSeconds() - start, r, once.paper()).c_str());
  std::fflush(out);
}

/// Forks a child for the pattern; copies its rows to `csv`, stopping it when a call takes more
/// than `seconds` of CPU (a call that long is the cliff the table shows).
void benchPattern(const fs::path& path, const std::string& name, double seconds, std::ostream& csv)
{
  int pipe_fds[2];
  if (pipe(pipe_fds) != 0)
    return;
  const pid_t child = fork();
  if (child == 0)
  {
    close(pipe_fds[0]);
    FILE* out = fdopen(pipe_fds[1], "w");
    foldPattern(path, name, out);
    std::fclose(out);
    _exit(0);
  }
  close(pipe_fds[1]);
  std::string buffer;
  int rows = 0;
  bool loaded = false;
  bool timed_out = false;
  std::string size = ",,";  // vertices, faces and driven creases, once loaded
  double cpu_at_row = 0.0;  // the child's CPU time at its last row
  char chunk[4096];
  while (true)
  {
    pollfd p{ pipe_fds[0], POLLIN, 0 };
    const int ready = poll(&p, 1, 100);
    if (ready == 0)
    {
      if (childCpuSeconds(child) - cpu_at_row > seconds)
      {
        timed_out = true;
        kill(child, SIGKILL);
        break;
      }
      continue;
    }
    const ssize_t n = read(pipe_fds[0], chunk, sizeof chunk);
    if (n <= 0)
      break;
    buffer.append(chunk, static_cast<size_t>(n));
    size_t line_end;
    while ((line_end = buffer.find('\n')) != std::string::npos)
    {
      const std::string line = buffer.substr(0, line_end + 1);
      buffer.erase(0, line_end + 1);
      if (line[0] == '#')
      {
        loaded = true;
        size = line.substr(std::string("#loaded,").size());
        size.pop_back();  // the line break
        cpu_at_row = childCpuSeconds(child);
        continue;
      }
      csv << line;
      std::cout << line;
      ++rows;
      cpu_at_row = childCpuSeconds(child);
    }
    csv.flush();
  }
  close(pipe_fds[0]);
  waitpid(child, nullptr, 0);
  if (timed_out)
  {
    const std::string names[] = { "step_25", "step_50", "step_75", "step_100", "one_call_100" };
    const std::string what = !loaded ? "load" : names[std::min(rows, 4)];
    csv << name << ',' << size << ',' << what << ',' << seconds << ",,,,,,,,,did not finish in " << seconds << " s\n";
    std::cout << name << ": did not finish " << what << " in " << seconds << " s" << std::endl;
  }
}
}  // namespace

int main(int argc, char** argv)
{
  if (argc < 3)
  {
    std::cerr << "usage: pattern_bench PATTERN_DIR OUT_CSV [SECONDS]\n";
    return 2;
  }
  const fs::path root = argv[1];
  const double seconds = argc > 3 ? std::atof(argv[3]) : 60.0;
  std::vector<fs::path> files;
  if (fs::is_regular_file(root))
    files.push_back(root);
  else
    for (const auto& entry : fs::recursive_directory_iterator(root))
      if (entry.is_regular_file() && modelFormat(entry.path().string()) && entry.path().filename() != "LICENSE")
      {
        const std::string ext = entry.path().extension().string();
        if (ext == ".svg" || ext == ".fold" || ext == ".cp" || ext == ".opx")
          files.push_back(entry.path());
      }
  std::sort(files.begin(), files.end());
  std::ofstream csv(argv[2]);
  csv << "pattern,vertices,faces,driven_creases,path,cpu_seconds,max_strain,angle_error,rigid,against_target,"
         "crossings,ordered_pairs,layer_problem,flat,answer\n";
  for (const fs::path& file : files)
    benchPattern(file, file == root ? file.filename().string() : fs::relative(file, root).string(), seconds, csv);
  return 0;
}

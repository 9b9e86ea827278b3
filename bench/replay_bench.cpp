// Replay speed: the operations a fold sequence records (the session's log, what the
// fold_sequence tool writes into its bag) applied again to a fresh session without
// animation, timed per operation, against the wall time of the recording: the bag's pace of
// one operation a second (a person folding with the mouse is slower: the seed's crane took
// about seven minutes).
//   replay_bench OUT.csv SEQUENCE.json [SEQUENCE.json ...]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

#include "virtual_origami/core/fold_sequence.h"
#include "virtual_origami/solvers/solver_factory.h"

using namespace virtual_origami::core;

namespace
{
constexpr double kRecordedSecondsPerOperation = 1.0;  // fold_sequence stamps its bags so

double median(std::vector<double> v)
{
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}
}  // namespace

int main(int argc, char** argv)
{
  if (argc < 3)
  {
    std::fprintf(stderr, "usage: replay_bench OUT.csv SEQUENCE.json [SEQUENCE.json ...]\n");
    return 2;
  }
  std::ofstream csv(argv[1]);
  csv << "model,operations,recorded_s,replay_ms,per_operation_us,slowest_operation_us,speedup\n";
  for (int a = 2; a < argc; ++a)
  {
    const std::string file = argv[a];
    std::ifstream in(file);
    std::stringstream text;
    text << in.rdbuf();
    const Expected<FoldSequence> sequence = parseFoldSequence(text.str());
    if (!sequence)
    {
      std::fprintf(stderr, "replay_bench: %s: %s\n", file.c_str(), sequence.message().c_str());
      return 1;
    }
    Session recorded_session;
    const Expected<std::vector<Paper>> states = foldSequence(*sequence, recorded_session, makeSolver(sequence->solver));
    if (!states)
    {
      std::fprintf(stderr, "replay_bench: %s: %s\n", file.c_str(), states.message().c_str());
      return 1;
    }
    const std::vector<Operation>& ops = recorded_session.log();
    const double recorded = kRecordedSecondsPerOperation * static_cast<double>(ops.size());

    // Repeat whole replays for at least a second (and 20 times), each operation timed alone.
    using Clock = std::chrono::steady_clock;
    std::vector<std::vector<double>> seconds(ops.size());
    double spent = 0.0;
    for (int rep = 0; rep < 20 || spent < 1.0; ++rep)
    {
      Session session;
      session.setSolver(std::shared_ptr<ShapeSolver>(makeSolver(sequence->solver)));
      for (size_t i = 0; i < ops.size(); ++i)
      {
        const auto t0 = Clock::now();
        const Status applied = session.apply(ops[i]);
        const double dt = std::chrono::duration<double>(Clock::now() - t0).count();
        if (!applied)
        {
          std::fprintf(stderr, "replay_bench: %s: operation %zu: %s\n", file.c_str(), i + 1, applied.message().c_str());
          return 1;
        }
        seconds[i].push_back(dt);
        spent += dt;
      }
      if (rep == 0)
      {
        // The replay must end where the recording did.
        const Paper& paper = session.paper();
        bool same = states->back().vertices.size() == paper.vertices.size();
        for (size_t v = 0; same && v < paper.vertices.size(); ++v)
          same = (states->back().vertices[v].folded - paper.vertices[v].folded).norm() < 1e-9;
        if (!same)
        {
          std::fprintf(stderr, "replay_bench: %s: the replay does not end in the recorded state\n", file.c_str());
          return 1;
        }
      }
    }
    double total = 0.0, slowest = 0.0;
    for (const auto& s : seconds)
    {
      total += median(s);
      slowest = std::max(slowest, median(s));
    }
    const std::string model = std::filesystem::path(file).stem().string();
    const double speedup = recorded / total;
    std::printf("%-10s %3zu operations: recorded %.1f s, replayed in %.3f ms (%.1f us per operation, slowest %.1f us): "
                "%.0fx faster\n",
                model.c_str(), ops.size(), recorded, total * 1e3, total / ops.size() * 1e6, slowest * 1e6, speedup);
    csv << model << ',' << ops.size() << ',' << recorded << ',' << total * 1e3 << ',' << total / ops.size() * 1e6 << ','
        << slowest * 1e6 << ',' << speedup << '\n';
  }
  return 0;
}

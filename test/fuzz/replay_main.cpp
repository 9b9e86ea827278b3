// A plain driver for a fuzz target's LLVMFuzzerTestOneInput, so `make test` runs the targets
// with g++ and no libFuzzer: it replays the committed corpus and crash regressions, then runs
// a bounded number of seeded mutations of them (a deterministic fuzz smoke run). A failing
// input is written to `replay-failure-<target>` in the working directory and named on stderr.
//
// Usage: <target>_replay [--mutations N] [--seed S] [--max-len BYTES] [--slow SECONDS] [--save M FILE] FILE_OR_DIR...
#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <string>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size);

namespace
{
using Bytes = std::vector<uint8_t>;

// What the signal handler reports: set before every input.
std::string g_failure_path;
const Bytes* g_current = nullptr;
char g_label[512] = "";

void writeAll(int fd, const void* data, size_t size)
{
  const char* p = static_cast<const char*>(data);
  while (size > 0)
  {
    const ssize_t n = ::write(fd, p, size);
    if (n <= 0)
      return;
    p += n;
    size -= static_cast<size_t>(n);
  }
}

extern "C" void onFatalSignal(int signal)
{
  const char* head = "\n==== replay: failed on ";
  writeAll(2, head, std::strlen(head));
  writeAll(2, g_label, std::strlen(g_label));
  if (g_current)
  {
    const int fd = ::open(g_failure_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (fd >= 0)
    {
      writeAll(fd, g_current->data(), g_current->size());
      ::close(fd);
      const char* saved = "\n     input saved as ";
      writeAll(2, saved, std::strlen(saved));
      writeAll(2, g_failure_path.c_str(), g_failure_path.size());
    }
  }
  writeAll(2, "\n", 1);
  std::signal(signal, SIG_DFL);
  std::raise(signal);
}

Bytes readFile(const std::filesystem::path& path)
{
  std::ifstream in(path, std::ios::binary);
  return Bytes(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

double g_slow = 0.0;  // --slow: inputs that take longer than this many seconds are named

void run(const Bytes& input, const std::string& label)
{
  std::snprintf(g_label, sizeof g_label, "%s", label.c_str());
  g_current = &input;
  const auto start = std::chrono::steady_clock::now();
  if (g_slow > 0)
    std::fprintf(stderr, "replay: %s ...\r", g_label);
  LLVMFuzzerTestOneInput(input.data(), input.size());
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (g_slow > 0 && seconds > g_slow)
    std::fprintf(stderr, "replay: %s took %.1f s\n", g_label, seconds);
  g_current = nullptr;
}

/// One of libFuzzer's simple mutations: flip a bit, set a byte, insert or erase bytes, copy a
/// run of bytes elsewhere, or splice in a piece of another input.
void mutate(Bytes& b, const std::vector<Bytes>& corpus, std::mt19937_64& rng, size_t max_len)
{
  auto pick = [&](size_t n) { return n == 0 ? size_t{ 0 } : static_cast<size_t>(rng() % n); };
  static const uint8_t interesting[] = { 0, 1, 0x7f, 0x80, 0xff, '0', '9', '-', '.', 'e', '[', ']', '{', '}', ',', '"' };
  switch (rng() % 7)
  {
    case 0:
      if (!b.empty())
        b[pick(b.size())] ^= static_cast<uint8_t>(1u << (rng() % 8));
      break;
    case 1:
      if (!b.empty())
        b[pick(b.size())] = static_cast<uint8_t>(rng());
      break;
    case 2:
      b.insert(b.begin() + static_cast<long>(pick(b.size() + 1)), interesting[pick(sizeof interesting)]);
      break;
    case 3:
      if (!b.empty())
      {
        const size_t at = pick(b.size());
        b.erase(b.begin() + static_cast<long>(at), b.begin() + static_cast<long>(std::min(b.size(), at + 1 + pick(8))));
      }
      break;
    case 4:
      if (!b.empty())
      {
        const size_t from = pick(b.size()), len = 1 + pick(std::min<size_t>(16, b.size() - from));
        const Bytes piece(b.begin() + static_cast<long>(from), b.begin() + static_cast<long>(from + len));
        b.insert(b.begin() + static_cast<long>(pick(b.size() + 1)), piece.begin(), piece.end());
      }
      break;
    case 5:
    {
      const Bytes& other = corpus[pick(corpus.size())];
      if (!other.empty())
      {
        const size_t from = pick(other.size()), len = 1 + pick(other.size() - from);
        const size_t at = pick(b.size() + 1);
        b.resize(at);
        b.insert(b.end(), other.begin() + static_cast<long>(from), other.begin() + static_cast<long>(from + len));
      }
      break;
    }
    default:
      if (!b.empty())
        b[pick(b.size())] = interesting[pick(sizeof interesting)];
  }
  if (b.size() > max_len)
    b.resize(max_len);
}
}  // namespace

int main(int argc, char** argv)
{
  long mutations = 0;
  long save_mutation = -1;
  std::string save_path;
  uint64_t seed = 1;
  size_t max_len = 4096;
  std::vector<std::filesystem::path> files;
  const std::string target = std::filesystem::path(argv[0]).filename().string();
  for (int i = 1; i < argc; ++i)
  {
    const std::string arg = argv[i];
    if (arg == "--mutations" && i + 1 < argc)
      mutations = std::atol(argv[++i]);
    else if (arg == "--seed" && i + 1 < argc)
      seed = std::strtoull(argv[++i], nullptr, 10);
    else if (arg == "--save" && i + 2 < argc)
    {
      save_mutation = std::atol(argv[++i]);
      save_path = argv[++i];
    }
    else if (arg == "--slow" && i + 1 < argc)
      g_slow = std::atof(argv[++i]);
    else if (arg == "--max-len" && i + 1 < argc)
      max_len = std::strtoull(argv[++i], nullptr, 10);
    else if (std::filesystem::is_directory(arg))
    {
      for (const auto& entry : std::filesystem::recursive_directory_iterator(arg))
        if (entry.is_regular_file() && entry.path().filename().string()[0] != '.' &&
            entry.path().extension() != ".md")
          files.push_back(entry.path());
    }
    else if (std::filesystem::is_regular_file(arg))
      files.emplace_back(arg);
    else
    {
      std::fprintf(stderr, "replay: no file or directory %s\n", arg.c_str());
      return 2;
    }
  }
  std::sort(files.begin(), files.end());
  g_failure_path = "replay-failure-" + target;
  for (int s : { SIGABRT, SIGSEGV, SIGFPE, SIGBUS, SIGILL })
    std::signal(s, onFatalSignal);

  std::vector<Bytes> corpus;
  for (const auto& file : files)
  {
    corpus.push_back(readFile(file));
    run(corpus.back(), file.string());
  }
  std::printf("replay: %zu inputs ran clean\n", corpus.size());
  if (corpus.empty())
    corpus.emplace_back();
  std::mt19937_64 rng(seed);
  for (long m = 0; m < mutations; ++m)
  {
    Bytes input = corpus[rng() % corpus.size()];
    const int rounds = 1 + static_cast<int>(rng() % 4);
    for (int r = 0; r < rounds; ++r)
      mutate(input, corpus, rng, max_len);
    if (m == save_mutation)  // to keep an input that hangs (a crash saves itself)
    {
      std::ofstream(save_path, std::ios::binary).write(reinterpret_cast<const char*>(input.data()),
                                                       static_cast<std::streamsize>(input.size()));
      std::printf("replay: mutation %ld written to %s\n", m, save_path.c_str());
      return 0;
    }
    run(input, "mutation " + std::to_string(m) + " of seed " + std::to_string(seed));
  }
  std::printf("replay: %ld seeded mutations (seed %llu) ran clean\n", mutations, static_cast<unsigned long long>(seed));
  return 0;
}

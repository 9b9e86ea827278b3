// Benchmark (not a test): crease and rotate latency at paper_model with clients contending.
// On a degree-4 vertex (crease x = 0.5, half creases from (0.5, 0.5) to (1, 0.8) and to
// (0, 0.9)), three phases, one after the other in the same launch:
//   rotate_alone  2 threads turning the face under (0.75, 0.97) back and forth about its
//                 automatic axis, the half crease to (1, 0.8) (every turn needs spring_solver,
//                 made slow by the launch)
//   crease_alone  2 threads creasing a corner of the sheet and undoing it (the baseline)
//   mixed         both pairs at once, 4 clients: the creasing ones go on, back to back,
//                 until the rotating ones have made their turns
//   mixed_paced   the same with a pause (1 s) between a creasing client's pairs: a person's pace
// Every call is timed from the client (ros::service::call round trip, persistent connection
// per thread); refusals are counted with their messages. Undo is the session's: a creasing
// client's undo may take back another client's latest change (it is part of the load).
// Writes <prefix>.csv (percentiles per phase and operation) and <prefix>_refusals.csv
// (refusals counted by message).
// Run by bench/contention_bench.launch (make bench).
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <map>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include <ros/ros.h>
#include <std_srvs/Trigger.h>
#include <virtual_origami/Crease.h>
#include <virtual_origami/PaperState.h>
#include <virtual_origami/Rotate.h>

namespace
{
using Clock = std::chrono::steady_clock;

struct Sample
{
  std::string phase, operation;
  int thread = 0;
  double start_s = 0, ms = 0;
  bool ok = false;
  std::string message;
};

double percentile(std::vector<double> v, double p)
{
  if (v.empty())
    return NAN;
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, static_cast<size_t>(p * (v.size() - 1) + 0.5))];
}

virtual_origami::Crease creaseRequest(double x0, double y0, double x1, double y1)
{
  virtual_origami::Crease c;
  c.request.start.x = x0;
  c.request.start.y = y0;
  c.request.end.x = x1;
  c.request.end.y = y1;
  return c;
}

/// A message fit for a CSV field.
std::string kindOf(const std::string& message)
{
  std::string out;
  for (char c : message)
    out += c == '"' ? '\'' : c;
  return out;
}

class Bench
{
public:
  Bench() : nh_("/origami"), start_(Clock::now())
  {
    state_sub_ =
        nh_.subscribe<virtual_origami::PaperState>("state", 10, [this](const virtual_origami::PaperState::ConstPtr& s) {
          std::lock_guard<std::mutex> lock(mutex_);
          state_ = s;
        });
  }

  ros::NodeHandle nh_;

  /// Timed call; the message is the service's answer (or why the call itself failed).
  template <class Service>
  void call(ros::ServiceClient& client, Service& srv, const std::string& phase, const std::string& operation,
            int thread, const std::function<std::string(const Service&, bool&)>& answer)
  {
    Sample s{ phase, operation, thread, seconds(), 0, false, "" };
    const Clock::time_point t0 = Clock::now();
    const bool called = client.call(srv);
    s.ms = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
    if (called)
      s.message = answer(srv, s.ok);
    else
      s.message = "the service call itself failed";
    std::lock_guard<std::mutex> lock(mutex_);
    samples_.push_back(s);
  }

  /// Crease a corner of the held face (below the half crease to (1, 0.8)) and undo it, `pairs` times.
  /// With `pairs` < 0, until `stop` is set; `pause` seconds between pairs.
  void creaser(const std::string& phase, int thread, int pairs, double pause = 0,
               const std::atomic<bool>* stop = nullptr)
  {
    ros::ServiceClient crease = nh_.serviceClient<virtual_origami::Crease>("crease", true);
    ros::ServiceClient undo = nh_.serviceClient<std_srvs::Trigger>("undo", true);
    const std::function<std::string(const virtual_origami::Crease&, bool&)> crease_answer =
        [](const virtual_origami::Crease& c, bool& ok) {
          ok = c.response.success;
          return c.response.message;
        };
    const std::function<std::string(const std_srvs::Trigger&, bool&)> undo_answer = [](const std_srvs::Trigger& t,
                                                                                       bool& ok) {
      ok = t.response.success;
      return t.response.message;
    };
    for (int i = 0; (pairs < 0 ? !stop->load() : i < pairs) && ros::ok(); ++i)
    {
      if (pause > 0 && i > 0)
        std::this_thread::sleep_for(std::chrono::duration<double>(pause));
      // Lines y = x - c across the corner (1, 0), a new one every call (c by the golden ratio's
      // sequence, each thread its own): a crease an undo missed (the undo took back another
      // client's change, a rotation say) stays, and a line repeated on it would be refused
      // at once ("nothing new to crease") instead of measured. Those misses are bounded by the
      // other clients' changes.
      const double golden = 0.6180339887498949;
      const double c = 0.62 + 0.3 * std::fmod((2 * i + thread + 1) * golden, 1.0);
      auto request = creaseRequest(c - 0.1, -0.1, 1.1, 1.1 - c);
      call(crease, request, phase, "crease", thread, crease_answer);
      if (!request.response.success)
        continue;
      std_srvs::Trigger t;
      call(undo, t, phase, "undo", thread, undo_answer);
    }
  }

  /// Turns the face by ±angle about its axis (both found by setUp), `count` times, towards the
  /// other side of half the angle (read from the latest state), so the model swings about a
  /// small fold. Every turn needs the solver: the axis is a half crease.
  void rotator(const std::string& phase, int thread, int count, double angle)
  {
    ros::ServiceClient rotate = nh_.serviceClient<virtual_origami::Rotate>("rotate", true);
    const std::function<std::string(const virtual_origami::Rotate&, bool&)> answer =
        [](const virtual_origami::Rotate& r, bool& ok) {
          ok = r.response.success;
          return r.response.message;
        };
    for (int i = 0; i < count && ros::ok(); ++i)
    {
      double fold = 0;
      {
        std::lock_guard<std::mutex> lock(mutex_);
        if (state_ && axis_ < static_cast<int>(state_->edges.size()))
          fold = state_->edges[axis_].fold_angle;
      }
      virtual_origami::Rotate r;
      r.request.face = face_;
      r.request.axis_edge = axis_;
      r.request.angle = fold > 0.5 * angle ? -angle : angle;
      r.request.commit = true;
      call(rotate, r, phase, "rotate", thread, answer);
    }
  }

  int face_ = -1, axis_ = -1;  // what the rotating clients turn, and about which crease

  /// Runs the given threads to the end and returns the wall time they took.
  double phase(std::vector<std::thread> threads)
  {
    const double t0 = seconds();
    for (std::thread& t : threads)
      t.join();
    return seconds() - t0;
  }

  double seconds() const
  {
    return std::chrono::duration<double>(Clock::now() - start_).count();
  }
  std::vector<Sample> samples() const
  {
    std::lock_guard<std::mutex> lock(mutex_);
    return samples_;
  }
  size_t vertices() const
  {
    std::lock_guard<std::mutex> lock(mutex_);
    return state_ ? state_->vertices_folded.size() : 0;
  }

private:
  Clock::time_point start_;
  ros::Subscriber state_sub_;
  mutable std::mutex mutex_;
  virtual_origami::PaperState::ConstPtr state_;
  std::vector<Sample> samples_;
};

bool setUp(Bench& bench)
{
  for (const char* s : { "crease", "rotate", "undo", "reset" })
    if (!ros::service::waitForService(bench.nh_.resolveName(s), ros::Duration(30)))
    {
      std::fprintf(stderr, "contention_bench: no %s service\n", s);
      return false;
    }
  std_srvs::Trigger reset;
  ros::service::call(bench.nh_.resolveName("reset"), reset);
  for (auto c :
       { creaseRequest(0.5, -0.1, 0.5, 1.1), creaseRequest(0.5, 0.5, 1.0, 0.8), creaseRequest(0.5, 0.5, 0.0, 0.9) })
  {
    if (!ros::service::call(bench.nh_.resolveName("crease"), c) || !c.response.success)
    {
      std::fprintf(stderr, "contention_bench: setting up the degree-4 vertex: %s\n", c.response.message.c_str());
      return false;
    }
  }
  // The face under (0.75, 0.97), with the automatic axis: the half crease to (1, 0.8), so the
  // face across it (below, where the creasing clients work) is held and the solver moves the
  // left half. (Under (0.9, 0.9) the automatic axis is the full crease x = 0.5, about which
  // the right half turns rigidly, without a solve.) Turned once and back, untimed.
  virtual_origami::Rotate r;
  r.request.face = -1;
  r.request.axis_edge = -1;
  r.request.click.x = 0.75;
  r.request.click.y = 0.97;
  r.request.angle = 0.3;
  r.request.commit = true;
  if (!ros::service::call(bench.nh_.resolveName("rotate"), r) || !r.response.success)
  {
    std::fprintf(stderr, "contention_bench: the first turn: %s\n", r.response.message.c_str());
    return false;
  }
  bench.face_ = r.response.face;
  bench.axis_ = r.response.axis_edge;
  r.request.face = bench.face_;
  r.request.axis_edge = bench.axis_;
  r.request.angle = -0.3;
  if (!ros::service::call(bench.nh_.resolveName("rotate"), r) || !r.response.success)
  {
    std::fprintf(stderr, "contention_bench: turning back: %s\n", r.response.message.c_str());
    return false;
  }
  return true;
}
}  // namespace

int main(int argc, char** argv)
{
  ros::init(argc, argv, "contention_bench");
  ros::NodeHandle pnh("~");
  const std::string prefix = pnh.param<std::string>("csv_prefix", "docs/bench/contention");
  const int pairs = pnh.param("crease_pairs", 1000);   // crease + undo, per creasing thread
  const int rotations = pnh.param("rotations", 10);    // per rotating thread (mixed phases)
  const double paced = pnh.param("paced_pause", 1.0);  // seconds between a creasing client's pairs
  const int alone = pnh.param("rotations_alone", 10);  // per rotating thread (rotate_alone)
  const double angle = pnh.param("angle", 0.3);
  ros::AsyncSpinner spinner(1);
  spinner.start();
  Bench bench;
  if (!setUp(bench))
    return 1;
  ros::WallDuration(0.5).sleep();

  std::map<std::string, double> wall;
  {
    std::vector<std::thread> t;
    t.emplace_back([&] { bench.rotator("rotate_alone", 2, alone, angle); });
    t.emplace_back([&] { bench.rotator("rotate_alone", 3, alone, angle); });
    wall["rotate_alone"] = bench.phase(std::move(t));
  }
  {
    std::vector<std::thread> t;
    t.emplace_back([&] { bench.creaser("crease_alone", 0, pairs); });
    t.emplace_back([&] { bench.creaser("crease_alone", 1, pairs); });
    wall["crease_alone"] = bench.phase(std::move(t));
  }
  // All four at once: the creasing clients go on until the rotating clients are done, so
  // that every turn is made while creases commit; back to back, then at a person's pace.
  for (const auto& [phase, pause] :
       { std::make_pair(std::string("mixed"), 0.0), std::make_pair(std::string("mixed_paced"), paced) })
  {
    std::atomic<bool> stop{ false };
    const double t0 = bench.seconds();
    std::thread c0([&, phase = phase, pause = pause] { bench.creaser(phase, 0, -1, pause, &stop); });
    std::thread c1([&, phase = phase, pause = pause] { bench.creaser(phase, 1, -1, pause, &stop); });
    std::thread r2([&, phase = phase] { bench.rotator(phase, 2, rotations, angle); });
    std::thread r3([&, phase = phase] { bench.rotator(phase, 3, rotations, angle); });
    r2.join();
    r3.join();
    stop = true;
    c0.join();
    c1.join();
    wall[phase] = bench.seconds() - t0;
  }

  const std::vector<Sample> samples = bench.samples();
  std::ofstream out(prefix + ".csv");
  out << "phase,operation,calls,succeeded,refused,p50_ms,p95_ms,p99_ms,max_ms,first_s,last_s,phase_wall_s,vertices\n";
  std::ofstream refusals(prefix + "_refusals.csv");
  refusals << "phase,operation,count,message\n";
  std::printf("contention at paper_model (%zu vertices at the end)\n", bench.vertices());
  for (const std::string phase : { "rotate_alone", "crease_alone", "mixed", "mixed_paced" })
    for (const std::string operation : { "crease", "undo", "rotate" })
    {
      std::vector<double> all;
      size_t ok = 0;
      double first = INFINITY, last = 0;
      std::map<std::string, int> why;
      for (const Sample& s : samples)
        if (s.phase == phase && s.operation == operation)
        {
          all.push_back(s.ms);
          ok += s.ok;
          first = std::min(first, s.start_s);
          last = std::max(last, s.start_s + s.ms / 1e3);
          if (!s.ok)
            ++why[kindOf(s.message)];
        }
      if (all.empty())
        continue;
      out << phase << ',' << operation << ',' << all.size() << ',' << ok << ',' << all.size() - ok << ','
          << percentile(all, 0.5) << ',' << percentile(all, 0.95) << ',' << percentile(all, 0.99) << ','
          << percentile(all, 1.0) << ',' << first << ',' << last << ',' << wall[phase] << ',' << bench.vertices()
          << '\n';
      std::printf("  %-12s %-6s %4zu calls, %4zu refused: p50 %8.2f ms  p95 %8.2f ms  p99 %8.2f ms  max %8.2f ms\n",
                  phase.c_str(), operation.c_str(), all.size(), all.size() - ok, percentile(all, 0.5),
                  percentile(all, 0.95), percentile(all, 0.99), percentile(all, 1.0));
      for (const auto& [message, count] : why)
      {
        refusals << phase << ',' << operation << ',' << count << ",\"" << message << "\"\n";
        std::printf("      %4d × %s\n", count, message.c_str());
      }
    }
  std::printf("wrote %s.csv and %s_refusals.csv\n", prefix.c_str(), prefix.c_str());
  return 0;
}

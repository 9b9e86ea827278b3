// Benchmark (not a test): from a service call to the markers that show its result, on a
// crease pattern of crane scale (100–200 vertices). Writes a CSV and prints p50/p99.
// Run by bench/service_latency.launch (make bench).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include <ros/callback_queue.h>
#include <ros/ros.h>
#include <std_srvs/Trigger.h>
#include <virtual_origami/Crease.h>
#include <virtual_origami/PaperState.h>
#include <virtual_origami/Rotate.h>
#include <visualization_msgs/MarkerArray.h>

namespace
{
using Clock = std::chrono::steady_clock;

struct Probe
{
  ros::NodeHandle nh{ "/origami" };
  ros::Subscriber markers_sub;
  Clock::time_point last_markers;
  int markers_seen = 0;
  size_t vertices = 0;
  ros::Subscriber state_sub;

  Probe()
  {
    markers_sub = nh.subscribe<visualization_msgs::MarkerArray>(
        "markers", 100, [this](const visualization_msgs::MarkerArray::ConstPtr&) {
          last_markers = Clock::now();
          ++markers_seen;
        },
        ros::VoidConstPtr(), ros::TransportHints().tcpNoDelay());
    state_sub = nh.subscribe<virtual_origami::PaperState>(
        "state", 10, [this](const virtual_origami::PaperState::ConstPtr& s) { vertices = s->vertices_folded.size(); },
        ros::VoidConstPtr(), ros::TransportHints().tcpNoDelay());
  }

  /// Milliseconds from the call's start to the markers published after it.
  template <class Service>
  double timed(const std::string& name, Service& srv)
  {
    const int before = markers_seen;
    const Clock::time_point start = Clock::now();
    if (!ros::service::call(nh.resolveName(name), srv))
      return -1;
    while (ros::ok() && markers_seen == before)
      ros::getGlobalCallbackQueue()->callAvailable(ros::WallDuration(0.001));
    return std::chrono::duration<double, std::milli>(last_markers - start).count();
  }
};

double percentile(std::vector<double> v, double p)
{
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
}  // namespace

int main(int argc, char** argv)
{
  ros::init(argc, argv, "service_latency");
  ros::NodeHandle private_nh("~");
  const std::string csv = private_nh.param<std::string>("csv", "docs/bench/service_latency.csv");
  const int repeats = private_nh.param("repeats", 200);
  // The probe subscribes with TCP_NODELAY: without it Nagle's algorithm holds the tail of a
  // markers message that follows the state message back for a delayed ACK (~40 ms).
  Probe probe;
  for (const char* s : { "crease", "rotate", "undo", "reset" })
    ros::service::waitForService(probe.nh.resolveName(s));
  ros::WallDuration(1.0).sleep();
  std_srvs::Trigger reset;
  ros::service::call(probe.nh.resolveName("reset"), reset);

  // A crane-scale pattern: a 10 × 10 grid of creases and both diagonals.
  for (int k = 1; k < 10; ++k)
  {
    auto vertical = creaseRequest(k / 10.0, -0.1, k / 10.0, 1.1);
    auto horizontal = creaseRequest(-0.1, k / 10.0, 1.1, k / 10.0);
    ros::service::call(probe.nh.resolveName("crease"), vertical);
    ros::service::call(probe.nh.resolveName("crease"), horizontal);
  }
  auto diagonal = creaseRequest(-0.1, -0.1, 1.1, 1.1);
  auto anti = creaseRequest(1.1, -0.1, -0.1, 1.1);
  ros::service::call(probe.nh.resolveName("crease"), diagonal);
  ros::service::call(probe.nh.resolveName("crease"), anti);
  while (ros::ok() && probe.vertices == 0)
    ros::spinOnce();
  ros::WallDuration(0.5).sleep();
  ros::spinOnce();

  std::map<std::string, std::vector<double>> samples;
  for (int i = 0; i < repeats && ros::ok(); ++i)
  {
    // A drag preview: the top row turns about y = 0.9 (not committed).
    virtual_origami::Rotate preview;
    preview.request.face = -1;
    preview.request.axis_edge = -1;
    preview.request.click.x = 0.55;
    preview.request.click.y = 0.97;
    preview.request.angle = 0.01 * (i % 100);
    preview.request.commit = false;
    samples["rotate_preview"].push_back(probe.timed("rotate", preview));
    // A committed fold of that row, then undone.
    virtual_origami::Rotate fold = preview;
    fold.request.angle = 1.0;
    fold.request.commit = true;
    samples["rotate_commit"].push_back(probe.timed("rotate", fold));
    std_srvs::Trigger undo;
    samples["undo"].push_back(probe.timed("undo", undo));
    // A new crease through the grid, then undone.
    auto crease = creaseRequest(-0.1, 0.05 + 0.9 * (i % 10) / 10.0 + 0.01, 1.1, 0.05 + 0.9 * (i % 10) / 10.0 + 0.03);
    samples["crease"].push_back(probe.timed("crease", crease));
    std_srvs::Trigger undo_crease;
    ros::service::call(probe.nh.resolveName("undo"), undo_crease);
  }

  std::ofstream out(csv);
  out << "operation,samples,vertices,p50_ms,p99_ms,max_ms\n";
  std::printf("service call -> markers published, %zu vertices, %d repeats\n", probe.vertices, repeats);
  for (const auto& [op, v] : samples)
  {
    std::vector<double> ok;
    for (double x : v)
      if (x >= 0)
        ok.push_back(x);
    if (ok.empty())
      continue;
    const double p50 = percentile(ok, 0.5), p99 = percentile(ok, 0.99), worst = percentile(ok, 1.0);
    out << op << ',' << ok.size() << ',' << probe.vertices << ',' << p50 << ',' << p99 << ',' << worst << '\n';
    std::printf("  %-15s p50 %7.3f ms   p99 %7.3f ms   max %7.3f ms\n", op.c_str(), p50, p99, worst);
  }
  std::printf("wrote %s\n", csv.c_str());
  return 0;
}

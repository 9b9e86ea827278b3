// Benchmark (not a test): a flood of mouse feedback at the interaction node. During one
// rotate drag, 500 pose updates a second for 10 s (far more than rviz sends) sweep the half
// of a creased sheet between 0° and 180°. Measures how far behind the pose the node applies
// is (lag), how many events wait in its queue, how long each update takes (the rotate
// preview call included), and whether paper_model stays responsive (a `save` call every
// 0.25 s). Writes a CSV of the samples and prints a summary. Run by bench/interaction_flood.launch.
#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <mutex>
#include <thread>
#include <vector>

#include <ros/ros.h>
#include <std_srvs/Trigger.h>
#include <virtual_origami/Crease.h>
#include <virtual_origami/InteractionStatus.h>
#include <virtual_origami/PaperState.h>
#include <virtual_origami/Save.h>
#include <visualization_msgs/InteractiveMarkerInit.h>
#include <visualization_msgs/MarkerArray.h>

#include "virtual_origami/ros/mouse_feedback.h"

namespace
{
using virtual_origami::InteractionStatus;

struct Sample
{
  double t = 0, lag_ms = 0, apply_ms = 0;
  uint32_t pending = 0;
};

double percentile(std::vector<double> v, double p)
{
  if (v.empty())
    return NAN;
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, static_cast<size_t>(p * (v.size() - 1) + 0.5))];
}

bool waitFor(const std::function<bool()>& done, double seconds)
{
  const ros::WallTime until = ros::WallTime::now() + ros::WallDuration(seconds);
  while (ros::ok() && ros::WallTime::now() < until && !done())
    ros::WallDuration(0.01).sleep();
  return done();
}
}  // namespace

int main(int argc, char** argv)
{
  ros::init(argc, argv, "interaction_flood");
  ros::NodeHandle nh("/origami"), pnh("~");
  const double rate = pnh.param("rate", 500.0), seconds = pnh.param("seconds", 10.0);
  const std::string csv = pnh.param<std::string>("csv", "interaction_flood.csv");

  std::mutex mutex;
  InteractionStatus status;
  bool have_status = false;
  std::vector<Sample> samples;
  std::atomic<int> previews{ 0 };
  ros::Time flood_start;
  visualization_msgs::InteractiveMarkerInit init;
  virtual_origami::PaperState state;

  auto status_sub =
      nh.subscribe<InteractionStatus>("interaction_status", 1000, [&](const InteractionStatus::ConstPtr& s) {
        std::lock_guard<std::mutex> lock(mutex);
        status = *s;
        have_status = true;
        if (!flood_start.isZero() && s->dragging && !s->applied_stamp.isZero() && s->applied_stamp >= flood_start)
          samples.push_back({ (ros::Time::now() - flood_start).toSec(),
                              (ros::Time::now() - s->applied_stamp).toSec() * 1e3, s->apply_seconds * 1e3,
                              s->pending });
      });
  auto init_sub = nh.subscribe<visualization_msgs::InteractiveMarkerInit>(
      "interaction/update_full", 10, [&](const visualization_msgs::InteractiveMarkerInit::ConstPtr& m) {
        std::lock_guard<std::mutex> lock(mutex);
        init = *m;
      });
  auto state_sub =
      nh.subscribe<virtual_origami::PaperState>("state", 10, [&](const virtual_origami::PaperState::ConstPtr& s) {
        std::lock_guard<std::mutex> lock(mutex);
        state = *s;
      });
  auto markers_sub = nh.subscribe<visualization_msgs::MarkerArray>(
      "markers", 1000, [&](const visualization_msgs::MarkerArray::ConstPtr&) { ++previews; });
  ros::Publisher feedback = nh.advertise<visualization_msgs::InteractiveMarkerFeedback>("interaction/feedback", 1000);
  ros::AsyncSpinner spinner(1);
  spinner.start();

  // A creased sheet in rotate mode.
  const auto locked = [&](const std::function<bool()>& f) {
    return [&, f] {
      std::lock_guard<std::mutex> lock(mutex);
      return f();
    };
  };
  ros::service::waitForService(nh.resolveName("reset"), ros::Duration(30));
  std_srvs::Trigger reset;
  ros::service::call(nh.resolveName("reset"), reset);
  virtual_origami::Crease crease;
  crease.request.end.x = crease.request.end.y = 1.0;
  if (!ros::service::call(nh.resolveName("crease"), crease) || !crease.response.success)
  {
    ROS_FATAL("interaction_flood: could not crease the sheet");
    return 1;
  }
  const uint64_t revision = crease.response.revision;
  int rotate_entry = -1;
  double lift = 0;
  if (!waitFor(locked([&] {
                 for (const auto& m : init.markers)
                   for (const auto& e : m.menu_entries)
                     if (e.title.find("Rotate mode") != std::string::npos)
                       rotate_entry = static_cast<int>(e.id);
                 if (!init.markers.empty() && !init.markers[0].controls.empty())
                   lift = init.markers[0].controls[0].markers[0].points[0].z;
                 return rotate_entry >= 0 && have_status && status.revision == revision;
               }),
               30) ||
      !waitFor([&] { return feedback.getNumSubscribers() > 0; }, 30))
  {
    ROS_FATAL("interaction_flood: no interaction node");
    return 1;
  }
  virtual_origami::MouseGesture gesture;
  gesture.client_id = "/interaction_flood";
  gesture.lift = lift;
  gesture.press = virtual_origami::core::Vec3(0.8, 0.3, 0.0);
  feedback.publish(gesture.menu(rotate_entry, gesture.press, ros::Time::now()));
  waitFor(locked([&] { return status.mode == "rotate"; }), 10);
  feedback.publish(gesture.down(ros::Time::now()));
  waitFor(locked([&] { return status.dragging; }), 10);
  const int previews_before = previews;
  uint64_t received_before, coalesced_before, applied_before;
  {
    std::lock_guard<std::mutex> lock(mutex);
    received_before = status.feedback_received;
    coalesced_before = status.feedback_coalesced;
    applied_before = status.updates_applied;
  }

  // paper_model's responsiveness during the flood: a save every 0.25 s, timed.
  std::vector<double> save_ms;
  std::atomic<bool> flooding{ true };
  std::thread probe([&] {
    while (flooding && ros::ok())
    {
      virtual_origami::Save save;
      save.request.path = "/tmp/interaction_flood_probe.fold";
      const ros::WallTime t0 = ros::WallTime::now();
      ros::service::call(nh.resolveName("save"), save);
      save_ms.push_back((ros::WallTime::now() - t0).toSec() * 1e3);
      ros::WallDuration(0.25).sleep();
    }
  });

  // The flood: the pointer sweeps from the press point over the crease to its mirror image
  // and back, once every 2 s.
  {
    std::lock_guard<std::mutex> lock(mutex);
    flood_start = ros::Time::now();
  }
  const virtual_origami::core::Vec3 mirror(0.3, 0.8, 0.0);
  ros::Rate loop(rate);
  int sent = 0;
  ros::Time last_stamp;
  const ros::WallTime start = ros::WallTime::now();
  while (ros::ok() && (ros::WallTime::now() - start).toSec() < seconds)
  {
    const double t = (ros::WallTime::now() - start).toSec();
    const double s = 0.5 - 0.5 * std::cos(M_PI * t);  // 0 → 1 → 0 every 2 s
    last_stamp = ros::Time::now();
    feedback.publish(gesture.moveTo(gesture.press + s * (mirror - gesture.press), last_stamp));
    ++sent;
    loop.sleep();
  }
  const double flood_seconds = (ros::WallTime::now() - start).toSec();
  flooding = false;
  probe.join();

  // After the flood: how soon the node shows the last pose, then a release commits it.
  const ros::WallTime after = ros::WallTime::now();
  waitFor(locked([&] { return status.applied_stamp == last_stamp; }), 10);
  const double catch_up_ms = (ros::WallTime::now() - after).toSec() * 1e3;
  InteractionStatus end;
  {
    std::lock_guard<std::mutex> lock(mutex);
    end = status;
  }
  const ros::WallTime release = ros::WallTime::now();
  feedback.publish(gesture.upAt(gesture.press, ros::Time::now()));  // back where it started: no turn
  waitFor(locked([&] { return !status.dragging; }), 10);
  const double release_ms = (ros::WallTime::now() - release).toSec() * 1e3;

  std::vector<double> lag, apply;
  uint32_t max_pending = 0;
  {
    std::lock_guard<std::mutex> lock(mutex);
    std::ofstream out(csv);
    out << "t_s,lag_ms,apply_ms,pending\n";
    for (const Sample& s : samples)
    {
      out << s.t << ',' << s.lag_ms << ',' << s.apply_ms << ',' << s.pending << '\n';
      lag.push_back(s.lag_ms);
      apply.push_back(s.apply_ms);
      max_pending = std::max(max_pending, s.pending);
    }
  }
  const uint64_t received = end.feedback_received - received_before;
  const uint64_t coalesced = end.feedback_coalesced - coalesced_before;
  const uint64_t applied = end.updates_applied - applied_before;
  std::printf("interaction_flood: %d pose updates sent in %.2f s (%.0f/s)\n", sent, flood_seconds,
              sent / flood_seconds);
  std::printf("  received by the node   %lu (%lu coalesced away, %lu applied: %.1f updates/s)\n",
              static_cast<unsigned long>(received), static_cast<unsigned long>(coalesced),
              static_cast<unsigned long>(applied), applied / flood_seconds);
  std::printf("  rotate previews drawn  %d (%.1f/s)\n", previews - previews_before,
              (previews - previews_before) / flood_seconds);
  std::printf("  lag of the applied pose  p50 %.1f ms, p95 %.1f ms, max %.1f ms (%zu samples)\n", percentile(lag, 0.5),
              percentile(lag, 0.95), lag.empty() ? NAN : *std::max_element(lag.begin(), lag.end()), lag.size());
  std::printf("  one update (preview call included)  p50 %.1f ms, p95 %.1f ms\n", percentile(apply, 0.5),
              percentile(apply, 0.95));
  std::printf("  events waiting in the node's queue  max %u\n", max_pending);
  std::printf("  paper_model `save` during the flood  p50 %.1f ms, max %.1f ms (%zu calls)\n", percentile(save_ms, 0.5),
              save_ms.empty() ? NAN : *std::max_element(save_ms.begin(), save_ms.end()), save_ms.size());
  std::printf("  after the flood: last pose applied within %.0f ms, release handled within %.0f ms\n", catch_up_ms,
              release_ms);
  std::printf("  samples in %s\n", csv.c_str());
  return 0;
}

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
#include "virtual_origami/ros/service_call.h"

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

/// The flood at the interaction node, in the order it runs: a creased sheet, a press in rotate
/// mode, the flood (with paper_model probed beside it), the release, the report. What the node
/// reports arrives on the spinner's thread and is kept under one mutex.
class InteractionFlood
{
public:
  InteractionFlood(ros::NodeHandle& nh, ros::NodeHandle& pnh)
    : nh_(nh)
    , rate_(pnh.param("rate", 500.0))
    , seconds_(pnh.param("seconds", 10.0))
    , csv_(pnh.param<std::string>("csv", "interaction_flood.csv"))
  {
    status_sub_ =
        nh_.subscribe<InteractionStatus>("interaction_status", 1000, [this](const InteractionStatus::ConstPtr& s) {
          std::lock_guard<std::mutex> lock(mutex_);
          status_ = *s;
          have_status_ = true;
          if (!flood_start_.isZero() && s->dragging && !s->applied_stamp.isZero() && s->applied_stamp >= flood_start_)
            samples_.push_back({ (ros::Time::now() - flood_start_).toSec(),
                                 (ros::Time::now() - s->applied_stamp).toSec() * 1e3, s->apply_seconds * 1e3,
                                 s->pending });
        });
    init_sub_ = nh_.subscribe<visualization_msgs::InteractiveMarkerInit>(
        "interaction/update_full", 10, [this](const visualization_msgs::InteractiveMarkerInit::ConstPtr& m) {
          std::lock_guard<std::mutex> lock(mutex_);
          init_ = *m;
        });
    state_sub_ =
        nh_.subscribe<virtual_origami::PaperState>("state", 10, [this](const virtual_origami::PaperState::ConstPtr& s) {
          std::lock_guard<std::mutex> lock(mutex_);
          state_ = *s;
        });
    markers_sub_ = nh_.subscribe<visualization_msgs::MarkerArray>(
        "markers", 1000, [this](const visualization_msgs::MarkerArray::ConstPtr&) { ++previews_; });
    feedback_ = nh_.advertise<visualization_msgs::InteractiveMarkerFeedback>("interaction/feedback", 1000);
    spinner_.start();
  }

  /// A creased sheet, and the interaction's menu offering rotate mode. False (said) if not.
  bool creaseSheet()
  {
    ros::service::waitForService(nh_.resolveName("reset"), ros::Duration(30));
    std_srvs::Trigger reset;
    virtual_origami::callService(nh_.resolveName("reset"), reset);
    virtual_origami::Crease crease;
    crease.request.end.x = crease.request.end.y = 1.0;
    if (!virtual_origami::callService(nh_.resolveName("crease"), crease) || !crease.response.success)
    {
      ROS_FATAL("interaction_flood: could not crease the sheet");
      return false;
    }
    const uint64_t revision = crease.response.revision;
    double lift = 0;
    if (!waitLocked(
            [&] {
              for (const auto& m : init_.markers)
                for (const auto& e : m.menu_entries)
                  if (e.title.find("Rotate mode") != std::string::npos)
                    rotate_entry_ = static_cast<int>(e.id);
              if (!init_.markers.empty() && !init_.markers[0].controls.empty())
                lift = init_.markers[0].controls[0].markers[0].points[0].z;
              return rotate_entry_ >= 0 && have_status_ && status_.revision == revision;
            },
            30) ||
        !waitFor([&] { return feedback_.getNumSubscribers() > 0; }, 30))
    {
      ROS_FATAL("interaction_flood: no interaction node");
      return false;
    }
    gesture_.client_id = "/interaction_flood";
    gesture_.lift = lift;
    gesture_.press = virtual_origami::core::Vec3(0.8, 0.3, 0.0);
    return true;
  }

  /// Rotate mode, a press, and the node's counters before the flood.
  void pressInRotateMode()
  {
    feedback_.publish(gesture_.menu(rotate_entry_, gesture_.press, ros::Time::now()));
    waitLocked([&] { return status_.mode == "rotate"; }, 10);
    feedback_.publish(gesture_.down(ros::Time::now()));
    waitLocked([&] { return status_.dragging; }, 10);
    previews_before_ = previews_;
    std::lock_guard<std::mutex> lock(mutex_);
    received_before_ = status_.feedback_received;
    coalesced_before_ = status_.feedback_coalesced;
    applied_before_ = status_.updates_applied;
  }

  /// The flood: the pointer sweeps from the press point over the crease to its mirror image and
  /// back, once every 2 s; paper_model's responsiveness probed meanwhile by a save every 0.25 s, timed.
  void flood()
  {
    std::atomic<bool> flooding{ true };
    std::thread probe([&] {
      while (flooding && ros::ok())
      {
        virtual_origami::Save save;
        save.request.path = "/tmp/interaction_flood_probe.fold";
        const ros::WallTime t0 = ros::WallTime::now();
        virtual_origami::callService(nh_.resolveName("save"), save);
        save_ms_.push_back((ros::WallTime::now() - t0).toSec() * 1e3);
        ros::WallDuration(0.25).sleep();
      }
    });
    {
      std::lock_guard<std::mutex> lock(mutex_);
      flood_start_ = ros::Time::now();
    }
    const virtual_origami::core::Vec3 mirror(0.3, 0.8, 0.0);
    ros::Rate loop(rate_);
    const ros::WallTime start = ros::WallTime::now();
    while (ros::ok() && (ros::WallTime::now() - start).toSec() < seconds_)
    {
      const double t = (ros::WallTime::now() - start).toSec();
      const double s = 0.5 - 0.5 * std::cos(M_PI * t);  // 0 → 1 → 0 every 2 s
      last_stamp_ = ros::Time::now();
      feedback_.publish(gesture_.moveTo(gesture_.press + s * (mirror - gesture_.press), last_stamp_));
      ++sent_;
      loop.sleep();
    }
    flood_seconds_ = (ros::WallTime::now() - start).toSec();
    flooding = false;
    probe.join();
  }

  /// After the flood: how soon the node shows the last pose, then a release commits it.
  void release()
  {
    const ros::WallTime after = ros::WallTime::now();
    waitLocked([&] { return status_.applied_stamp == last_stamp_; }, 10);
    catch_up_ms_ = (ros::WallTime::now() - after).toSec() * 1e3;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      end_ = status_;
    }
    const ros::WallTime release = ros::WallTime::now();
    feedback_.publish(gesture_.upAt(gesture_.press, ros::Time::now()));  // back where it started: no turn
    waitLocked([&] { return !status_.dragging; }, 10);
    release_ms_ = (ros::WallTime::now() - release).toSec() * 1e3;
  }

  /// The samples written to the CSV, the summary printed.
  void report()
  {
    std::vector<double> lag, apply;
    uint32_t max_pending = 0;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      std::ofstream out(csv_);
      out << "t_s,lag_ms,apply_ms,pending\n";
      for (const Sample& s : samples_)
      {
        out << s.t << ',' << s.lag_ms << ',' << s.apply_ms << ',' << s.pending << '\n';
        lag.push_back(s.lag_ms);
        apply.push_back(s.apply_ms);
        max_pending = std::max(max_pending, s.pending);
      }
    }
    const uint64_t received = end_.feedback_received - received_before_;
    const uint64_t coalesced = end_.feedback_coalesced - coalesced_before_;
    const uint64_t applied = end_.updates_applied - applied_before_;
    std::printf("interaction_flood: %d pose updates sent in %.2f s (%.0f/s)\n", sent_, flood_seconds_,
                sent_ / flood_seconds_);
    std::printf("  received by the node   %lu (%lu coalesced away, %lu applied: %.1f updates/s)\n",
                static_cast<unsigned long>(received), static_cast<unsigned long>(coalesced),
                static_cast<unsigned long>(applied), applied / flood_seconds_);
    std::printf("  rotate previews drawn  %d (%.1f/s)\n", previews_ - previews_before_,
                (previews_ - previews_before_) / flood_seconds_);
    std::printf("  lag of the applied pose  p50 %.1f ms, p95 %.1f ms, max %.1f ms (%zu samples)\n",
                percentile(lag, 0.5), percentile(lag, 0.95),
                lag.empty() ? NAN : *std::max_element(lag.begin(), lag.end()), lag.size());
    std::printf("  one update (preview call included)  p50 %.1f ms, p95 %.1f ms\n", percentile(apply, 0.5),
                percentile(apply, 0.95));
    std::printf("  events waiting in the node's queue  max %u\n", max_pending);
    std::printf("  paper_model `save` during the flood  p50 %.1f ms, max %.1f ms (%zu calls)\n",
                percentile(save_ms_, 0.5), save_ms_.empty() ? NAN : *std::max_element(save_ms_.begin(), save_ms_.end()),
                save_ms_.size());
    std::printf("  after the flood: last pose applied within %.0f ms, release handled within %.0f ms\n", catch_up_ms_,
                release_ms_);
    std::printf("  samples in %s\n", csv_.c_str());
  }

private:
  /// waitFor with `done` asked under the mutex.
  bool waitLocked(const std::function<bool()>& done, double seconds)
  {
    return waitFor(
        [&] {
          std::lock_guard<std::mutex> lock(mutex_);
          return done();
        },
        seconds);
  }

  ros::NodeHandle nh_;
  const double rate_, seconds_;
  const std::string csv_;

  // Written by the subscriptions' callbacks (under mutex_, but previews_).
  std::mutex mutex_;
  InteractionStatus status_;
  bool have_status_ = false;
  std::vector<Sample> samples_;
  std::atomic<int> previews_{ 0 };
  ros::Time flood_start_;
  visualization_msgs::InteractiveMarkerInit init_;
  virtual_origami::PaperState state_;

  virtual_origami::MouseGesture gesture_;
  int rotate_entry_ = -1;
  // The node's counters at the press, and what the flood measured.
  int previews_before_ = 0;
  uint64_t received_before_ = 0, coalesced_before_ = 0, applied_before_ = 0;
  std::vector<double> save_ms_;
  int sent_ = 0;
  ros::Time last_stamp_;
  double flood_seconds_ = 0, catch_up_ms_ = 0, release_ms_ = 0;
  InteractionStatus end_;

  // Declared last: the spinner stops before anything its callbacks touch goes.
  ros::Subscriber status_sub_, init_sub_, state_sub_, markers_sub_;
  ros::Publisher feedback_;
  ros::AsyncSpinner spinner_{ 1 };
};
}  // namespace

int main(int argc, char** argv)
{
  ros::init(argc, argv, "interaction_flood");
  ros::NodeHandle nh("/origami"), pnh("~");
  InteractionFlood bench(nh, pnh);
  if (!bench.creaseSheet())
    return 1;
  bench.pressInRotateMode();
  bench.flood();
  bench.release();
  bench.report();
  return 0;
}

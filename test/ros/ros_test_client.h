// What every rostest of the package needs: service calls, the latest state, waiting.
#pragma once

#include <gtest/gtest.h>

#include <csignal>
#include <cstdio>
#include <fstream>
#include <functional>
#include <string>

#include <ros/master.h>
#include <ros/ros.h>
#include <std_srvs/Trigger.h>
#include <virtual_origami/Crease.h>
#include <virtual_origami/PaperState.h>
#include <virtual_origami/Rotate.h>

namespace virtual_origami::test
{
/// Spins until `done` holds or `seconds` pass; true when it held.
inline bool waitFor(const std::function<bool()>& done, double seconds = 10.0)
{
  const ros::WallTime until = ros::WallTime::now() + ros::WallDuration(seconds);
  while (ros::ok() && ros::WallTime::now() < until)
  {
    ros::spinOnce();
    if (done())
      return true;
    ros::WallDuration(0.01).sleep();
  }
  return done();
}

/// The pid of the process roslaunch started for a node under this test's master, or -1.
/// Processes of other ROS systems on the machine (another test run) are left alone.
inline int pidOf(const std::string& node)
{
  const std::string command = "pgrep -f '__name:=" + node + "( |$)'";
  const std::string ours = "ROS_MASTER_URI=" + ros::master::getURI();
  FILE* pipe = ::popen(command.c_str(), "r");
  int found = -1;
  for (int pid; pipe && found < 0 && std::fscanf(pipe, "%d", &pid) == 1;)
  {
    std::ifstream environ("/proc/" + std::to_string(pid) + "/environ");
    for (std::string entry; std::getline(environ, entry, '\0');)
      if (entry == ours)
        found = pid;
  }
  if (pipe)
    ::pclose(pipe);
  return found;
}

/// SIGKILL, as a crash would; with `respawned`, returns once another process has taken its place.
inline void crash(const std::string& node, bool respawned = true)
{
  const int pid = pidOf(node);
  ASSERT_GT(pid, 0) << node << " is not running";
  ASSERT_EQ(::kill(pid, SIGKILL), 0);
  if (respawned)
    ASSERT_TRUE(waitFor([&] { const int now = pidOf(node); return now > 0 && now != pid; }, 30.0))
        << node << " was not restarted";
}

class PaperClient
{
public:
  explicit PaperClient(const std::string& ns = "/origami") : nh_(ns)
  {
    state_sub_ = nh_.subscribe<PaperState>("state", 10, [this](const PaperState::ConstPtr& s) { state_ = *s; ++states_; });
  }

  template <class Service>
  Service call(const std::string& name, const typename Service::Request& request)
  {
    Service srv;
    srv.request = request;
    const std::string resolved = nh_.resolveName(name);
    EXPECT_TRUE(ros::service::waitForService(resolved, ros::Duration(30))) << resolved;
    EXPECT_TRUE(ros::service::call(resolved, srv)) << resolved;
    return srv;
  }

  std_srvs::Trigger trigger(const std::string& name) { return call<std_srvs::Trigger>(name, {}); }

  Crease crease(double x0, double y0, double x1, double y1, bool snap = false)
  {
    Crease::Request r;
    r.start.x = x0;
    r.start.y = y0;
    r.end.x = x1;
    r.end.y = y1;
    r.snap = snap;
    return call<Crease>("crease", r);
  }

  Rotate rotate(int face, int axis, double x, double y, double angle, bool commit = true)
  {
    Rotate::Request r;
    r.face = face;
    r.axis_edge = axis;
    r.click.x = x;
    r.click.y = y;
    r.angle = angle;
    r.commit = commit;
    return call<Rotate>("rotate", r);
  }

  /// The latest state once its revision is `revision`.
  const PaperState& stateAt(uint64_t revision)
  {
    EXPECT_TRUE(waitFor([&] { return states_ > 0 && state_.revision == revision; }))
        << "state stayed at revision " << state_.revision << ", expected " << revision;
    return state_;
  }
  const PaperState& state()
  {
    waitFor([&] { return states_ > 0; });
    return state_;
  }
  ros::NodeHandle& nh() { return nh_; }

private:
  ros::NodeHandle nh_;
  ros::Subscriber state_sub_;
  PaperState state_;
  int states_ = 0;
};

}  // namespace virtual_origami::test

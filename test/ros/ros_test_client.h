// What every rostest of the package needs: service calls, the latest state, waiting.
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <csignal>
#include <functional>
#include <string>

#include <ros/master.h>
#include <ros/network.h>
#include <ros/ros.h>
#include <std_srvs/Trigger.h>
#include <virtual_origami/Crease.h>
#include <virtual_origami/PaperState.h>
#include <virtual_origami/Rotate.h>
#include <xmlrpcpp/XmlRpcClient.h>

#include "virtual_origami/ros/service_call.h"

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

/// The pid of a node registered with this test's master (`paper_model` means
/// `/origami/paper_model`), asked of the node itself; -1 when it is not running. Processes of
/// other ROS systems on the machine (another test run) are never found.
inline int pidOf(const std::string& node)
{
  XmlRpc::XmlRpcValue args, result, payload;
  args[0] = ros::this_node::getName();
  args[1] = node.front() == '/' ? node : "/origami/" + node;
  if (!ros::master::execute("lookupNode", args, result, payload, false) ||
      payload.getType() != XmlRpc::XmlRpcValue::TypeString)
    return -1;
  std::string host;
  uint32_t port = 0;
  if (!ros::network::splitURI(static_cast<std::string>(payload), host, port))
    return -1;
  XmlRpc::XmlRpcClient client(host.c_str(), static_cast<int>(port), "/");
  XmlRpc::XmlRpcValue pid_args, pid;
  pid_args[0] = ros::this_node::getName();
  // A killed node stays registered until its successor registers: its URI refuses the call.
  if (!client.execute("getPid", pid_args, pid) || pid.getType() != XmlRpc::XmlRpcValue::TypeArray ||
      pid.size() < 3 || static_cast<int>(pid[0]) != 1)
    return -1;
  return static_cast<int>(pid[2]);
}

/// SIGKILL, as a crash would; with `respawned`, returns once another process has taken its place.
inline void crash(const std::string& node, bool respawned = true)
{
  int pid = -1;
  // A node just launched may not have registered yet.
  waitFor([&] { return (pid = pidOf(node)) > 0; }, 30.0);
  ASSERT_GT(pid, 0) << node << " is not running";
  ASSERT_EQ(::kill(pid, SIGKILL), 0);
  if (respawned)
  {
    ASSERT_TRUE(waitFor([&] { const int now = pidOf(node); return now > 0 && now != pid; }, 30.0))
        << node << " was not restarted";
  }
}

/// A point of the `paper` frame as a message.
inline geometry_msgs::Point point(double x, double y, double z = 0.0)
{
  geometry_msgs::Point p;
  p.x = x;
  p.y = y;
  p.z = z;
  return p;
}

/// The vertex of a state at a crease-pattern point, or -1.
inline int vertexAt(const PaperState& state, double x, double y)
{
  for (size_t v = 0; v < state.vertices_crease_pattern.size(); ++v)
    if (std::abs(state.vertices_crease_pattern[v].x - x) < 1e-12 && std::abs(state.vertices_crease_pattern[v].y - y) < 1e-12)
      return static_cast<int>(v);
  return -1;
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
    EXPECT_TRUE(callService(resolved, srv)) << resolved;
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
  /// The latest state once it is one published at `since` or later: a service's answer and the
  /// state it made come on two connections, and the answer may come first.
  const PaperState& stateSince(const ros::Time& since)
  {
    EXPECT_TRUE(waitFor([&] { return states_ > 0 && state_.header.stamp >= since; }, 30.0))
        << "no state published since " << since;
    return state_;
  }
  /// States received so far: a test that restarts the model waits for one past it.
  int received() const { return states_; }
  /// The first state received after `count` states.
  const PaperState& stateAfter(int count)
  {
    EXPECT_TRUE(waitFor([&] { return states_ > count; }, 30.0)) << "no new state";
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

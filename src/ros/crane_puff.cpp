#include "virtual_origami/ros/crane_puff.h"

#include <fstream>
#include <sstream>

#include <virtual_origami/PinVertex.h>

#include "virtual_origami/core/fold_sequence.h"
#include "virtual_origami/ros/conversions.h"
#include "virtual_origami/ros/operation_client.h"

namespace virtual_origami
{
CranePuff::CranePuff(ros::NodeHandle nh, CranePuffOptions options) : nh_(nh), options_(std::move(options))
{
  state_sub_ = nh_.subscribe<PaperState>("state", 10, [this](const PaperState::ConstPtr& s) {
    std::lock_guard<std::mutex> lock(mutex_);
    state_ = *s;
    have_state_ = true;
  });
  timer_ = nh_.createWallTimer(ros::WallDuration(1.0 / std::max(options_.rate, 1.0)), &CranePuff::broadcast, this);
}

void CranePuff::broadcast(const ros::WallTimerEvent&)
{
  std::lock_guard<std::mutex> lock(mutex_);
  if (!broadcasting_)
    return;
  for (int k = 0; k < 2; ++k)
    tf_.sendTransform(frameTransform(options_.paper_frame, options_.frame_prefix + std::to_string(k), tips_[k]));
}

core::Expected<PaperState> CranePuff::stateAfter(uint64_t revision)
{
  const ros::WallTime until = ros::WallTime::now() + ros::WallDuration(options_.timeout);
  while (ros::ok() && ros::WallTime::now() < until)
  {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      if (have_state_ && state_.revision >= revision)
        return state_;
    }
    ros::WallDuration(0.01).sleep();
  }
  return core::Expected<PaperState>::failure("no state of revision " + std::to_string(revision) + " within " +
                                             std::to_string(options_.timeout) + " s");
}

core::Status CranePuff::run()
{
  std::ifstream in(options_.sequence);
  if (!in)
    return core::failure("cannot read the fold sequence " + options_.sequence);
  std::stringstream text;
  text << in.rdbuf();
  const core::Expected<core::FoldSequence> sequence = core::parseFoldSequence(text.str());
  if (!sequence)
    return core::failure(options_.sequence + ": " + sequence.message());

  OperationClient client(nh_.getNamespace());
  if (!client.waitForServices(options_.timeout))
    return core::failure("the paper's services are not offered in " + nh_.getNamespace());
  const core::Expected<PaperState> before = stateAfter(0);
  if (!before)
    return core::failure(before.message());
  uint64_t applied_count = 0;
  for (const core::FoldStep& step : sequence->steps)
    for (int k = 0; k < step.repeat; ++k, ++applied_count)
      if (const core::Status applied = client.apply(toMessage(step.operation)); !applied)
        return core::failure("folding " + options_.sequence + " (" + step.note + "): " + applied.message());

  // Each operation is one revision: the state the last one made is the folded crane.
  const core::Expected<PaperState> state = stateAfter(before->revision + applied_count);
  if (!state)
    return core::failure(state.message());
  double side = 0.0;
  for (const auto& p : state->vertices_crease_pattern)
    side = std::max(side, std::max(p.x, p.y));
  int tip[2] = { -1, -1 };
  for (size_t v = 0; v < state->vertices_crease_pattern.size(); ++v)
  {
    const core::Vec2 p(state->vertices_crease_pattern[v].x, state->vertices_crease_pattern[v].y);
    if (p.norm() < 1e-9 * side)
      tip[0] = static_cast<int>(v);
    if ((p - core::Vec2(side, side)).norm() < 1e-9 * side)
      tip[1] = static_cast<int>(v);
  }
  if (tip[0] < 0 || tip[1] < 0)
    return core::failure("the folded paper has no corners (0, 0) and (s, s) to pull");
  core::Vec3 start[2];
  for (int k = 0; k < 2; ++k)
    start[k] = toVec3(state->vertices_folded[tip[k]]);
  const core::Vec3 apart = (start[1] - start[0]).normalized();
  {
    std::lock_guard<std::mutex> lock(mutex_);
    tips_[0] = start[0];
    tips_[1] = start[1];
    broadcasting_ = true;
  }
  ros::WallDuration(0.5).sleep();  // the frames are known before the pins take them
  for (int k = 0; k < 2; ++k)
  {
    PinVertex pin;
    pin.request.vertex = tip[k];
    pin.request.frame_id = options_.frame_prefix + std::to_string(k);
    const std::string name = nh_.resolveName("pin");
    if (!ros::service::waitForService(name, ros::Duration(options_.timeout)) || !ros::service::call(name, pin))
      return core::failure("the service " + name + " did not answer");
    if (!pin.response.success)
      return core::failure("pin vertex " + std::to_string(tip[k]) + ": " + pin.response.message);
  }
  ROS_INFO("crane_puff: the crane is folded and its wing tips (vertices %d and %d) pinned; pulling them %g apart",
           tip[0], tip[1], options_.spread * side);
  const ros::WallTime began = ros::WallTime::now();
  ros::WallRate rate(options_.rate);
  while (ros::ok())
  {
    const double s = std::min(1.0, (ros::WallTime::now() - began).toSec() / options_.duration);
    {
      std::lock_guard<std::mutex> lock(mutex_);
      tips_[0] = start[0] - 0.5 * s * options_.spread * side * apart;
      tips_[1] = start[1] + 0.5 * s * options_.spread * side * apart;
    }
    if (s >= 1.0)
      break;
    rate.sleep();
  }
  ROS_INFO("crane_puff: the wing tips are pulled apart; holding them there");
  return core::success();
}

}  // namespace virtual_origami

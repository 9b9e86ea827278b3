#include "virtual_origami/ros/interaction_node.h"

#include <algorithm>

#include <dynamic_reconfigure/Reconfigure.h>
#include <geometry_msgs/PoseStamped.h>
#include <std_srvs/Trigger.h>
#include <virtual_origami/Crease.h>
#include <virtual_origami/DragVertex.h>
#include <virtual_origami/FlatFold.h>
#include <virtual_origami/FoldByAssignment.h>
#include <virtual_origami/InteractionStatus.h>
#include <virtual_origami/PinVertex.h>
#include <virtual_origami/Rotate.h>
#include <virtual_origami/VertexTarget.h>

#include "virtual_origami/ros/conversions.h"
#include "virtual_origami/ros/tool_hint.h"

namespace virtual_origami
{
namespace
{
core::GestureSettings gestureSettings(const ros::NodeHandle& private_nh)
{
  core::GestureSettings s;
  s.snap_radius_set = private_nh.getParam("snap_radius", s.snap.radius);
  private_nh.param("edge_divisions", s.snap.edge_divisions, s.snap.edge_divisions);
  private_nh.param("angle_divisions", s.snap.angle_divisions, s.snap.angle_divisions);
  s.min_crease_length = private_nh.param("min_crease_length", s.min_crease_length);
  s.layer_gap = private_nh.param("layer_gap", s.layer_gap);
  s.fold_frames = std::max(1, private_nh.param("fold_frames", s.fold_frames));
  s.view_turn = private_nh.param("view_turn", s.view_turn);
  s.slider_catch_up_after = private_nh.param("slider_catch_up_after", s.slider_catch_up_after);
  std::vector<double> view;
  if (private_nh.getParam("view_direction", view) && view.size() == 3)
    s.view_direction = core::Vec3(view[0], view[1], view[2]);
  const std::string mode = private_nh.param<std::string>("mode", "crease");
  s.mode = mode == "rotate" ? core::GestureMode::Rotate :
           mode == "fold"   ? core::GestureMode::Fold :
           mode == "drag"   ? core::GestureMode::Drag :
           mode == "flap"   ? core::GestureMode::Flap :
                              core::GestureMode::Crease;
  return s;
}
}  // namespace

InteractionNode::InteractionNode(ros::NodeHandle nh, ros::NodeHandle private_nh)
  : nh_(nh)
  , tf_listener_(tf_buffer_)
  , model_(gestureSettings(private_nh), *this, [] { return ros::Time::now().toSec(); })
  // Its own thread takes the feedback as it comes, so a busy service call never makes rviz's
  // events wait in a queue that could drop a release.
  , server_(private_nh.param<std::string>("server_ns", "interaction"), "", true)
{
  style_.frame_id = private_nh.param<std::string>("paper_frame", style_.frame_id);
  style_.margin = private_nh.param("margin", style_.margin);
  style_.pick_alpha = static_cast<float>(private_nh.param("pick_alpha", static_cast<double>(style_.pick_alpha)));
  camera_frame_ = private_nh.param("camera_frame", camera_frame_);
  camera_timeout_ = private_nh.param("camera_timeout", camera_timeout_);
  slider_enabled_ = private_nh.param("fold_slider", slider_enabled_);
  slider_style_.frame_id = style_.frame_id;

  crease_ = nh_.serviceClient<Crease>("crease");
  rotate_ = nh_.serviceClient<Rotate>("rotate");
  squash_ = nh_.serviceClient<std_srvs::Trigger>("squash");
  undo_ = nh_.serviceClient<std_srvs::Trigger>("undo");
  keep_bend_ = nh_.serviceClient<std_srvs::Trigger>("curved_mesh_solver/keep_bend");
  redo_ = nh_.serviceClient<std_srvs::Trigger>("redo");
  reset_ = nh_.serviceClient<std_srvs::Trigger>("reset");
  pin_ = nh_.serviceClient<PinVertex>("pin");
  fold_ = nh_.serviceClient<FoldByAssignment>("fold_by_assignment");
  flat_fold_ = nh_.serviceClient<FlatFold>("flat_fold");
  drag_vertex_ = nh_.serviceClient<DragVertex>("drag_vertex");
  // Strain colours are paper_model's (it draws the paper): its dynamic_reconfigure.
  const std::string paper_model = private_nh.param<std::string>("paper_model", "paper_model");
  paper_model_reconfigure_ = nh_.serviceClient<dynamic_reconfigure::Reconfigure>(paper_model + "/set_parameters");
  strain_colours_sub_ =
      nh_.subscribe(paper_model + "/parameter_updates", 1, &InteractionNode::strainColoursChanged, this);

  buildMenu();

  markers_pub_ = nh_.advertise<visualization_msgs::MarkerArray>("interaction_markers", 10);
  status_pub_ = nh_.advertise<InteractionStatus>("interaction_status", 10);
  curved_drag_pub_ = nh_.advertise<VertexTarget>("curved_drag", 1);
  curved_sheet_sub_ = nh_.subscribe("curved_mesh", 1, &InteractionNode::curvedSheetReceived, this);
  view_turn_pub_ = nh_.advertise<geometry_msgs::PoseStamped>("view_turn", 1);
  slider_pub_ = nh_.advertise<visualization_msgs::MarkerArray>("fold_slider_markers", 10, true);
  state_sub_ = nh_.subscribe("state", 1, &InteractionNode::stateReceived, this);
  tool_sub_ = nh_.subscribe("tool_events", 100, &InteractionNode::toolReceived, this);
  period_ = 1.0 / private_nh.param("rate", 30.0);
  timer_ = nh_.createTimer(ros::Duration(period_), &InteractionNode::handleEvents, this);
  // An event is taken at once, not at the next tick (a slider's preview waited up to 33 ms for
  // it), and the queue no more often than `update_rate`: a flood of poses is still one update a
  // period. 60 Hz: at 30 a preview answered in 20 ms waited 13 ms more before the next began.
  update_period_ = 1.0 / std::max(1.0, private_nh.param("update_rate", 60.0));
  prompt_timer_ = nh_.createTimer(ros::Duration(0.001), &InteractionNode::handlePrompt, this, true, false);
  status_timer_ = nh_.createTimer(ros::Duration(1.0), &InteractionNode::publishStatus, this);
}

void InteractionNode::received(const Feedback::ConstPtr& feedback, MenuCallback chosen, bool slider)
{
  std::lock_guard<std::mutex> lock(mutex_);
  ++received_;
  // A Fold tool's event in the queue has no feedback: never a pose to merge with.
  const auto isPose = [](const Event& e) {
    return !e.chosen && e.feedback && e.feedback->event_type == Feedback::POSE_UPDATE;
  };
  const Event event{ feedback, std::move(chosen), slider, nullptr };
  if (isPose(event) && !events_.empty() && isPose(events_.back()) && events_.back().slider == slider)
  {
    events_.back().feedback = feedback;  // only the latest pose matters
    ++coalesced_;
    return;
  }
  events_.push_back(event);
  promptLocked();
}

void InteractionNode::promptLocked()
{
  if (prompted_)
    return;
  prompted_ = true;
  const double due = taken_at_ + update_period_ - ros::WallTime::now().toSec();
  prompt_timer_.stop();
  prompt_timer_.setPeriod(ros::Duration(std::max(1e-3, due)));
  prompt_timer_.start();
}

void InteractionNode::handleEvents(const ros::TimerEvent&)
{
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (!events_.empty())
    {
      promptLocked();  // the prompt takes them (it runs already, unless something stopped it)
      return;
    }
  }
  if (model_.state() == core::GestureState::FoldingMarks)
  {
    model_.tick();
    publishStatus();
  }
  else if (model_.state() == core::GestureState::Sliding)
    model_.catchUpSlider();  // the handle rests: its previews go on to it
}

void InteractionNode::handlePrompt(const ros::TimerEvent&)
{
  std::deque<Event> events;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    prompted_ = false;
    events.swap(events_);
    taken_at_ = ros::WallTime::now().toSec();
  }
  if (events.empty())
    return;
  const ros::WallTime start = ros::WallTime::now();
  const uint64_t updates = model_.updates();
  model_.finishFold();  // the user goes on: the fold first, at once
  ros::Time pointer_stamp;
  for (const Event& e : events)
  {
    static const Feedback none;
    const Feedback& f = e.feedback ? *e.feedback : none;
    if (e.tool)
    {
      toolEvent(*e.tool);
      if (e.tool->kind <= ToolEvent::RELEASE)
        pointer_stamp = e.tool->header.stamp;
    }
    else if (e.chosen)
      e.chosen(f);
    else if (e.slider)
      slide(f);
    else if (f.event_type == Feedback::MOUSE_DOWN)
    {
      if (!f.header.frame_id.empty() && f.header.frame_id != style_.frame_id)
        ROS_WARN_ONCE("interaction: feedback in frame %s, expected %s", f.header.frame_id.c_str(),
                      style_.frame_id.c_str());
      model_.press(pointer(f));
      pointer_stamp = f.header.stamp;
    }
    else if (f.event_type == Feedback::POSE_UPDATE)
    {
      model_.move(pointer(f));
      pointer_stamp = f.header.stamp;
    }
    else if (f.event_type == Feedback::MOUSE_UP)
    {
      model_.release(pointer(f));
      pointer_stamp = f.header.stamp;
    }
  }
  model_.update();
  if (model_.updates() != updates)
  {
    if (!pointer_stamp.isZero())
      applied_stamp_ = pointer_stamp;
    apply_seconds_ = (ros::WallTime::now() - start).toSec();
  }
  publishStatus();
}

core::Pointer InteractionNode::pointer(const Feedback& feedback) const
{
  core::Pointer p;
  if (feedback.mouse_point_valid)
    p.mouse_point = toVec3(feedback.mouse_point);
  p.marker_position = toVec3(feedback.pose.position);
  p.camera = camera(feedback.header.stamp);
  return p;
}

void InteractionNode::slide(const Feedback& feedback)
{
  if (!slider_shown_)
    return;
  if (feedback.event_type == Feedback::MOUSE_DOWN)
    model_.slidePress();
  else if (feedback.event_type == Feedback::POSE_UPDATE)
    model_.slideMove(sliderFraction(track_, toVec3(feedback.pose.position)));
  else if (feedback.event_type == Feedback::MOUSE_UP)
    model_.slideRelease(sliderFraction(track_, toVec3(feedback.pose.position)));
}

void InteractionNode::stateReceived(const PaperState::ConstPtr& state)
{
  core::Expected<core::Paper> paper = fromMessage(*state);
  if (!paper)
  {
    ROS_ERROR("interaction: unusable state: %s", paper.message().c_str());
    return;
  }
  std::vector<int> pinned;
  for (const Pin& pin : state->pins)
    pinned.push_back(pin.vertex);
  model_.paperChanged(std::move(*paper), state->revision, std::move(pinned));
}

std::optional<ViewCamera> InteractionNode::camera(const ros::Time& stamp) const
{
  geometry_msgs::TransformStamped t;
  try
  {
    // rviz stamps feedback of a frame-following marker with 0: then the latest camera.
    t = tf_buffer_.lookupTransform(style_.frame_id, camera_frame_, stamp);
  }
  catch (const tf2::TransformException&)
  {
    try
    {
      t = tf_buffer_.lookupTransform(style_.frame_id, camera_frame_, ros::Time(0));
    }
    catch (const tf2::TransformException&)
    {
      return std::nullopt;
    }
  }
  if ((ros::Time::now() - t.header.stamp).toSec() > camera_timeout_)
    return std::nullopt;  // rviz is gone (tf keeps a frame's last pose for ever)
  ViewCamera c;
  c.eye = core::Vec3(t.transform.translation.x, t.transform.translation.y, t.transform.translation.z);
  c.axes =
      Eigen::Quaterniond(t.transform.rotation.w, t.transform.rotation.x, t.transform.rotation.y, t.transform.rotation.z)
          .normalized()
          .toRotationMatrix();
  return c;
}

void InteractionNode::publishStatus(const ros::TimerEvent&)
{
  if (!model_.dragging() && model_.paper() && camera(ros::Time::now()).has_value() != camera_known_)
    model_.refreshSheet();  // rviz's camera came or went: the drag plane changes with it
  const core::GestureStatus gestures = model_.status();
  InteractionStatus status;
  status.header.stamp = ros::Time::now();
  status.mode = core::modeName(model_.mode());
  status.picked_edge = gestures.picked_edge;
  status.picked_face = gestures.picked_face;
  status.picked_vertex = gestures.picked_vertex;
  status.bending = gestures.bending;
  status.picked_layer = gestures.picked_layer;
  status.layers = gestures.layers;
  status.marked_edges = gestures.marked_edges;
  status.marked_angles = gestures.marked_angles;
  status.dragging = gestures.dragging;
  status.revision = model_.revision();
  {
    std::lock_guard<std::mutex> lock(mutex_);
    status.feedback_received = received_;
    status.feedback_coalesced = coalesced_;
    status.pending = static_cast<uint32_t>(events_.size());
  }
  status.updates_applied = model_.updates();
  status.applied_stamp = applied_stamp_;
  status.apply_seconds = apply_seconds_;
  status.message = message_;
  core::GestureStatus held = gestures;  // a fold animating holds nothing the user could let go
  held.dragging = model_.dragging() || model_.state() == core::GestureState::Sliding;
  status.hint = toolHint(model_.mode(), held);
  status_pub_.publish(status);
}

}  // namespace virtual_origami

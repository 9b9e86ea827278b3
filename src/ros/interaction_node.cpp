#include "virtual_origami/ros/interaction_node.h"

#include <algorithm>
#include <cmath>

#include <dynamic_reconfigure/Reconfigure.h>
#include <std_srvs/Trigger.h>
#include <virtual_origami/Crease.h>
#include <virtual_origami/DragVertex.h>
#include <virtual_origami/VertexTarget.h>
#include <virtual_origami/FlatFold.h>
#include <virtual_origami/FoldByAssignment.h>
#include <virtual_origami/InteractionStatus.h>
#include <virtual_origami/PinVertex.h>
#include <virtual_origami/Rotate.h>

#include "virtual_origami/core/axis.h"
#include "virtual_origami/core/geometry.h"
#include "virtual_origami/core/layers.h"
#include "virtual_origami/ros/conversions.h"
#include "virtual_origami/ros/interaction_text.h"

namespace virtual_origami
{
namespace
{
using interactive_markers::MenuHandler;

/// A turn smaller than this (radians) is no turn: nothing is previewed or committed.
constexpr double kNoTurn = 1e-3;
/// Characters per line of a message: a short column stays inside the view.
constexpr size_t kMessageWidth = 32;

/// Calls a service; false (and the reason in `message`) when it cannot be reached.
template <class Service>
bool call(ros::ServiceClient& client, Service& srv, std::string& message)
{
  if (client.call(srv))
    return true;
  message = client.getService() + " did not answer; is paper_model running?";
  return false;
}
}  // namespace

InteractionNode::InteractionNode(ros::NodeHandle nh, ros::NodeHandle private_nh)
  : nh_(nh)
  // Its own thread takes the feedback as it comes, so a busy service call never makes rviz's
  // events wait in a queue that could drop a release.
  , tf_listener_(tf_buffer_)
  , server_(private_nh.param<std::string>("server_ns", "interaction"), "", true)
{
  style_.frame_id = private_nh.param<std::string>("paper_frame", style_.frame_id);
  style_.margin = private_nh.param("margin", style_.margin);
  layer_gap_ = private_nh.param("layer_gap", layer_gap_);
  style_.pick_alpha = static_cast<float>(private_nh.param("pick_alpha", static_cast<double>(style_.pick_alpha)));
  snap_radius_set_ = private_nh.getParam("snap_radius", snap_.radius);
  private_nh.param("edge_divisions", snap_.edge_divisions, snap_.edge_divisions);
  private_nh.param("angle_divisions", snap_.angle_divisions, snap_.angle_divisions);
  min_crease_length_ = private_nh.param("min_crease_length", min_crease_length_);
  std::vector<double> view;
  if (private_nh.getParam("view_direction", view) && view.size() == 3)
    view_direction_ = core::Vec3(view[0], view[1], view[2]);
  const std::string mode = private_nh.param<std::string>("mode", "crease");
  mode_ = mode == "rotate" ? Mode::Rotate : mode == "fold" ? Mode::Fold : mode == "drag" ? Mode::Drag : Mode::Crease;
  fold_frames_ = std::max(1, private_nh.param("fold_frames", fold_frames_));
  camera_frame_ = private_nh.param("camera_frame", camera_frame_);
  camera_timeout_ = private_nh.param("camera_timeout", camera_timeout_);
  view_turn_ = private_nh.param("view_turn", view_turn_);
  slider_enabled_ = private_nh.param("fold_slider", slider_enabled_);
  slider_style_.frame_id = style_.frame_id;

  crease_ = nh_.serviceClient<Crease>("crease");
  rotate_ = nh_.serviceClient<Rotate>("rotate");
  squash_ = nh_.serviceClient<std_srvs::Trigger>("squash");
  undo_ = nh_.serviceClient<std_srvs::Trigger>("undo");
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

  const auto entry = [this](const std::string& title, Action action) {
    return menu_.insert(title, [this, action](const Feedback::ConstPtr& f) { received(f, action); });
  };
  crease_entry_ = entry("Crease mode", Action::CreaseMode);
  rotate_entry_ = entry("Rotate mode", Action::RotateMode);
  entry("Squash", Action::Squash);
  entry("Undo", Action::Undo);
  entry("Redo", Action::Redo);
  entry("Reset", Action::Reset);
  entry("Pin the nearest vertex", Action::Pin);
  entry("Release the nearest pin", Action::Release);
  const auto fold_menu = menu_.insert("Fold by assignment");
  for (int percent : { 0, 25, 50, 75, 100 })
    menu_.insert(fold_menu, std::to_string(percent) + " %", [this, percent](const Feedback::ConstPtr& f) {
      received(f, Action::FoldByAssignment, false, percent / 100.0);
    });
  strain_entry_ = entry("Colour by strain", Action::ColourByStrain);
  // After the entries above, which keep their places in the menu.
  fold_entry_ = entry("Fold mode: mark creases", Action::FoldMode);
  drag_entry_ = entry("Drag mode: drag a vertex", Action::DragMode);
  const auto marked = menu_.insert("Fold on the marked creases");
  menu_.insert(marked, "Fold flat", [this](const Feedback::ConstPtr& f) { received(f, Action::FoldFlat); });
  menu_.insert(marked, "Fold to a right angle",
               [this](const Feedback::ConstPtr& f) { received(f, Action::FoldRightAngle); });
  menu_.insert(marked, "Keep the face here", [this](const Feedback::ConstPtr& f) { received(f, Action::KeepFace); });
  menu_.insert(marked, "Clear the marks", [this](const Feedback::ConstPtr& f) { received(f, Action::ClearMarks); });
  entry("Next layer down", Action::NextLayer);
  layers_entry_ = entry("Turn the picked layers only", Action::PickedLayersOnly);
  snap_entry_ = entry("Snap the line", Action::Snapping);

  markers_pub_ = nh_.advertise<visualization_msgs::MarkerArray>("interaction_markers", 10);
  status_pub_ = nh_.advertise<InteractionStatus>("interaction_status", 10);
  curved_drag_pub_ = nh_.advertise<VertexTarget>("curved_drag", 1);
  curved_sheet_sub_ = nh_.subscribe("curved_mesh", 1, &InteractionNode::curvedSheetReceived, this);
  view_turn_pub_ = nh_.advertise<geometry_msgs::PoseStamped>("view_turn", 1);
  slider_pub_ = nh_.advertise<visualization_msgs::MarkerArray>("fold_slider_markers", 10, true);
  state_sub_ = nh_.subscribe("state", 1, &InteractionNode::stateReceived, this);
  timer_ = nh_.createTimer(ros::Duration(1.0 / private_nh.param("rate", 30.0)), &InteractionNode::handleEvents, this);
  status_timer_ = nh_.createTimer(ros::Duration(1.0), &InteractionNode::publishStatus, this);
}

void InteractionNode::received(const Feedback::ConstPtr& feedback, Action action, bool slider, double fraction)
{
  std::lock_guard<std::mutex> lock(mutex_);
  ++received_;
  const bool pose = action == Action::None && feedback->event_type == Feedback::POSE_UPDATE;
  if (pose && !events_.empty() && events_.back().action == Action::None && events_.back().slider == slider &&
      events_.back().feedback->event_type == Feedback::POSE_UPDATE)
  {
    events_.back().feedback = feedback;  // only the latest pose matters
    ++coalesced_;
    return;
  }
  events_.push_back({ feedback, action, slider, fraction });
}

void InteractionNode::handleEvents(const ros::TimerEvent&)
{
  std::deque<Event> events;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    events.swap(events_);
  }
  if (events.empty())
  {
    if (folding_)
    {
      animateFold();
      publishStatus();
    }
    return;
  }
  while (folding_)  // the user goes on: the fold first, at once
    animateFold();
  for (const Event& e : events)
  {
    if (e.action == Action::FoldByAssignment)
    {
      const std::string said = foldByAssignment(e.fraction);
      if (!said.empty())
        tell(said, e.feedback->mouse_point_valid ? onSheet(e.feedback->mouse_point) : core::Vec3::Zero());
    }
    else if (e.action != Action::None)
      menu(e.action, *e.feedback);
    else if (e.slider)
      slide(*e.feedback);
    else if (e.feedback->event_type == Feedback::MOUSE_DOWN)
      press(*e.feedback);
    else if (e.feedback->event_type == Feedback::POSE_UPDATE)
      move(*e.feedback);
    else if (e.feedback->event_type == Feedback::MOUSE_UP)
    {
      move(*e.feedback);
      release();
    }
  }
  if (dragging_ && moved_)
    updateDrag();
  if (slider_dragging_ && slider_moved_)
    updateSlider();
  publishStatus();
}

void InteractionNode::stateReceived(const PaperState::ConstPtr& state)
{
  core::Expected<core::Paper> paper = fromMessage(*state);
  if (!paper)
  {
    ROS_ERROR("interaction: unusable state: %s", paper.message().c_str());
    return;
  }
  paper_ = std::move(*paper);
  revision_ = state->revision;
  pinned_.clear();
  for (const Pin& pin : state->pins)
    pinned_.push_back(pin.vertex);
  if (!snap_radius_set_)
    snap_.radius = core::SnapSettings{}.radius * paper_->scale();
  const std::vector<int> levels = core::stackLevels(*paper_);
  const int top = levels.empty() ? 0 : *std::max_element(levels.begin(), levels.end());
  pick_lift_ = (top + 1) * layer_gap_ + 0.002 * paper_->scale();
  style_.drawn_top = top * layer_gap_;
  if (dragging_ || slider_dragging_)
  {
    paper_changed_ = true;  // re-sending a marker now would end the drag in rviz
    slider_changed_ = true;
  }
  else
  {
    showPaper();
    showSlider();
  }
  showPicks();
}

void InteractionNode::showPaper()
{
  if (!paper_)
    return;
  const std::string description = mode_ == Mode::Crease ? "crease: drag a line" :
                                  mode_ == Mode::Rotate ? "rotate: drag a face" :
                                  mode_ == Mode::Fold   ? "fold: click creases, then Fold" :
                                                          "drag: drag a vertex";
  style_.pick_lift = pick_lift_;
  // With the camera known the drag plane faces the view: the pointer is on the mouse's sight
  // line wherever it goes (a plane along the sheet is missed by sight lines above its horizon).
  camera_known_ = camera(ros::Time::now()).has_value();
  style_.view_facing_drag = camera_known_;
  server_.insert(paperInteractiveMarker(*paper_, description, style_),
                 [this](const Feedback::ConstPtr& f) { received(f, Action::None); });
  menu_.setCheckState(crease_entry_, mode_ == Mode::Crease ? MenuHandler::CHECKED : MenuHandler::UNCHECKED);
  menu_.setCheckState(rotate_entry_, mode_ == Mode::Rotate ? MenuHandler::CHECKED : MenuHandler::UNCHECKED);
  menu_.setCheckState(fold_entry_, mode_ == Mode::Fold ? MenuHandler::CHECKED : MenuHandler::UNCHECKED);
  menu_.setCheckState(drag_entry_, mode_ == Mode::Drag ? MenuHandler::CHECKED : MenuHandler::UNCHECKED);
  menu_.setCheckState(layers_entry_, picked_layers_only_ ? MenuHandler::CHECKED : MenuHandler::UNCHECKED);
  menu_.setCheckState(snap_entry_, snapping_ ? MenuHandler::CHECKED : MenuHandler::UNCHECKED);
  menu_.setCheckState(strain_entry_, colour_by_strain_ ? MenuHandler::CHECKED : MenuHandler::UNCHECKED);
  menu_.apply(server_, style_.marker_name);
  server_.applyChanges();
  paper_changed_ = false;
}

core::Vec3 InteractionNode::onSheet(const geometry_msgs::Point& mouse_point) const
{
  return toVec3(mouse_point) - core::Vec3(0, 0, style_.pick_lift);
}

double InteractionNode::tableHeight() const
{
  double z = paper_->vertices.empty() ? 0.0 : paper_->vertices[0].folded.z();
  for (const core::Vertex& v : paper_->vertices)
    z = std::min(z, v.folded.z());
  return z;
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

core::Vec3 InteractionNode::sight(const std::optional<ViewCamera>& camera, const core::Vec3& point) const
{
  if (camera)
  {
    const core::Vec3 ray = camera->rayTo(point);
    if (ray.allFinite())
      return ray;
  }
  return view_direction_.normalized();
}

core::Vec3 InteractionNode::creaseEnd() const
{
  const std::optional<ViewCamera> now = camera(pointer_stamp_);
  if (!now)
    return pointer_;
  // Off the paper (on the margin) the line is drawn on the table under it.
  const core::Vec3 normal = press_face_ >= 0 ? paper_->faceNormal(press_face_) : core::Vec3::UnitZ();
  return alongSightOnto(*now, pointer_, press_, normal).value_or(pointer_);
}

void InteractionNode::turnView()
{
  if (!view_turn_ || !press_camera_ || !ring_ || !ring_->edge_on)
    return;
  const std::optional<ViewCamera> turned =
      turnedView(*press_camera_, press_, paper_->faceCentroid(ring_->face), ring_->axis_b - ring_->axis_a);
  if (!turned)
    return;
  geometry_msgs::PoseStamped goal;
  goal.header.frame_id = style_.frame_id;
  goal.header.stamp = ros::Time::now();
  goal.pose.position = toPoint(turned->eye);
  const Eigen::Quaterniond q(turned->axes);
  goal.pose.orientation.w = q.w();
  goal.pose.orientation.x = q.x();
  goal.pose.orientation.y = q.y();
  goal.pose.orientation.z = q.z();
  view_turn_pub_.publish(goal);
  view_turned_ = true;
}

void InteractionNode::turnViewBack()
{
  if (!view_turned_)
    return;
  geometry_msgs::PoseStamped back;  // no frame: the view before the turn
  back.header.stamp = ros::Time::now();
  view_turn_pub_.publish(back);
  view_turned_ = false;
}

void InteractionNode::press(const Feedback& feedback)
{
  dragging_ = false;
  if (!paper_ || !feedback.mouse_point_valid)
    return;
  if (!feedback.header.frame_id.empty() && feedback.header.frame_id != style_.frame_id)
    ROS_WARN_ONCE("interaction: feedback in frame %s, expected %s", feedback.header.frame_id.c_str(),
                  style_.frame_id.c_str());
  dragging_ = true;
  moved_ = false;
  press_camera_ = camera(feedback.header.stamp);
  if (press_camera_)
  {
    // rviz's point lies on the pickable copy, a little towards the eye: along the sight line
    // onto the face the eye sees there.
    grab_ = toVec3(feedback.mouse_point);
    press_ = core::onSurface(*paper_, grab_, sight(press_camera_, grab_));
    if (press_ == grab_)  // on no face: on the margin, which lies on the table under the paper
      press_ =
          alongSightOnto(*press_camera_, grab_, core::Vec3(0, 0, tableHeight()), core::Vec3::UnitZ()).value_or(grab_);
  }
  else
    grab_ = press_ = core::onSurface(*paper_, onSheet(feedback.mouse_point), view_direction_);
  pointer_ = grab_;
  press_face_ = core::faceAt(*paper_, press_, 1e-6 * paper_->scale());
  pose_at_press_ = toVec3(feedback.pose.position);
  pointer_stamp_ = feedback.header.stamp;
  angle_ = previewed_angle_ = 0.0;
  reach_ = 0.0;
  previewed_ = false;
  ring_.reset();
  ring_refusal_.clear();
  crease_at_press_ = -1;
  if (mode_ == Mode::Rotate)
  {
    crease_at_press_ = core::creaseNear(*paper_, press_, snap_.radius);
    // A layer picked here (Next layer down) turns instead of the top one.
    const int face = pickedHere(Pick::Kind::Face, press_) ? pick_.current() : -1;
    core::Expected<core::RotationRing> ring =
        core::rotationRing(*paper_, press_, sight(press_camera_, press_), face, namedAxis(), !picked_layers_only_);
    if (!ring)
    {
      ring_refusal_ = ring.message();
      return;  // the drag goes on in rviz, but turns nothing; said on release
    }
    ring_ = *ring;
    turnView();
  }
  if (mode_ == Mode::Drag)
    pressVertex();
  updateDrag();
}

void InteractionNode::move(const Feedback& feedback)
{
  if (!dragging_)
    return;
  // The drag plane carries the marker along: the pointer is the grab point moved as far as it,
  // on the line of sight through the mouse.
  const core::Vec3 moved = toVec3(feedback.pose.position) - pose_at_press_;
  pointer_ = grab_ + moved;
  pointer_stamp_ = feedback.header.stamp;
  reach_ = std::max(reach_, moved.norm());
  moved_ = true;
}

void InteractionNode::updateDrag()
{
  const ros::WallTime start = ros::WallTime::now();
  moved_ = false;
  if (mode_ == Mode::Crease)
    showMarkers(creaseDragMarkers(core::creaseDrag(*paper_, press_, creaseEnd(), lineSnap()), style_, ros::Time::now()));
  else if (mode_ == Mode::Drag)
    updateVertexDrag();
  else if (ring_)
  {
    const std::optional<ViewCamera> now = camera(pointer_stamp_);
    if (now)
    {
      // The view may have turned since the press (turnView): seen from the side now, the face
      // follows the pointer's sight line onto the ring's plane.
      const core::Vec3 d = (ring_->axis_b - ring_->axis_a).normalized();
      ring_->edge_on = std::abs(now->rayTo(ring_->press).dot(d)) < 0.5;
    }
    angle_ = core::ringAngle(*ring_, pointer_, sight(now, pointer_), angle_);
    // No preview of no turn: paper_model draws it from a rotated copy, which does not keep
    // the order of the layers the turn would part (a click redrew a 4-layer stack at 2
    // heights). Back at no turn after a preview, the preview of 0 puts the paper back.
    if (std::abs(angle_) > kNoTurn ? !previewed_ || std::abs(angle_ - previewed_angle_) > 1e-4 :
                                     previewed_ && previewed_angle_ != 0.0)
      previewRotation(std::abs(angle_) > kNoTurn ? angle_ : 0.0);
    showMarkers(rotationDragMarkers(*ring_, angle_, style_, ros::Time::now()));
  }
  ++applied_;
  applied_stamp_ = pointer_stamp_;
  apply_seconds_ = (ros::WallTime::now() - start).toSec();
}

bool InteractionNode::previewRotation(double angle)
{
  Rotate srv;
  srv.request.face = turningFace();
  srv.request.axis_edge = ring_->axis_edge;
  srv.request.click = toPoint(ring_->press);
  srv.request.angle = angle;
  srv.request.commit = false;
  srv.request.picked_layers_only = picked_layers_only_;
  std::string message;
  if (!call(rotate_, srv, message) || !srv.response.success)
  {
    ROS_DEBUG("interaction: preview at %.3f rad refused: %s", angle, srv.response.message.c_str());
    return false;
  }
  previewed_ = true;
  previewed_angle_ = angle;
  return true;
}

void InteractionNode::release()
{
  if (!dragging_)
    return;
  if (moved_)
    updateDrag();
  dragging_ = false;
  turnViewBack();
  showMarkers(clearedMarkers(style_, ros::Time::now()));
  std::string message;
  const bool clicked = reach_ < min_crease_length_ * paper_->scale();
  bool beside = false;  // what a click picked is said beside the paper, clear of the next click
  if (mode_ == Mode::Fold)
  {
    message = clicked ? foldClick() : "In fold mode click on creases to mark them; drag in the other modes.";
    beside = clicked;
  }
  else if (mode_ == Mode::Drag)
    message = releaseVertex();
  else if (mode_ == Mode::Rotate && clicked)
    message = click();
  else if (mode_ == Mode::Rotate && !ring_)
    message = ring_refusal_;
  else if (mode_ == Mode::Crease)
  {
    const core::CreaseDrag drag = core::creaseDrag(*paper_, press_, creaseEnd(), lineSnap());
    if (drag.length() >= min_crease_length_ * paper_->scale())
    {
      Crease srv;
      srv.request.start = toPoint(drag.start.point);
      srv.request.end = toPoint(drag.end.point);
      if (press_camera_)
      {
        // Through stacked layers of a 3D form, the layers under the line as the eye sees them.
        srv.request.has_eye = true;
        srv.request.eye = toPoint(press_camera_->eye);
      }
      srv.request.snap = false;  // snapped here already: what was drawn is what is creased
      if (call(crease_, srv, message) && !srv.response.success)
        message = srv.response.message;  // a refusal says why; a crease shows itself
    }
  }
  else if (ring_)
  {
    // The angle last shown is the one committed; a press without a turn commits nothing
    // and draws nothing new.
    const double angle = previewed_ ? previewed_angle_ : 0.0;
    if (std::abs(angle) > kNoTurn)
    {
      Rotate srv;
      srv.request.face = turningFace();
      srv.request.axis_edge = ring_->axis_edge;
      srv.request.click = toPoint(ring_->press);
      srv.request.angle = angle;
      srv.request.commit = true;
      srv.request.picked_layers_only = picked_layers_only_;
      if (call(rotate_, srv, message) && !srv.response.success)
        message = srv.response.message;
    }
    else if (previewed_ && previewed_angle_ != 0.0)
      previewRotation(0.0);
  }
  if (!message.empty() && beside)
    tellBeside(message);
  else if (!message.empty())
    tell(message, pointer_);
  else
    message_.clear();  // done, or nothing to do: an earlier refusal no longer applies
  // rviz keeps the marker where the drag left it: put it back under the sheet.
  geometry_msgs::Pose identity;
  identity.orientation.w = 1.0;
  server_.setPose(style_.marker_name, identity);
  if (paper_changed_)
    showPaper();
  else
    server_.applyChanges();
  if (slider_changed_ && !slider_dragging_)
    showSlider();
  showPicks();  // the clearing above took the marks with it
}

std::string InteractionNode::click()
{
  const int named = namedAxis();
  std::string message;
  if (crease_at_press_ >= 0 && crease_at_press_ != named)
  {
    named_axis_ = paper_->edges[crease_at_press_].vertices;
    message = "The axis: this crease. Drag a part of the paper to turn it about the crease; click off the "
              "creases for the automatic axis.";
  }
  else if (named >= 0)
  {
    named_axis_ = { -1, -1 };
    message = "The automatic axis again.";
  }
  else if (!ring_)
    message = ring_refusal_;
  showMarkers(clearedMarkers(style_, ros::Time::now()));
  return message;
}

int InteractionNode::turningFace() const
{
  // rotate turns a face about a crease of its own: about a crease named elsewhere, the face
  // of the flap next to it.
  const core::Edge& hinge = paper_->edges[ring_->axis_edge];
  if (hinge.faces[0] == ring_->face || hinge.faces[1] == ring_->face)
    return ring_->face;
  for (int f : hinge.faces)
    if (std::count(ring_->moving_faces.begin(), ring_->moving_faces.end(), f))
      return f;
  return ring_->face;
}

int InteractionNode::namedAxis() const
{
  if (!paper_ || named_axis_[0] < 0)
    return -1;
  for (size_t e = 0; e < paper_->edges.size(); ++e)
  {
    const core::Edge& edge = paper_->edges[e];
    if (edge.isCrease() && ((edge.vertices[0] == named_axis_[0] && edge.vertices[1] == named_axis_[1]) ||
                            (edge.vertices[0] == named_axis_[1] && edge.vertices[1] == named_axis_[0])))
      return static_cast<int>(e);
  }
  return -1;
}

void InteractionNode::showMarkers(visualization_msgs::MarkerArray array)
{
  const int named = mode_ == Mode::Rotate ? namedAxis() : -1;
  if (named >= 0)
  {
    const core::Edge& edge = paper_->edges[named];
    const visualization_msgs::MarkerArray axis = namedAxisMarkers(
        paper_->vertices[edge.vertices[0]].folded, paper_->vertices[edge.vertices[1]].folded, style_, ros::Time::now());
    array.markers.insert(array.markers.end(), axis.markers.begin(), axis.markers.end());
  }
  markers_pub_.publish(array);
}

void InteractionNode::menu(Action action, const Feedback& feedback)
{
  const core::Vec3 at = feedback.mouse_point_valid ? onSheet(feedback.mouse_point) : core::Vec3::Zero();
  std_srvs::Trigger trigger;
  std::string message;
  const auto triggered = [&](ros::ServiceClient& client) {
    if (call(client, trigger, message))
      message = trigger.response.message;
  };
  switch (action)
  {
    case Action::CreaseMode:
    case Action::RotateMode:
      setMode(action == Action::CreaseMode ? Mode::Crease : Mode::Rotate);
      message = mode_ == Mode::Crease ? "crease mode" : "rotate mode";
      break;
    case Action::Squash:
      triggered(squash_);
      break;
    case Action::Undo:
      triggered(undo_);
      break;
    case Action::Redo:
      triggered(redo_);
      break;
    case Action::Reset:
      triggered(reset_);
      break;
    case Action::Pin:
    case Action::Release: {
      if (!paper_ || !feedback.mouse_point_valid)
        break;
      // The vertex nearest the right-click: any vertex to pin, a pinned one to release.
      int nearest = -1;
      double best = 0.1 * paper_->scale();
      for (size_t v = 0; v < paper_->vertices.size(); ++v)
      {
        const bool candidate = action == Action::Pin || std::count(pinned_.begin(), pinned_.end(), v) > 0;
        const double d = (paper_->vertices[v].folded - at).norm();
        if (candidate && d < best)
        {
          best = d;
          nearest = static_cast<int>(v);
        }
      }
      if (nearest < 0)
      {
        message = action == Action::Pin ? "no vertex near the click" : "no pin near the click";
        break;
      }
      PinVertex pin;
      pin.request.vertex = nearest;
      pin.request.release = action == Action::Release;
      if (call(pin_, pin, message))
        message = pin.response.message;
      break;
    }
    case Action::ColourByStrain:
      message = toggleStrainColours();
      break;
    case Action::FoldMode:
    case Action::DragMode:
      setMode(action == Action::FoldMode ? Mode::Fold : Mode::Drag);
      message = mode_ == Mode::Fold ? "Fold mode: click creases to mark them valley, mountain or unfold; click the face "
                                      "that stays; then Fold on the marked creases." :
                                      "Drag mode: press on a vertex and drag it.";
      break;
    case Action::NextLayer:
      press_camera_ = camera(feedback.header.stamp);
      message = nextLayer(surfacePoint(feedback));
      break;
    case Action::KeepFace: {
      press_camera_ = camera(feedback.header.stamp);
      const Mode was = mode_;
      mode_ = Mode::Fold;  // the face that stays belongs to the marks
      message = keepFaceAt(surfacePoint(feedback));
      if (was != Mode::Fold)
        setMode(Mode::Fold);
      break;
    }
    case Action::FoldFlat:
      message = startFold(M_PI);
      break;
    case Action::FoldRightAngle:
      message = startFold(M_PI / 2);
      break;
    case Action::ClearMarks:
      marks_.clear();
      keep_point_.reset();
      pick_ = Pick{};
      showPicks();
      message = "Marks cleared.";
      break;
    case Action::Snapping:
      snapping_ = !snapping_;
      showPaper();
      message = snapping_ ? "A drawn line snaps to vertices and divisions." : "A drawn line creases exactly as drawn.";
      break;
    case Action::PickedLayersOnly:
      picked_layers_only_ = !picked_layers_only_;
      showPaper();
      message = picked_layers_only_ ? "A turn carries the picked layers only." :
                                      "A turn carries the whole stack on the face.";
      break;
    case Action::FoldByAssignment:  // handled with its fraction in handleEvents
    case Action::None:
      break;
  }
  if (!message.empty() && (action == Action::NextLayer || action == Action::KeepFace))
    tellBeside(message);
  else if (!message.empty())
    tell(message, at);
}

core::SnapSettings InteractionNode::lineSnap() const
{
  core::SnapSettings settings = snap_;
  if (!snapping_)
    settings.radius = 0.0;
  return settings;
}

void InteractionNode::setMode(Mode mode)
{
  mode_ = mode;
  dragging_ = false;
  stopBending();
  turnViewBack();
  showPaper();
  showMarkers(clearedMarkers(style_, ros::Time::now()));
  showPicks();
}

void InteractionNode::tellBeside(const std::string& text)
{
  ROS_INFO("interaction: %s", text.c_str());
  message_ = forTheUser(text);
  const std::string lines = wrapLines(message_, kMessageWidth);
  if (paper_)
    markers_pub_.publish(messageMarker(lines, besideAnchor(*paper_, lines, style_), style_, ros::Time::now()));
}

void InteractionNode::tell(const std::string& text, const core::Vec3& at)
{
  ROS_INFO("interaction: %s", text.c_str());
  message_ = forTheUser(text);
  const std::string lines = wrapLines(message_, kMessageWidth);
  const core::Vec3 anchor = paper_ ? messageAnchor(*paper_, at, lines, style_) : at;
  markers_pub_.publish(messageMarker(lines, anchor, style_, ros::Time::now()));
}

void InteractionNode::publishStatus(const ros::TimerEvent&)
{
  if (!dragging_ && paper_ && camera(ros::Time::now()).has_value() != camera_known_)
    showPaper();  // rviz's camera came or went: the drag plane changes with it
  InteractionStatus status;
  status.header.stamp = ros::Time::now();
  status.mode = mode_ == Mode::Crease ? "crease" : mode_ == Mode::Rotate ? "rotate" : mode_ == Mode::Fold ? "fold" : "drag";
  const bool fresh = pick_.revision == revision_;
  status.picked_edge = fresh && pick_.kind == Pick::Kind::Crease ? pick_.current() : -1;
  status.picked_face = mode_ == Mode::Fold ? keptFace() : fresh && pick_.kind == Pick::Kind::Face ? pick_.current() : -1;
  status.picked_vertex = fresh && pick_.kind == Pick::Kind::Vertex ? pick_.current() : -1;
  status.bending = bending_;
  status.picked_layer = fresh && pick_.kind != Pick::Kind::None ? static_cast<uint32_t>(pick_.index + 1) : 0;
  status.layers = fresh ? static_cast<uint32_t>(pick_.candidates.size()) : 0;
  if (paper_)
    for (const auto& [edge, mark] : marks_.edges(*paper_))
    {
      status.marked_edges.push_back(edge);
      status.marked_angles.push_back(core::markAngle(mark));
    }
  status.dragging = dragging_ || slider_dragging_ || folding_.has_value();
  status.revision = revision_;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    status.feedback_received = received_;
    status.feedback_coalesced = coalesced_;
    status.pending = static_cast<uint32_t>(events_.size());
  }
  status.updates_applied = applied_;
  status.applied_stamp = applied_stamp_;
  status.apply_seconds = apply_seconds_;
  status.message = message_;
  status_pub_.publish(status);
}

}  // namespace virtual_origami

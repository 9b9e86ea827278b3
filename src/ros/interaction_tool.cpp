// The Fold tool's events (msg/ToolEvent.msg, from the rviz tool virtual_origami/Fold) onto the
// gesture model: the same calls the sheet marker's feedback and its menu make, so a gesture
// means the same whichever way it comes. The tool reports the line of sight through the mouse;
// RayPointer finds the paper on it as rviz finds the sheet marker.
#include <cmath>

#include <geometry_msgs/TransformStamped.h>
#include <tf2/exceptions.h>

#include "virtual_origami/ros/conversions.h"
#include "virtual_origami/ros/fold_slider.h"
#include "virtual_origami/ros/interaction_node.h"
#include "virtual_origami/ros/tool_keys.h"

namespace virtual_origami
{
namespace
{
/// Camera axes from the event's quaternion; from the ray alone (z along it) when the
/// quaternion is not one.
Eigen::Matrix3d cameraAxes(const geometry_msgs::Quaternion& q, const core::Vec3& ray)
{
  const Eigen::Quaterniond rotation(q.w, q.x, q.y, q.z);
  if (rotation.norm() > 1e-6 && std::isfinite(rotation.norm()))
    return rotation.normalized().toRotationMatrix();
  Eigen::Matrix3d axes;
  const core::Vec3 z = ray.normalized();
  const core::Vec3 x = (std::abs(z.z()) < 0.9 ? core::Vec3::UnitZ() : core::Vec3::UnitX()).cross(z).normalized();
  axes << x, z.cross(x), z;
  return axes;
}
}  // namespace

void InteractionNode::toolReceived(const ToolEvent::ConstPtr& event)
{
  std::lock_guard<std::mutex> lock(mutex_);
  ++received_;
  if (event->kind == ToolEvent::MOVE && !events_.empty() && events_.back().tool &&
      events_.back().tool->kind == ToolEvent::MOVE)
  {
    events_.back().tool = event;  // only the latest pointer matters
    ++coalesced_;
    return;
  }
  Event queued;
  queued.tool = event;
  events_.push_back(queued);
  promptLocked();
}

std::optional<core::SightRay> InteractionNode::sightRay(const ToolEvent& event) const
{
  core::SightRay ray;
  ray.camera.eye = toVec3(event.eye);
  ray.direction = core::Vec3(event.ray.x, event.ray.y, event.ray.z);
  ray.camera.axes = cameraAxes(event.camera, ray.direction);
  const std::string& frame = event.header.frame_id;
  if (!frame.empty() && frame != style_.frame_id)
  {
    geometry_msgs::TransformStamped t;
    try
    {
      t = tf_buffer_.lookupTransform(style_.frame_id, frame, ros::Time(0));
    }
    catch (const tf2::TransformException& e)
    {
      ROS_WARN_THROTTLE(5.0, "interaction: a Fold tool event in frame %s, not known in %s: %s", frame.c_str(),
                        style_.frame_id.c_str(), e.what());
      return std::nullopt;
    }
    const Eigen::Quaterniond r(t.transform.rotation.w, t.transform.rotation.x, t.transform.rotation.y,
                               t.transform.rotation.z);
    const Eigen::Matrix3d rotation = r.normalized().toRotationMatrix();
    const core::Vec3 shift(t.transform.translation.x, t.transform.translation.y, t.transform.translation.z);
    ray.camera.eye = rotation * ray.camera.eye + shift;
    ray.camera.axes = rotation * ray.camera.axes;
    ray.direction = rotation * ray.direction;
  }
  if (!ray.camera.eye.allFinite() || !ray.direction.allFinite() || ray.direction.norm() < 1e-12)
  {
    ROS_WARN_THROTTLE(5.0, "interaction: a Fold tool event without a line of sight");
    return std::nullopt;
  }
  ray.direction.normalize();
  return ray;
}

void InteractionNode::toolEvent(const ToolEvent& event)
{
  const std::optional<core::SightRay> ray = sightRay(event);
  if (!ray || !model_.paper())
  {
    if (event.kind == ToolEvent::RELEASE || event.kind == ToolEvent::CANCEL)
    {
      ray_pointer_.letGo();
      if (tool_sliding_)
        model_.slideRelease(model_.sliderFraction());
      tool_sliding_ = false;
    }
    return;
  }
  const core::Paper& paper = *model_.paper();
  const core::PickableSheet sheet{ model_.shownLift(), style_.margin };
  const core::Pointer at = core::RayPointer::at(paper, *ray, sheet);
  switch (event.kind)
  {
    case ToolEvent::PRESS:
      if (slider_shown_ && sliderOnRay(*ray, true))
      {
        tool_slide_from_ = model_.sliderFraction();
        model_.slidePress();
        tool_sliding_ = model_.state() == core::GestureState::Sliding;
        break;
      }
      model_.press(ray_pointer_.press(paper, *ray, sheet));
      if (!model_.dragging())
        ray_pointer_.letGo();  // off the paper: nothing held, as rviz sends the marker nothing
      break;
    case ToolEvent::MOVE:
      if (tool_sliding_)
      {
        if (const std::optional<double> fraction = sliderOnRay(*ray, false))
        {
          model_.slideMove(*fraction);
          placeSliderHandle(*fraction);
        }
      }
      else if (ray_pointer_.holding())
        model_.move(ray_pointer_.move(*ray));
      break;
    case ToolEvent::RELEASE:
      if (tool_sliding_)
      {
        tool_sliding_ = false;
        model_.slideRelease(sliderOnRay(*ray, false).value_or(model_.sliderFraction()));
        placeSliderHandle(model_.sliderFraction());
      }
      else if (ray_pointer_.holding())
        model_.release(ray_pointer_.release(paper, *ray, sheet));
      break;
    case ToolEvent::DOUBLE_CLICK:
      // Its first click came as a press and release (a face picked to stay, or a mark).
      if (!toolHolds())
        model_.foldMarks(M_PI, at);
      break;
    case ToolEvent::WHEEL:
      if (toolHolds() || event.wheel_delta == 0)
        break;
      if (at.mouse_point && event.wheel_delta > 0)  // turned away from the user: down
        model_.nextLayer(at);
      else if (at.mouse_point)
        model_.previousLayer(at);
      else
        tell(core::Message{ "Nothing under the pointer: the wheel walks through the layers under it.",
                            core::Vec3::Zero(), core::Message::Place::Beside });
      break;
    case ToolEvent::KEY:
      toolKey(event, at);
      break;
    case ToolEvent::CANCEL:
      cancelToolDrag(at);
      break;
    default:
      ROS_WARN_THROTTLE(5.0, "interaction: a Fold tool event of unknown kind %d", event.kind);
      break;
  }
}

void InteractionNode::toolKey(const ToolEvent& event, const core::Pointer& at)
{
  const ToolAction action = toolKeyAction(event.key, event.modifiers);
  if (action == ToolAction::None || (event.auto_repeat && !repeats(action)))
    return;
  if (action == ToolAction::Cancel)
  {
    cancelToolDrag(at);
    return;
  }
  if (toolHolds())
    return;  // the drag first: released or cancelled
  switch (action)
  {
    case ToolAction::NextLayer:
    case ToolAction::PreviousLayer:
      if (at.mouse_point && action == ToolAction::NextLayer)
        model_.nextLayer(at);
      else if (at.mouse_point)
        model_.previousLayer(at);
      else
        tell(core::Message{ "Nothing under the pointer: Tab walks through the layers under it.", core::Vec3::Zero(),
                            core::Message::Place::Beside });
      break;
    case ToolAction::FoldMarks:
      model_.foldMarks(M_PI, at);
      break;
    case ToolAction::Undo:
      model_.command(core::PaperCommand::Undo, at);
      break;
    case ToolAction::Redo:
      model_.command(core::PaperCommand::Redo, at);
      break;
    case ToolAction::CreaseMode:
      model_.chooseMode(core::GestureMode::Crease, at);
      break;
    case ToolAction::RotateMode:
      model_.chooseMode(core::GestureMode::Rotate, at);
      break;
    case ToolAction::FoldMode:
      model_.chooseMode(core::GestureMode::Fold, at);
      break;
    case ToolAction::DragMode:
      model_.chooseMode(core::GestureMode::Drag, at);
      break;
    case ToolAction::FlapMode:
      model_.chooseMode(core::GestureMode::Flap, at);
      break;
    default:
      break;
  }
}

void InteractionNode::cancelToolDrag(const core::Pointer& at)
{
  if (tool_sliding_)
  {
    // The handle back where it was pressed: its preview puts the paper back; no commit.
    tool_sliding_ = false;
    model_.slideMove(tool_slide_from_);
    model_.update();
    model_.chooseMode(model_.mode(), at);
    placeSliderHandle(model_.sliderFraction());
    tell(core::Message{ "Cancelled: nothing changed.", core::Vec3::Zero(), core::Message::Place::Slider });
    return;
  }
  if (!ray_pointer_.holding())
    return;
  ray_pointer_.letGo();
  if (!model_.dragging())
    return;
  core::Pointer back;  // the marker where the press grabbed it: no turn, the vertex where it lay
  back.camera = at.camera;
  model_.move(back);
  model_.update();
  model_.chooseMode(model_.mode(), at);
  tell(core::Message{ "Cancelled: nothing changed.", core::Vec3::Zero(), core::Message::Place::Beside });
}

std::optional<double> InteractionNode::sliderOnRay(const core::SightRay& ray, bool on_handle) const
{
  const double along = ray.direction.z();
  if (std::abs(along) < 1e-12)
    return std::nullopt;
  const double t = (track_.start.z() - ray.camera.eye.z()) / along;
  if (t <= 0)
    return std::nullopt;
  const core::Vec3 at = ray.camera.eye + t * ray.direction;
  if (on_handle)
  {
    const double reach = slider_style_.handle_size * (model_.paper() ? model_.paper()->scale() : 1.0);
    if ((at - sliderPoint(track_, model_.sliderFraction())).norm() > reach)
      return std::nullopt;
  }
  return sliderFraction(track_, at);
}

void InteractionNode::placeSliderHandle(double fraction)
{
  if (!slider_shown_)
    return;
  geometry_msgs::Pose pose;
  const core::Vec3 along = (track_.end - track_.start).normalized();
  const double yaw = std::atan2(along.y(), along.x());
  pose.position = toPoint(sliderPoint(track_, fraction));
  pose.orientation.z = std::sin(yaw / 2);
  pose.orientation.w = std::cos(yaw / 2);
  server_.setPose(slider_style_.marker_name, pose);
  server_.applyChanges();
}

}  // namespace virtual_origami

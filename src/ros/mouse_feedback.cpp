#include "virtual_origami/ros/mouse_feedback.h"

#include <cmath>

#include "virtual_origami/ros/conversions.h"

namespace virtual_origami
{
namespace
{
using visualization_msgs::InteractiveMarkerFeedback;

/// Where rviz reports a point of the sheet: on the pickable copy, `lift` over it, on the sight
/// line through it when the eye is known.
core::Vec3 lifted(const MouseGesture& g, const core::Vec3& p)
{
  return p + (g.eye ? Eigen::Vector3d(g.lift * (*g.eye - p).normalized()) : core::Vec3(0, 0, g.lift));
}

InteractiveMarkerFeedback event(const MouseGesture& g, uint8_t type, const core::Vec3& pointer, bool with_point,
                                const ros::Time& stamp)
{
  InteractiveMarkerFeedback f;
  f.header.frame_id = g.frame_id;
  f.header.stamp = stamp;
  f.client_id = g.client_id;
  f.marker_name = g.marker_name;
  f.control_name = "drag";
  f.event_type = type;
  // The marker sits at the origin until dragged; it moves with the point under the mouse: with
  // the eye known, on the drag plane through the grab point facing the eye (rviz's VIEW_FACING
  // plane), anywhere along the sight line through `pointer`.
  const core::Vec3 grab = lifted(g, g.press);
  core::Vec3 on_plane = lifted(g, pointer);
  if (g.eye && type != InteractiveMarkerFeedback::MENU_SELECT)
  {
    const core::Vec3 normal = (*g.eye - grab).normalized(), ray = pointer - *g.eye;
    if (std::abs(ray.dot(normal)) > 1e-9)
      on_plane = *g.eye + ((grab - *g.eye).dot(normal) / ray.dot(normal)) * ray;
  }
  f.pose.position = toPoint(on_plane - grab);
  f.pose.orientation.w = 1.0;
  f.mouse_point = toPoint(lifted(g, pointer));
  f.mouse_point_valid = with_point;
  return f;
}
}  // namespace

InteractiveMarkerFeedback MouseGesture::down(const ros::Time& stamp) const
{
  return event(*this, InteractiveMarkerFeedback::MOUSE_DOWN, press, true, stamp);
}

InteractiveMarkerFeedback MouseGesture::moveTo(const core::Vec3& at, const ros::Time& stamp) const
{
  return event(*this, InteractiveMarkerFeedback::POSE_UPDATE, at, false, stamp);
}

InteractiveMarkerFeedback MouseGesture::upAt(const core::Vec3& at, const ros::Time& stamp) const
{
  return event(*this, InteractiveMarkerFeedback::MOUSE_UP, at, true, stamp);
}

InteractiveMarkerFeedback MouseGesture::menu(uint32_t entry, const core::Vec3& at, const ros::Time& stamp) const
{
  InteractiveMarkerFeedback f = event(*this, InteractiveMarkerFeedback::MENU_SELECT, at, true, stamp);
  f.pose.position = toPoint(core::Vec3::Zero());
  f.menu_entry_id = entry;
  return f;
}

}  // namespace virtual_origami

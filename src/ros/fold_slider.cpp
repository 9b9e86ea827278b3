#include "virtual_origami/ros/fold_slider.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <visualization_msgs/InteractiveMarkerControl.h>

#include "virtual_origami/ros/conversions.h"
#include "virtual_origami/ros/markers.h"

namespace virtual_origami
{
namespace
{
using visualization_msgs::Marker;

Marker sliderPart(const SliderStyle& style, const ros::Time& stamp, const std::string& ns, int type)
{
  return baseMarker(style.frame_id, stamp, ns, type, style.line_width, rgba(0.25f, 0.25f, 0.3f));
}
}  // namespace

SliderTrack sliderTrack(const core::Paper& paper, const SliderStyle& style)
{
  if (paper.vertices.empty())
    return {};
  core::Vec2 lo = paper.vertices[0].crease_pattern, hi = lo;
  for (const core::Vertex& v : paper.vertices)
  {
    lo = lo.cwiseMin(v.crease_pattern);
    hi = hi.cwiseMax(v.crease_pattern);
  }
  const double y = lo.y() - style.gap * paper.scale();
  return { core::Vec3(lo.x(), y, 0.0), core::Vec3(hi.x(), y, 0.0) };
}

double sliderFraction(const SliderTrack& track, const core::Vec3& point)
{
  const core::Vec3 along = track.end - track.start;
  const double length2 = along.squaredNorm();
  if (!(length2 > 0) || !point.allFinite())
    return 0.0;
  return std::clamp(2.0 * (point - track.start).dot(along) / length2 - 1.0, -1.0, 1.0);
}

core::Vec3 sliderPoint(const SliderTrack& track, double fraction)
{
  return track.start + 0.5 * (std::clamp(fraction, -1.0, 1.0) + 1.0) * (track.end - track.start);
}

visualization_msgs::InteractiveMarker sliderHandle(const SliderTrack& track, double fraction, const SliderStyle& style)
{
  visualization_msgs::InteractiveMarker im;
  im.header.frame_id = style.frame_id;
  im.name = style.marker_name;
  im.description = "fold by assignment";
  im.pose.position = toPoint(sliderPoint(track, fraction));
  // The marker's x axis along the track: MOVE_AXIS moves along the control's x.
  const core::Vec3 along = (track.end - track.start).normalized();
  const double yaw = std::atan2(along.y(), along.x());
  im.pose.orientation.z = std::sin(yaw / 2);
  im.pose.orientation.w = std::cos(yaw / 2);
  im.scale = static_cast<float>(3 * style.handle_size);

  Marker handle;
  handle.type = Marker::CYLINDER;
  handle.pose.orientation.w = 1.0;
  handle.scale.x = handle.scale.y = style.handle_size;
  handle.scale.z = 0.5 * style.handle_size;
  handle.color = rgba(0.9f, 0.45f, 0.0f);

  visualization_msgs::InteractiveMarkerControl control;
  control.name = "slide";
  control.interaction_mode = visualization_msgs::InteractiveMarkerControl::MOVE_AXIS;
  control.orientation.w = 1.0;
  control.always_visible = true;
  control.markers.push_back(handle);
  im.controls.push_back(control);
  return im;
}

visualization_msgs::MarkerArray sliderMarkers(const SliderTrack& track, double fraction, const SliderStyle& style,
                                              const ros::Time& stamp)
{
  visualization_msgs::MarkerArray array;
  Marker line = sliderPart(style, stamp, "fold_slider_track", Marker::LINE_LIST);
  line.points = { toPoint(track.start), toPoint(track.end) };
  const core::Vec3 across = core::Vec3::UnitZ().cross(track.end - track.start).normalized() * style.handle_size * 0.4;
  for (int tick = -4; tick <= 4; ++tick)
  {
    const core::Vec3 at = sliderPoint(track, tick / 4.0);
    line.points.push_back(toPoint(at - across));
    line.points.push_back(toPoint(at + across));
  }
  array.markers.push_back(line);

  Marker text = sliderPart(style, stamp, "fold_slider_percent", Marker::TEXT_VIEW_FACING);
  text.scale.z = style.text_size;
  text.color = rgba(0.1f, 0.1f, 0.3f);
  char buffer[48];
  std::snprintf(buffer, sizeof buffer, "fold %.0f %%", 100.0 * std::clamp(fraction, -1.0, 1.0));
  text.text = buffer;
  text.pose.position = toPoint(sliderPoint(track, fraction) + core::Vec3(0, 0, 1.5 * style.text_size));
  array.markers.push_back(text);
  return array;
}

visualization_msgs::MarkerArray sliderRemoved(const SliderStyle& style, const ros::Time& stamp)
{
  visualization_msgs::MarkerArray array;
  for (const char* ns : { "fold_slider_track", "fold_slider_percent" })
  {
    Marker m = sliderPart(style, stamp, ns, Marker::LINE_LIST);
    m.action = Marker::DELETE;
    array.markers.push_back(m);
  }
  return array;
}

}  // namespace virtual_origami

// What rviz's Interact tool sends the interaction node for a mouse event on the sheet, so that
// tests and tools drive the node exactly as rviz does. Pure functions.
#pragma once

#include <optional>
#include <string>

#include <ros/time.h>
#include <visualization_msgs/InteractiveMarkerFeedback.h>

#include "virtual_origami/core/paper.h"

namespace virtual_origami
{
/// One mouse gesture on the sheet marker: the press point on the sheet, then the pointer on
/// the drag plane (the marker moves by pointer − press, as in rviz's MOVE_PLANE control).
struct MouseGesture
{
  std::string client_id = "/mouse";
  std::string frame_id = "paper";
  std::string marker_name = "paper";
  core::Vec3 press = core::Vec3::Zero();
  double lift = 0.0;  // how far above the sheet rviz sees the marker (its mesh's z on a flat sheet)
  /// rviz's eye, when the ViewCamera display broadcasts it: the press's mouse point then lies
  /// `lift` towards the eye (on the press's sight line), as rviz reports it on the pickable copy,
  /// and the marker moves on the drag plane facing the eye (the sheet marker's VIEW_FACING
  /// plane), to where the pointer's sight line meets it.
  std::optional<core::Vec3> eye;

  /// MOUSE_DOWN at the press, MOUSE_UP or POSE_UPDATE with the pointer at `at`, MENU_SELECT of
  /// menu entry `entry` with the right-click at `at`.
  visualization_msgs::InteractiveMarkerFeedback down(const ros::Time& stamp) const;
  visualization_msgs::InteractiveMarkerFeedback moveTo(const core::Vec3& at, const ros::Time& stamp) const;
  visualization_msgs::InteractiveMarkerFeedback upAt(const core::Vec3& at, const ros::Time& stamp) const;
  visualization_msgs::InteractiveMarkerFeedback menu(uint32_t entry, const core::Vec3& at,
                                                     const ros::Time& stamp) const;
};

}  // namespace virtual_origami

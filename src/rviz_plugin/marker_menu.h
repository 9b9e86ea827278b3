// The context menu of one interactive marker (the interaction node's sheet, `paper`) as its
// server publishes it, for a tool that is not rviz's Interact tool: the entries are kept from the
// server's `update_full` and `update` topics (the same the InteractiveMarkers display reads, check
// marks in their titles), built into a QMenu on demand, and a choice goes back on the server's
// `feedback` topic as the MENU_SELECT that rviz's Interact tool sends.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include <QMenu>
#include <boost/shared_ptr.hpp>
#include <ros/ros.h>
#include <visualization_msgs/InteractiveMarker.h>
#include <visualization_msgs/InteractiveMarkerFeedback.h>
#include <visualization_msgs/InteractiveMarkerInit.h>
#include <visualization_msgs/InteractiveMarkerUpdate.h>

namespace virtual_origami::rviz_plugin
{
class MarkerMenu
{
public:
  /// Listens to the server whose update topic is `update_topic` (".../update"; its
  /// "update_full" and "feedback" beside it) for the marker `marker_name`; `client_id` names the
  /// sender of the feedback.
  void connect(ros::NodeHandle& nh, const std::string& update_topic, const std::string& marker_name,
               const std::string& client_id);

  /// Whether the marker and its menu are known.
  bool known() const
  {
    return !marker_.menu_entries.empty();
  }
  /// The frame the marker's points are given in (its header's frame).
  const std::string& frameId() const
  {
    return marker_.header.frame_id;
  }

  /// The menu as the server describes it (submenus for entries with children); `chosen` is
  /// called with the id of the entry the user picks.
  boost::shared_ptr<QMenu> build(const std::function<void(uint32_t)>& chosen) const;

  /// The MENU_SELECT feedback for entry `id`, right-clicked at `point` (in frameId(); invalid:
  /// no point found under the mouse), as rviz's Interact tool fills it in.
  visualization_msgs::InteractiveMarkerFeedback selection(uint32_t id, const geometry_msgs::Point& point,
                                                          bool point_valid) const;
  void send(const visualization_msgs::InteractiveMarkerFeedback& feedback);

private:
  void take(const visualization_msgs::InteractiveMarker& marker);
  void addEntries(QMenu* menu, uint32_t parent, const std::function<void(uint32_t)>& chosen) const;

  std::string marker_name_, client_id_;
  ros::Subscriber full_sub_, update_sub_;
  ros::Publisher feedback_pub_;
  visualization_msgs::InteractiveMarker marker_;
};

/// The server's topic namespace from its update topic: "/origami/interaction/update" ->
/// "/origami/interaction"; a topic not ending in "/update" is the namespace itself.
std::string serverNamespace(const std::string& update_topic);

}  // namespace virtual_origami::rviz_plugin

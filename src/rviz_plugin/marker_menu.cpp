#include "marker_menu.h"

#include <QAction>

namespace virtual_origami::rviz_plugin
{
std::string serverNamespace(const std::string& update_topic)
{
  const std::string suffix = "/update";
  if (update_topic.size() > suffix.size() &&
      update_topic.compare(update_topic.size() - suffix.size(), suffix.size(), suffix) == 0)
    return update_topic.substr(0, update_topic.size() - suffix.size());
  return update_topic;
}

void MarkerMenu::connect(ros::NodeHandle& nh, const std::string& update_topic, const std::string& marker_name,
                         const std::string& client_id)
{
  marker_name_ = marker_name;
  client_id_ = client_id;
  marker_ = visualization_msgs::InteractiveMarker();
  const std::string ns = serverNamespace(update_topic);
  full_sub_ = nh.subscribe<visualization_msgs::InteractiveMarkerInit>(
      ns + "/update_full", 10, [this](const visualization_msgs::InteractiveMarkerInit::ConstPtr& init) {
        for (const auto& marker : init->markers)
          take(marker);
      });
  update_sub_ = nh.subscribe<visualization_msgs::InteractiveMarkerUpdate>(
      ns + "/update", 100, [this](const visualization_msgs::InteractiveMarkerUpdate::ConstPtr& update) {
        for (const auto& marker : update->markers)
          take(marker);
        for (const auto& erased : update->erases)
          if (erased == marker_name_)
            marker_ = visualization_msgs::InteractiveMarker();
      });
  feedback_pub_ = nh.advertise<visualization_msgs::InteractiveMarkerFeedback>(ns + "/feedback", 100);
}

void MarkerMenu::take(const visualization_msgs::InteractiveMarker& marker)
{
  if (marker.name == marker_name_)
    marker_ = marker;
}

void MarkerMenu::addEntries(QMenu* menu, uint32_t parent, const std::function<void(uint32_t)>& chosen) const
{
  for (const visualization_msgs::MenuEntry& entry : marker_.menu_entries)
  {
    if (entry.parent_id != parent)
      continue;
    const QString title = QString::fromStdString(entry.title);
    bool has_children = false;
    for (const visualization_msgs::MenuEntry& child : marker_.menu_entries)
      has_children = has_children || child.parent_id == entry.id;
    if (has_children)
      addEntries(menu->addMenu(title), entry.id, chosen);
    else if (entry.command_type == visualization_msgs::MenuEntry::FEEDBACK)
    {
      // interactive_markers' MenuHandler writes a check box as "[x] " or "[ ] " before the title.
      const bool checked = title.startsWith("[x] "), unchecked = title.startsWith("[ ] ");
      QAction* action = menu->addAction(checked || unchecked ? title.mid(4) : title);
      action->setCheckable(checked || unchecked);
      action->setChecked(checked);
      const uint32_t id = entry.id;
      QObject::connect(action, &QAction::triggered, [chosen, id] { chosen(id); });
    }
  }
}

boost::shared_ptr<QMenu> MarkerMenu::build(const std::function<void(uint32_t)>& chosen) const
{
  boost::shared_ptr<QMenu> menu(new QMenu());
  addEntries(menu.get(), 0, chosen);
  return menu;
}

visualization_msgs::InteractiveMarkerFeedback MarkerMenu::selection(uint32_t id, const geometry_msgs::Point& point,
                                                                    bool point_valid) const
{
  visualization_msgs::InteractiveMarkerFeedback f;
  f.header.frame_id = marker_.header.frame_id;
  f.header.stamp = marker_.header.stamp;
  f.client_id = client_id_;
  f.marker_name = marker_.name;
  f.control_name = marker_.controls.empty() ? "" : marker_.controls.front().name;
  f.event_type = visualization_msgs::InteractiveMarkerFeedback::MENU_SELECT;
  f.pose = marker_.pose;
  f.menu_entry_id = id;
  f.mouse_point = point;
  f.mouse_point_valid = point_valid;
  return f;
}

void MarkerMenu::send(const visualization_msgs::InteractiveMarkerFeedback& feedback)
{
  feedback_pub_.publish(feedback);
}

}  // namespace virtual_origami::rviz_plugin

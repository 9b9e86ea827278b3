// rviz display `virtual_origami/ViewCamera`: rviz's view camera for nodes that need it. rviz
// tells an interactive marker server nothing about its camera; the interaction node needs the
// eye to follow the pointer from any view, to crease through stacked layers along the line of
// sight, and to turn the view while a face turns (seed 000 Fig. 11).
//  - broadcasts the camera as the tf frame `Frame` (optical convention: x right, y down, z along
//    the line of sight) under the fixed frame, and its projection as a sensor_msgs/CameraInfo
//    (the render panel's size in pixels, K from the vertical field of view);
//  - takes view turns on `View Turn Topic` (geometry_msgs/PoseStamped): the camera pose to take
//    (in that convention, without roll), or an empty frame_id for the view the turn began
//    from. Orbit-like views (Focal Point, Yaw, Pitch, Distance) can be turned.
#pragma once

#include <memory>
#include <optional>

#include <OgreVector3.h>
#include <geometry_msgs/PoseStamped.h>
#include <ros/ros.h>
#include <rviz/display.h>

namespace tf2_ros
{
class TransformBroadcaster;
}
namespace rviz
{
class StringProperty;
class BoolProperty;
}  // namespace rviz

namespace virtual_origami::rviz_plugin
{
class ViewCameraDisplay : public rviz::Display
{
  Q_OBJECT
public:
  ViewCameraDisplay();
  ~ViewCameraDisplay() override;

  void update(float wall_dt, float ros_dt) override;

protected:
  void onInitialize() override;
  void onEnable() override;
  void onDisable() override;

private Q_SLOTS:
  void updateTopics();

private:
  void turn(const geometry_msgs::PoseStamped::ConstPtr& goal);
  void restoreView();

  rviz::StringProperty* frame_property_;
  rviz::StringProperty* info_topic_property_;
  rviz::StringProperty* turn_topic_property_;
  rviz::BoolProperty* turn_property_;
  std::unique_ptr<tf2_ros::TransformBroadcaster> broadcaster_;
  ros::Publisher info_pub_;
  ros::Subscriber turn_sub_;
  /// The view's Focal Point, Yaw, Pitch and Distance before a turn, to go back to.
  struct Saved
  {
    Ogre::Vector3 focal_point;
    float yaw, pitch, distance;
  };
  std::optional<Saved> saved_;
  uint32_t seq_ = 0;
};

}  // namespace virtual_origami::rviz_plugin

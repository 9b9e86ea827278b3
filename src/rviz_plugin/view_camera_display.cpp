#include "view_camera_display.h"

#include <cmath>

#include <OgreCamera.h>
#include <OgreSceneNode.h>
#include <OgreViewport.h>
#include <geometry_msgs/TransformStamped.h>
#include <pluginlib/class_list_macros.hpp>
#include <rviz/display_context.h>
#include <rviz/frame_manager.h>
#include <rviz/properties/bool_property.h>
#include <rviz/properties/string_property.h>
#include <rviz/properties/vector_property.h>
#include <rviz/render_panel.h>
#include <rviz/view_controller.h>
#include <rviz/view_manager.h>
#include <sensor_msgs/CameraInfo.h>
#include <tf2_ros/transform_broadcaster.h>

namespace virtual_origami::rviz_plugin
{
namespace
{
/// The child property of that name, or nullptr (subProp() answers a stand-in when there is none).
rviz::Property* child(rviz::Property* parent, const QString& name)
{
  for (int i = 0; parent && i < parent->numChildren(); ++i)
    if (parent->childAt(i)->getName() == name)
      return parent->childAt(i);
  return nullptr;
}

/// Ogre's camera looks along its -z with y up; the optical convention looks along z with y down.
const Ogre::Quaternion kToOptical(Ogre::Radian(M_PI), Ogre::Vector3::UNIT_X);
}  // namespace

ViewCameraDisplay::ViewCameraDisplay()
{
  frame_property_ = new rviz::StringProperty("Frame", "rviz_camera",
                                             "The tf frame broadcast for the view's camera (x right, y down, z "
                                             "along the line of sight), child of the fixed frame.",
                                             this);
  info_topic_property_ = new rviz::StringProperty("Camera Info Topic", "rviz_camera/camera_info",
                                                  "sensor_msgs/CameraInfo of the view: the render panel's size in "
                                                  "pixels and its pinhole projection.",
                                                  this, SLOT(updateTopics()));
  turn_property_ = new rviz::BoolProperty(
      "Turn View", true, "Let a node turn the view for a while (the interaction node, while a face turns).", this);
  turn_topic_property_ = new rviz::StringProperty("View Turn Topic", "/origami/view_turn",
                                                  "geometry_msgs/PoseStamped: the camera pose to take, or an empty "
                                                  "frame_id for the view before the turn.",
                                                  this, SLOT(updateTopics()));
}

ViewCameraDisplay::~ViewCameraDisplay() = default;

void ViewCameraDisplay::onInitialize()
{
  broadcaster_ = std::make_unique<tf2_ros::TransformBroadcaster>();
  updateTopics();
}

void ViewCameraDisplay::onEnable()
{
  updateTopics();
}

void ViewCameraDisplay::onDisable()
{
  restoreView();
  turn_sub_.shutdown();
  info_pub_.shutdown();
}

void ViewCameraDisplay::updateTopics()
{
  if (!context_ || !isEnabled())
    return;
  info_pub_ = update_nh_.advertise<sensor_msgs::CameraInfo>(info_topic_property_->getStdString(), 1);
  // update_nh_'s callbacks run in rviz's main thread, where the view may be changed.
  turn_sub_ = update_nh_.subscribe(turn_topic_property_->getStdString(), 10, &ViewCameraDisplay::turn, this);
}

void ViewCameraDisplay::update(float /*wall_dt*/, float /*ros_dt*/)
{
  rviz::ViewController* view = context_->getViewManager()->getCurrent();
  Ogre::Camera* camera = view ? view->getCamera() : nullptr;
  if (!camera)
    return;
  const ros::Time now = ros::Time::now();
  const Ogre::Vector3 p = camera->getDerivedPosition();
  const Ogre::Quaternion q = camera->getDerivedOrientation() * kToOptical;
  geometry_msgs::TransformStamped t;
  t.header.stamp = now;
  t.header.frame_id = context_->getFixedFrame().toStdString();
  t.child_frame_id = frame_property_->getStdString();
  t.transform.translation.x = p.x;
  t.transform.translation.y = p.y;
  t.transform.translation.z = p.z;
  t.transform.rotation.w = q.w;
  t.transform.rotation.x = q.x;
  t.transform.rotation.y = q.y;
  t.transform.rotation.z = q.z;
  broadcaster_->sendTransform(t);

  sensor_msgs::CameraInfo info;
  info.header = t.header;
  info.header.frame_id = t.child_frame_id;
  info.header.seq = ++seq_;
  const Ogre::Viewport* viewport = camera->getViewport();
  info.width = viewport ? static_cast<uint32_t>(viewport->getActualWidth()) : 0;
  info.height = viewport ? static_cast<uint32_t>(viewport->getActualHeight()) : 0;
  if (camera->getProjectionType() == Ogre::PT_PERSPECTIVE && info.height > 0)
  {
    const double f = 0.5 * info.height / std::tan(0.5 * camera->getFOVy().valueRadians());
    info.distortion_model = "plumb_bob";
    info.D.assign(5, 0.0);
    info.K = { f, 0, 0.5 * info.width, 0, f, 0.5 * info.height, 0, 0, 1 };
    info.R = { 1, 0, 0, 0, 1, 0, 0, 0, 1 };
    info.P = { f, 0, 0.5 * info.width, 0, 0, f, 0.5 * info.height, 0, 0, 0, 1, 0 };
  }
  info_pub_.publish(info);
  setStatus(rviz::StatusProperty::Ok, "Camera", QString("broadcast as ") + t.child_frame_id.c_str());
}

void ViewCameraDisplay::turn(const geometry_msgs::PoseStamped::ConstPtr& goal)
{
  if (!turn_property_->getBool())
    return;
  if (goal->header.frame_id.empty())
  {
    restoreView();
    return;
  }
  rviz::ViewController* view = context_->getViewManager()->getCurrent();
  rviz::Property* focal = child(view, "Focal Point");
  rviz::Property* yaw = child(view, "Yaw");
  rviz::Property* pitch = child(view, "Pitch");
  rviz::Property* distance = child(view, "Distance");
  auto* focal_vector = dynamic_cast<rviz::VectorProperty*>(focal);
  if (!focal_vector || !yaw || !pitch || !distance || !view->getCamera())
  {
    setStatus(rviz::StatusProperty::Warn, "View turn",
              "only an orbit view (Focal Point, Yaw, Pitch, Distance) can be turned");
    return;
  }
  Ogre::Vector3 eye;
  Ogre::Quaternion orientation;
  geometry_msgs::PoseStamped latest = *goal;
  latest.header.stamp = ros::Time();  // the goal holds in its frame as it is now
  if (!context_->getFrameManager()->transform(latest.header, latest.pose, eye, orientation))
  {
    setStatus(rviz::StatusProperty::Warn, "View turn", QString("no transform from ") + goal->header.frame_id.c_str());
    return;
  }
  if (!saved_)
    saved_ = Saved{ focal_vector->getVector(), yaw->getValue().toFloat(), pitch->getValue().toFloat(),
                    distance->getValue().toFloat() };
  const Ogre::Vector3 forward = orientation * Ogre::Vector3::UNIT_Z;  // optical z
  const float d = distance->getValue().toFloat();
  // The orbit's camera sits at focal + d (cos yaw cos pitch, sin yaw cos pitch, sin pitch), in the
  // frame of the view's target, whose position the camera's parent node carries.
  const Ogre::Vector3 target = view->getCamera()->getParentSceneNode() ?
                                   view->getCamera()->getParentSceneNode()->_getDerivedPosition() :
                                   Ogre::Vector3::ZERO;
  focal_vector->setVector(eye + d * forward - target);
  yaw->setValue(std::atan2(-forward.y, -forward.x));
  pitch->setValue(std::asin(std::max(-1.0f, std::min(1.0f, -forward.z))));
  setStatus(rviz::StatusProperty::Ok, "View turn", "turned");
  context_->queueRender();
}

void ViewCameraDisplay::restoreView()
{
  if (!saved_ || !context_)
    return;
  rviz::ViewController* view = context_->getViewManager()->getCurrent();
  if (auto* p = dynamic_cast<rviz::VectorProperty*>(child(view, "Focal Point")))
    p->setVector(saved_->focal_point);
  if (rviz::Property* p = child(view, "Yaw"))
    p->setValue(saved_->yaw);
  if (rviz::Property* p = child(view, "Pitch"))
    p->setValue(saved_->pitch);
  if (rviz::Property* p = child(view, "Distance"))
    p->setValue(saved_->distance);
  saved_.reset();
  setStatus(rviz::StatusProperty::Ok, "View turn", "back");
  context_->queueRender();
}

}  // namespace virtual_origami::rviz_plugin

PLUGINLIB_EXPORT_CLASS(virtual_origami::rviz_plugin::ViewCameraDisplay, rviz::Display)

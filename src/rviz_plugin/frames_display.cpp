#include "frames_display.h"

#include <algorithm>
#include <cmath>
#include <set>
#include <vector>

#include <OgreSceneManager.h>
#include <OgreSceneNode.h>
#include <pluginlib/class_list_macros.hpp>
#include <rviz/display_context.h>
#include <rviz/frame_manager.h>
#include <rviz/ogre_helpers/axes.h>
#include <rviz/ogre_helpers/movable_text.h>
#include <rviz/ogre_helpers/shape.h>
#include <rviz/properties/bool_property.h>
#include <rviz/properties/color_property.h>
#include <rviz/properties/float_property.h>
#include <rviz/properties/string_property.h>
#include <tf2_ros/buffer.h>

#include "unpickable.h"

namespace virtual_origami::rviz_plugin
{
FramesDisplay::FramesDisplay()
{
  pattern_property_ = new rviz::StringProperty("Frames", "world|paper|pin_.*",
                                               "The frames to show: a regular expression matched against the whole "
                                               "frame name. paper_model "
                                               "also broadcasts face_<i> per face (face_.* shows them).",
                                               this, SLOT(updatePattern()));
  length_property_ =
      new rviz::FloatProperty("Length", 0.06, "Length of each axis, in metres.", this, SLOT(updateLooks()));
  length_property_->setMin(0.0001);
  names_property_ =
      new rviz::BoolProperty("Show Names", true, "Name the frames (one name per place).", this, SLOT(updateLooks()));
  text_height_property_ =
      new rviz::FloatProperty("Text Height", 0.035, "Height of the names, in metres.", this, SLOT(updateLooks()));
  text_height_property_->setMin(0.0001);
  text_color_property_ =
      new rviz::ColorProperty("Text Color", QColor(40, 40, 40),
                              "Colour of the names (dark: the view's background is light).", this, SLOT(updateLooks()));
  updatePattern();
}

FramesDisplay::~FramesDisplay()
{
  clear();
}

void FramesDisplay::onInitialize()
{
  updatePattern();
}

void FramesDisplay::onEnable()
{
  scene_node_->setVisible(true);
  since_update_ = 1e9f;
}

void FramesDisplay::onDisable()
{
  scene_node_->setVisible(false);
  clear();
}

void FramesDisplay::reset()
{
  rviz::Display::reset();
  clear();
}

void FramesDisplay::updatePattern()
{
  try
  {
    pattern_ = std::regex(pattern_property_->getStdString());
    pattern_ok_ = true;
    if (context_)
      setStatus(rviz::StatusProperty::Ok, "Frames", "pattern OK");
  }
  catch (const std::regex_error& e)
  {
    pattern_ok_ = false;
    if (context_)
      setStatus(rviz::StatusProperty::Error, "Frames", QString("not a regular expression: ") + e.what());
  }
  clear();
  since_update_ = 1e9f;
}

void FramesDisplay::updateLooks()
{
  clear();
  since_update_ = 1e9f;
}

void FramesDisplay::clear()
{
  for (auto& [key, s] : shown_)
  {
    if (s.name_node)
    {
      s.name_node->detachAllObjects();
      scene_manager_->destroySceneNode(s.name_node);
    }
    delete s.name;
  }
  shown_.clear();
}

FramesDisplay::Shown& FramesDisplay::shown(const std::string& key)
{
  return shown_[key];
}

void FramesDisplay::update(float wall_dt, float /*ros_dt*/)
{
  since_update_ += wall_dt;
  if (since_update_ < 0.1f || !pattern_ok_)
    return;
  since_update_ = 0.0f;
  std::vector<std::string> frames;
  context_->getFrameManager()->getTF2BufferPtr()->_getFrameStrings(frames);
  std::sort(frames.begin(), frames.end());

  std::set<std::string> seen;
  std::map<std::string, std::pair<Ogre::Vector3, std::string>> places;  // names joined per place
  const float length = length_property_->getFloat();
  for (const std::string& frame : frames)
  {
    if (!std::regex_match(frame, pattern_))
      continue;
    Ogre::Vector3 position;
    Ogre::Quaternion orientation;
    if (!context_->getFrameManager()->getTransform(frame, ros::Time(), position, orientation))
      continue;
    const std::string key = "axes " + frame;
    seen.insert(key);
    Shown& s = shown(key);
    if (!s.axes)
    {
      s.axes = std::make_unique<rviz::Axes>(scene_manager_, scene_node_, length, 0.08f * length);
      for (rviz::Shape* shape : { s.axes->getXShape(), s.axes->getYShape(), s.axes->getZShape() })
        seeThroughForPicking(shape->getMaterial());
    }
    s.axes->setPosition(position);
    s.axes->setOrientation(orientation);
    // Frames at one place (world and paper at the sheet's corner) share one name.
    char place[96];
    std::snprintf(place, sizeof place, "%.4f %.4f %.4f", position.x, position.y, position.z);
    auto& [at, names] = places[place];
    at = position;
    names += (names.empty() ? "" : ", ") + frame;
  }
  if (names_property_->getBool())
  {
    const Ogre::ColourValue colour = text_color_property_->getOgreColor();
    for (const auto& [place, at_names] : places)
    {
      const std::string key = "name " + at_names.second + " at " + place;
      seen.insert(key);
      Shown& s = shown(key);
      if (!s.name)
      {
        s.name = new rviz::MovableText(at_names.second, "Liberation Sans", text_height_property_->getFloat(), colour);
        s.name->setTextAlignment(rviz::MovableText::H_CENTER, rviz::MovableText::V_ABOVE);
        seeThroughForPicking(s.name->getMaterial());
        s.name_node = scene_node_->createChildSceneNode();
        s.name_node->attachObject(s.name);
      }
      s.name_node->setPosition(at_names.first + Ogre::Vector3(0, 0, 1.2f * length));
    }
  }
  for (auto it = shown_.begin(); it != shown_.end();)
  {
    if (seen.count(it->first))
    {
      ++it;
      continue;
    }
    if (it->second.name_node)
    {
      it->second.name_node->detachAllObjects();
      scene_manager_->destroySceneNode(it->second.name_node);
    }
    delete it->second.name;
    it = shown_.erase(it);
  }
  context_->queueRender();
}

}  // namespace virtual_origami::rviz_plugin

PLUGINLIB_EXPORT_CLASS(virtual_origami::rviz_plugin::FramesDisplay, rviz::Display)

// rviz display `virtual_origami/Frames`: the tf frames a user of the paper wants to see (by
// default world, paper and the pins; not paper_model's frame per face), as axes with dark
// names, one name per place. Unlike rviz's TF display they never take a press: the Interact
// tool sees through them to the sheet.
#pragma once

#include <map>
#include <memory>
#include <regex>
#include <string>

#include <rviz/display.h>

namespace Ogre
{
class SceneNode;
}
namespace rviz
{
class Axes;
class BoolProperty;
class ColorProperty;
class FloatProperty;
class MovableText;
class StringProperty;
}  // namespace rviz

namespace virtual_origami::rviz_plugin
{
class FramesDisplay : public rviz::Display
{
  Q_OBJECT
public:
  FramesDisplay();
  ~FramesDisplay() override;

  void update(float wall_dt, float ros_dt) override;
  void reset() override;

protected:
  void onInitialize() override;
  void onEnable() override;
  void onDisable() override;

private Q_SLOTS:
  void updatePattern();
  void updateLooks();

private:
  struct Shown
  {
    std::unique_ptr<rviz::Axes> axes;
    Ogre::SceneNode* name_node = nullptr;
    rviz::MovableText* name = nullptr;
  };
  void clear();
  Shown& shown(const std::string& key);

  rviz::StringProperty* pattern_property_;
  rviz::FloatProperty* length_property_;
  rviz::BoolProperty* names_property_;
  rviz::FloatProperty* text_height_property_;
  rviz::ColorProperty* text_color_property_;
  std::regex pattern_;
  bool pattern_ok_ = true;
  float since_update_ = 1e9f;
  std::map<std::string, Shown> shown_;  // by frame name (axes) and by place (names)
};

}  // namespace virtual_origami::rviz_plugin

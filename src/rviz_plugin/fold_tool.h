// rviz tool `virtual_origami/Fold`: the mouse and the keyboard over the 3D view for the
// interaction node, beyond what interactive markers report (docs/INTERACTION.md, "The Fold
// tool"). While it is the current tool, a left press on the paper (on anything rviz picks there),
// the drag and the release, a double click, the wheel over the paper and keys go to the node as
// virtual_origami/ToolEvent on `Topic`, each with the line of sight through the mouse in the fixed
// frame; the node carries them out as it carries out the sheet marker's feedback. A right click
// on the paper opens the sheet marker's menu (marker_menu.h), chosen entries going back as rviz's
// Interact tool sends them. A press beside the paper, the middle button, a right drag and
// Ctrl+wheel move the view. The status line says what
// a click does, from the node's interaction_status. It draws nothing of its own.
#pragma once

#include <optional>
#include <string>

#include <QPoint>
#include <QPointer>
#include <QString>
#include <ros/ros.h>
#include <rviz/render_panel.h>
#include <rviz/tool.h>
#include <virtual_origami/InteractionStatus.h>
#include <virtual_origami/ToolEvent.h>

#include "marker_menu.h"

namespace Ogre
{
class Viewport;
}
namespace rviz
{
class StringProperty;
class ViewportMouseEvent;
}  // namespace rviz

namespace virtual_origami::rviz_plugin
{
class FoldTool : public rviz::Tool
{
  Q_OBJECT
public:
  FoldTool();
  ~FoldTool() override;

  void activate() override;
  void deactivate() override;
  int processMouseEvent(rviz::ViewportMouseEvent& event) override;
  int processKeyEvent(QKeyEvent* event, rviz::RenderPanel* panel) override;

protected:
  void onInitialize() override;
  /// On the render panel while active: Tab (which Qt would take to move the focus), Esc during a
  /// drag (which rviz would take to change the tool), and the focus leaving mid-drag.
  bool eventFilter(QObject* watched, QEvent* event) override;

private Q_SLOTS:
  void updateTopics();
  void updateMenuTopic();

private:
  /// What the held buttons do: nothing held, a gesture on the paper, or the view moving.
  enum class Held
  {
    None,
    Gesture,
    View,
  };
  /// Whether rviz picks anything at the pixel (the sheet marker, the drawn paper).
  bool overPaper(Ogre::Viewport* viewport, int x, int y) const;
  /// An event at pixel (x, y) of `viewport`, with its line of sight.
  ToolEvent event(uint8_t kind, Ogre::Viewport* viewport, int x, int y) const;
  void send(const ToolEvent& event);
  void sendKey(QKeyEvent* key, rviz::RenderPanel* panel);
  void cancel();
  /// The sheet marker's menu at pixel (x, y), where the right button was clicked.
  void showMenu(rviz::ViewportMouseEvent& event, int x, int y);
  void statusReceived(const InteractionStatus::ConstPtr& status);
  void showStatus();

  rviz::StringProperty* topic_property_;
  rviz::StringProperty* status_topic_property_;
  rviz::StringProperty* update_topic_property_;
  ros::NodeHandle nh_;
  ros::Publisher events_pub_;
  ros::Subscriber status_sub_;
  Held held_ = Held::None;
  bool active_ = false;
  QPointer<rviz::RenderPanel> filtered_panel_;  // gone with the window, maybe before the tool
  Ogre::Viewport* last_viewport_ = nullptr;
  int last_x_ = 0, last_y_ = 0;
  std::string hint_;
  MarkerMenu menu_;
  /// Where the right button went down over the paper: released there (within a few pixels) it
  /// opens the menu; moved further it was a drag of the view.
  std::optional<QPoint> right_press_;
};

}  // namespace virtual_origami::rviz_plugin

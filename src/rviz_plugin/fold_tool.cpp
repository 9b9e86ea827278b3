#include "fold_tool.h"

#include <OgreCamera.h>
#include <OgreRay.h>
#include <OgreViewport.h>
#include <QCursor>
#include <QKeyEvent>
#include <QKeySequence>
#include <rviz/display_context.h>
#include <rviz/frame_manager.h>
#include <rviz/load_resource.h>
#include <rviz/properties/string_property.h>
#include <rviz/render_panel.h>
#include <rviz/selection/selection_manager.h>
#include <rviz/view_controller.h>
#include <rviz/view_manager.h>
#include <rviz/viewport_mouse_event.h>

namespace virtual_origami::rviz_plugin
{
namespace
{
/// Ogre's camera looks along its -z with y up; the optical convention looks along z with y down.
const Ogre::Quaternion kToOptical(Ogre::Radian(M_PI), Ogre::Vector3::UNIT_X);
/// How far the mouse may move between the right button's press and release for a click (pixels,
/// each way): further, it was a drag of the view.
constexpr int kClickSlack = 3;
/// The interaction node's sheet marker, whose menu a right click opens.
const char* const kSheetMarker = "paper";

uint8_t modifierBits(Qt::KeyboardModifiers modifiers)
{
  return (modifiers & Qt::ShiftModifier ? ToolEvent::SHIFT : 0) |
         (modifiers & Qt::ControlModifier ? ToolEvent::CONTROL : 0) |
         (modifiers & Qt::AltModifier ? ToolEvent::ALT : 0);
}
}  // namespace

FoldTool::FoldTool()
{
  shortcut_key_ = 'f';
  topic_property_ = new rviz::StringProperty("Topic", "/origami/tool_events",
                                             "virtual_origami/ToolEvent for the interaction node: presses, drags, "
                                             "double clicks, the wheel and keys, with the line of sight.",
                                             getPropertyContainer(), SLOT(updateTopics()), this);
  status_topic_property_ = new rviz::StringProperty("Status Topic", "/origami/interaction_status",
                                                    "virtual_origami/InteractionStatus of the interaction node: its "
                                                    "hint is the status "
                                                    "line (what a click does).",
                                                    getPropertyContainer(), SLOT(updateTopics()), this);
  update_topic_property_ = new rviz::StringProperty("Update Topic", "/origami/interaction/update",
                                                    "The interaction node's interactive marker server (the "
                                                    "InteractiveMarkers display's Update "
                                                    "Topic): a right click on the paper opens its sheet's menu.",
                                                    getPropertyContainer(), SLOT(updateMenuTopic()), this);
}

FoldTool::~FoldTool()
{
  if (filtered_panel_)
    filtered_panel_->removeEventFilter(this);
}

void FoldTool::onInitialize()
{
  setIcon(rviz::loadPixmap("package://rviz/icons/classes/Interact.png"));
  setCursor(QCursor(Qt::CrossCursor));
  updateTopics();
  updateMenuTopic();
}

void FoldTool::updateTopics()
{
  events_pub_ = nh_.advertise<ToolEvent>(topic_property_->getStdString(), 100);
  status_sub_ = nh_.subscribe(status_topic_property_->getStdString(), 1, &FoldTool::statusReceived, this);
}

void FoldTool::updateMenuTopic()
{
  menu_.connect(nh_, update_topic_property_->getStdString(), kSheetMarker, ros::this_node::getName() + "/Fold");
}

void FoldTool::activate()
{
  active_ = true;
  held_ = Held::None;
  filtered_panel_ = context_->getViewManager()->getRenderPanel();
  if (filtered_panel_)
    filtered_panel_->installEventFilter(this);
  showStatus();
}

void FoldTool::deactivate()
{
  cancel();  // the tool put away mid-drag (Esc, a tool's key): the node lets go
  if (filtered_panel_)
    filtered_panel_->removeEventFilter(this);
  filtered_panel_ = nullptr;
  active_ = false;
}

bool FoldTool::overPaper(Ogre::Viewport* viewport, int x, int y) const
{
  rviz::M_Picked picked;
  context_->getSelectionManager()->pick(viewport, x, y, x + 1, y + 1, picked, true);
  return !picked.empty();
}

ToolEvent FoldTool::event(uint8_t kind, Ogre::Viewport* viewport, int x, int y) const
{
  ToolEvent e;
  e.header.stamp = ros::Time::now();
  e.header.frame_id = context_->getFixedFrame().toStdString();
  e.kind = kind;
  if (!viewport || !viewport->getCamera() || viewport->getActualWidth() <= 0 || viewport->getActualHeight() <= 0)
    return e;
  Ogre::Camera* camera = viewport->getCamera();
  // The scene's frame is the fixed frame. For an orthographic view the ray starts on the near
  // plane over the pixel: that is the eye for this line of sight.
  const Ogre::Ray ray = camera->getCameraToViewportRay(static_cast<float>(x) / viewport->getActualWidth(),
                                                       static_cast<float>(y) / viewport->getActualHeight());
  const Ogre::Quaternion q = camera->getDerivedOrientation() * kToOptical;
  e.eye.x = ray.getOrigin().x;
  e.eye.y = ray.getOrigin().y;
  e.eye.z = ray.getOrigin().z;
  e.camera.w = q.w;
  e.camera.x = q.x;
  e.camera.y = q.y;
  e.camera.z = q.z;
  e.ray.x = ray.getDirection().x;
  e.ray.y = ray.getDirection().y;
  e.ray.z = ray.getDirection().z;
  return e;
}

void FoldTool::send(const ToolEvent& event)
{
  events_pub_.publish(event);
}

void FoldTool::cancel()
{
  if (held_ != Held::Gesture)
    return;
  held_ = Held::None;
  send(event(ToolEvent::CANCEL, last_viewport_, last_x_, last_y_));
}

int FoldTool::processMouseEvent(rviz::ViewportMouseEvent& event)
{
  last_viewport_ = event.viewport;
  last_x_ = event.x;
  last_y_ = event.y;
  rviz::ViewController* view = event.panel->getViewController();
  const auto toView = [&] {
    if (view)
      view->handleMouseEvent(event);
  };
  switch (event.type)
  {
    case QEvent::MouseButtonPress:
      if (held_ == Held::None && event.acting_button == Qt::LeftButton && overPaper(event.viewport, event.x, event.y))
      {
        held_ = Held::Gesture;
        send(this->event(ToolEvent::PRESS, event.viewport, event.x, event.y));
      }
      else if (held_ != Held::Gesture)
      {
        // The right button on the paper may be a click for the menu: the view takes it all the
        // same (a right drag zooms), a click moves nothing.
        right_press_.reset();
        if (held_ == Held::None && event.acting_button == Qt::RightButton &&
            overPaper(event.viewport, event.x, event.y))
          right_press_ = QPoint(event.x, event.y);
        held_ = Held::View;
        toView();
      }
      break;
    case QEvent::MouseButtonDblClick:
      // Its first click came as a press and a release.
      if (held_ == Held::None && event.acting_button == Qt::LeftButton && overPaper(event.viewport, event.x, event.y))
        send(this->event(ToolEvent::DOUBLE_CLICK, event.viewport, event.x, event.y));
      break;
    case QEvent::MouseMove:
      if (held_ == Held::Gesture)
        send(this->event(ToolEvent::MOVE, event.viewport, event.x, event.y));
      else if (held_ == Held::View)
        toView();
      break;
    case QEvent::MouseButtonRelease:
      if (held_ == Held::Gesture && event.acting_button == Qt::LeftButton)
      {
        held_ = Held::None;
        send(this->event(ToolEvent::RELEASE, event.viewport, event.x, event.y));
      }
      else if (held_ == Held::View)
      {
        toView();
        if (!(event.buttons_down & (Qt::LeftButton | Qt::MiddleButton | Qt::RightButton)))
          held_ = Held::None;
        if (right_press_ && event.acting_button == Qt::RightButton &&
            std::abs(event.x - right_press_->x()) <= kClickSlack &&
            std::abs(event.y - right_press_->y()) <= kClickSlack)
          showMenu(event, right_press_->x(), right_press_->y());
        right_press_.reset();
      }
      break;
    case QEvent::Wheel:
      if (held_ == Held::None && !event.control() && overPaper(event.viewport, event.x, event.y))
      {
        ToolEvent e = this->event(ToolEvent::WHEEL, event.viewport, event.x, event.y);
        e.wheel_delta = event.wheel_delta;
        e.modifiers = modifierBits(event.modifiers);
        send(e);
      }
      else if (held_ != Held::Gesture)
        toView();
      break;
    default:
      break;
  }
  showStatus();
  return Render;
}

void FoldTool::showMenu(rviz::ViewportMouseEvent& event, int x, int y)
{
  if (!menu_.known())
  {
    setStatus(QString("Fold: no menu from the interaction node on %1.").arg(update_topic_property_->getString()));
    return;
  }
  // The point under the mouse in the marker's frame, as the Interact tool reports a right click.
  geometry_msgs::Point point;
  Ogre::Vector3 at, frame_position;
  Ogre::Quaternion frame_orientation;
  const bool valid =
      context_->getSelectionManager()->get3DPoint(event.viewport, x, y, at) &&
      context_->getFrameManager()->getTransform(menu_.frameId(), ros::Time(), frame_position, frame_orientation);
  if (valid)
  {
    const Ogre::Vector3 local = frame_orientation.Inverse() * (at - frame_position);
    point.x = local.x;
    point.y = local.y;
    point.z = local.z;
  }
  event.panel->showContextMenu(
      menu_.build([this, point, valid](uint32_t id) { menu_.send(menu_.selection(id, point, valid)); }));
}

void FoldTool::sendKey(QKeyEvent* key, rviz::RenderPanel* panel)
{
  // The pointer where the mouse is now (a key comes without one).
  Ogre::Viewport* viewport = panel ? panel->getViewport() : last_viewport_;
  int x = last_x_, y = last_y_;
  if (panel)
  {
    const QPoint at = panel->mapFromGlobal(QCursor::pos());
    x = at.x();
    y = at.y();
  }
  ToolEvent e = event(ToolEvent::KEY, viewport, x, y);
  e.key = QKeySequence(key->key()).toString().toStdString();
  e.modifiers = modifierBits(key->modifiers());
  e.auto_repeat = key->isAutoRepeat();
  send(e);
}

int FoldTool::processKeyEvent(QKeyEvent* event, rviz::RenderPanel* panel)
{
  const int k = event->key();
  if (k == Qt::Key_Shift || k == Qt::Key_Control || k == Qt::Key_Alt || k == Qt::Key_Meta)
    return 0;
  sendKey(event, panel);
  return Render;
}

bool FoldTool::eventFilter(QObject* watched, QEvent* event)
{
  if (!active_ || watched != filtered_panel_.data())
    return false;
  if (event->type() == QEvent::KeyPress)
  {
    auto* key = static_cast<QKeyEvent*>(event);
    if (key->key() == Qt::Key_Tab || key->key() == Qt::Key_Backtab)
    {
      sendKey(key, filtered_panel_);  // rather than Qt's focus moving on
      return true;
    }
    if (key->key() == Qt::Key_Escape && held_ == Held::Gesture)
    {
      cancel();  // rather than rviz's change to the default tool
      return true;
    }
  }
  else if (event->type() == QEvent::FocusOut)
    cancel();  // the release may never come here
  return false;
}

void FoldTool::statusReceived(const InteractionStatus::ConstPtr& status)
{
  hint_ = status->hint;
  showStatus();
}

void FoldTool::showStatus()
{
  if (!active_)
    return;
  setStatus(
      hint_.empty() ?
          QString("Fold: waiting for the interaction node's status on %1.").arg(status_topic_property_->getString()) :
          QString::fromStdString(hint_));
}

}  // namespace virtual_origami::rviz_plugin

#include <pluginlib/class_list_macros.hpp>
PLUGINLIB_EXPORT_CLASS(virtual_origami::rviz_plugin::FoldTool, rviz::Tool)

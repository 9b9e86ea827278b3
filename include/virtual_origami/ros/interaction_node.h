// The interaction node (SPEC §5): an interactive_markers server over the paper, the adapter of
// the gesture model (core/gesture_model.h). rviz's feedback on the sheet, on the fold slider
// beside it and from the right-click menu becomes the model's inputs; the model's requests
// become paper_model's service calls, and what it shows (the snapping guides, axis and ring
// while dragging, the marked creases, the picked layer, messages, the view turn) becomes
// markers. The services are the only way it changes the paper: previews while dragging or
// animating, one committed call on release. The Fold tool's events (`tool_events`: presses,
// drags, the wheel, keys, with the line of sight through the mouse) drive the same model.
#pragma once

#include <deque>
#include <functional>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include <dynamic_reconfigure/Config.h>
#include <interactive_markers/interactive_marker_server.h>
#include <interactive_markers/menu_handler.h>
#include <ros/ros.h>
#include <tf2_ros/buffer.h>
#include <tf2_ros/transform_listener.h>
#include <virtual_origami/PaperState.h>
#include <virtual_origami/ToolEvent.h>
#include <visualization_msgs/InteractiveMarkerFeedback.h>

#include "virtual_origami/core/gesture_model.h"
#include "virtual_origami/core/ray_pointer.h"
#include "virtual_origami/ros/fold_slider.h"
#include "virtual_origami/ros/interaction_markers.h"
#include "virtual_origami/ros/interaction_view.h"

namespace virtual_origami
{
class InteractionNode : private core::GestureOutputs
{
public:
  InteractionNode(ros::NodeHandle nh, ros::NodeHandle private_nh);

private:
  using Feedback = visualization_msgs::InteractiveMarkerFeedback;
  using MenuCallback = std::function<void(const Feedback&)>;
  struct Event
  {
    Feedback::ConstPtr feedback;
    MenuCallback chosen;       // a menu entry's; none for the sheet and the slider
    bool slider = false;       // from the fold slider's handle, not the sheet
    ToolEvent::ConstPtr tool;  // the Fold tool's, instead of feedback
  };
  /// A right-click menu entry: its title, its submenu (empty: top level), what it does and,
  /// for a checkbox, whether it is checked.
  struct MenuEntry
  {
    std::string title;
    std::string submenu;
    MenuCallback chosen;
    std::function<bool()> checked;
  };

  // The server's thread: only queue (a pose replaces the pose queued before it from the same
  // marker).
  void received(const Feedback::ConstPtr& feedback, MenuCallback chosen = {}, bool slider = false);
  /// The Fold tool's events, queued as feedback is (a move replaces the move queued before it).
  void toolReceived(const ToolEvent::ConstPtr& event);

  /// Has the node's thread take the queue at once, or once a period (1 / `update_rate`) has
  /// passed since it last took it (mutex_ held).
  void promptLocked();

  // The node's thread (interaction_node.cpp).
  /// The tick (`rate`): a step of a fold's animation, when nothing is queued.
  void handleEvents(const ros::TimerEvent&);
  /// Takes the queue (promptLocked) and applies it.
  void handlePrompt(const ros::TimerEvent&);
  void stateReceived(const PaperState::ConstPtr& state);
  void publishStatus(const ros::TimerEvent& = {});
  /// rviz's camera at `stamp` (the ViewCamera display's tf frame), when it is broadcast;
  /// the latest one when `stamp` is newer than what tf holds.
  std::optional<ViewCamera> camera(const ros::Time& stamp) const;
  /// The mouse as the model takes it.
  core::Pointer pointer(const Feedback& feedback) const;
  /// The right-click on the sheet (zero without a mouse point).
  core::Vec3 rightClick(const Feedback& feedback) const;
  void slide(const Feedback& feedback);

  // The Fold tool (interaction_tool.cpp).
  void toolEvent(const ToolEvent& event);
  /// The event's line of sight in the paper frame; none when tf cannot say where it lies.
  std::optional<core::SightRay> sightRay(const ToolEvent& event) const;
  void toolKey(const ToolEvent& event, const core::Pointer& at);
  /// The slider's fraction where the line of sight meets the track's plane; with `on_handle`
  /// only there within the handle's size of it (a press takes the handle).
  std::optional<double> sliderOnRay(const core::SightRay& ray, bool on_handle) const;
  /// The handle where the tool's drag has it (rviz moves it only for its own drags).
  void placeSliderHandle(double fraction);
  bool toolHolds() const
  {
    return ray_pointer_.holding() || tool_sliding_;
  }
  /// Lets go of the tool's drag: the pointer back where it grabbed (previews put the paper
  /// back), then the mode chosen again (nothing committed, the view turned back).
  void cancelToolDrag(const core::Pointer& at);

  // The menu (interaction_menu.cpp): the entries in their order, inserted into `menu_`.
  std::vector<MenuEntry> menuEntries();
  void buildMenu();
  void setCheckMarks();

  // The model's outputs (interaction_outputs.cpp).
  core::PaperReply send(const core::PaperRequest& request) override;
  void show(const core::GestureOutput& output) override;
  void showPaper();
  void showSlider();
  void tell(const core::Message& message);
  /// Asks paper_model to colour by strain, or not; what to tell the user.
  std::string toggleStrainColours();
  void strainColoursChanged(const dynamic_reconfigure::Config::ConstPtr& config);
  void curvedSheetReceived(const visualization_msgs::MarkerArray::ConstPtr& sheet);

  ros::NodeHandle nh_;
  InteractionStyle style_;
  std::string camera_frame_ = "rviz_camera";
  double camera_timeout_ = 2.0;  // a camera frame older than this (s) is rviz gone
  tf2_ros::Buffer tf_buffer_;
  tf2_ros::TransformListener tf_listener_;
  bool camera_known_ = false;  // when the sheet marker was last sent (its drag plane depends on it)
  core::GestureModel model_;

  interactive_markers::InteractiveMarkerServer server_;
  interactive_markers::MenuHandler menu_;
  std::vector<std::pair<interactive_markers::MenuHandler::EntryHandle, std::function<bool()>>> checkboxes_;
  ros::Subscriber state_sub_, strain_colours_sub_, curved_sheet_sub_, tool_sub_;
  ros::Publisher markers_pub_, status_pub_, view_turn_pub_, slider_pub_, curved_drag_pub_;
  ros::ServiceClient crease_, rotate_, squash_, undo_, redo_, reset_, keep_bend_, pin_, fold_, flat_fold_, drag_vertex_,
      paper_model_reconfigure_;
  /// The slider's previews on one kept connection (a new one per call cost 0.6–3 ms of each
  /// preview); opened again when paper_model went away.
  ros::ServiceClient fold_previews_;
  ros::Timer timer_, status_timer_;
  ros::Timer prompt_timer_;  // one-shot, started by the first event queued after the queue was taken

  std::mutex mutex_;  // guards the queue and the counters the server's thread writes
  std::deque<Event> events_;
  bool prompted_ = false;            // prompt_timer_ runs
  double period_ = 1.0 / 30;         // 1 / `rate`: the fold animation's tick
  double update_period_ = 1.0 / 60;  // 1 / `update_rate`: the queue is taken no more often
  double taken_at_ = 0.0;            // wall seconds when the queue was last taken
  uint64_t received_ = 0, coalesced_ = 0;

  core::RayPointer ray_pointer_;  // the Fold tool's held press
  bool tool_sliding_ = false;     // the Fold tool holds the slider's handle
  double tool_slide_from_ = 0.0;  // the fraction the handle was pressed at

  // The fold slider: drawn here, driven by the model.
  bool slider_enabled_ = true;
  SliderStyle slider_style_;
  SliderTrack track_;
  bool slider_shown_ = false;
  bool colour_by_strain_ = false;  // as paper_model's dynamic_reconfigure says

  ros::Time applied_stamp_;  // the pointer's stamp when the model last applied a drag
  double apply_seconds_ = 0.0;
  std::string message_;
};

}  // namespace virtual_origami

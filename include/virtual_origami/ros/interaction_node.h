// The interaction node (SPEC §5): an interactive_markers server over the paper. Mouse
// presses and drags in rviz become crease, rotate, flat fold and vertex drag requests to
// paper_model, with the snapping guides, axis and ring drawn while dragging, the marked creases
// in colour and the picked layer outlined; a right-click menu switches modes and asks for
// squash, undo, redo, reset, pins, the next layer down, folds on the marked creases, folds by
// assignment and strain colours. Beside the sheet a slider folds a loaded crease pattern by
// assignment. The services are the only way it changes the paper: previews while dragging or
// animating, one committed call on release.
#pragma once

#include <array>
#include <deque>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include <dynamic_reconfigure/Config.h>
#include <geometry_msgs/PoseStamped.h>
#include <interactive_markers/interactive_marker_server.h>
#include <interactive_markers/menu_handler.h>
#include <ros/ros.h>
#include <tf2_ros/buffer.h>
#include <tf2_ros/transform_listener.h>
#include <virtual_origami/PaperState.h>
#include <visualization_msgs/InteractiveMarkerFeedback.h>

#include "virtual_origami/core/chosen_creases.h"
#include "virtual_origami/core/drag.h"
#include "virtual_origami/ros/fold_slider.h"
#include "virtual_origami/ros/interaction_markers.h"
#include "virtual_origami/ros/interaction_view.h"

namespace virtual_origami
{
class InteractionNode
{
public:
  InteractionNode(ros::NodeHandle nh, ros::NodeHandle private_nh);

  enum class Mode
  {
    Crease,
    Rotate,
    Fold,  // mark creases, pick the face that stays, fold flat (SPEC §3.7)
    Drag,  // drag a vertex (SPEC §3.6)
  };
  enum class Action
  {
    None,
    CreaseMode,
    RotateMode,
    Squash,
    Undo,
    Redo,
    Reset,
    Pin,
    Release,
    FoldByAssignment,
    ColourByStrain,
    FoldMode,
    DragMode,
    NextLayer,
    KeepFace,
    FoldFlat,
    FoldRightAngle,
    ClearMarks,
    PickedLayersOnly,
    Snapping,
  };

private:
  using Feedback = visualization_msgs::InteractiveMarkerFeedback;
  struct Event
  {
    Feedback::ConstPtr feedback;
    Action action = Action::None;  // a menu entry
    bool slider = false;           // from the fold slider's handle, not the sheet
    double fraction = 0.0;         // FoldByAssignment: how far
  };

  // The server's thread: only queue (a pose replaces the pose queued before it from the same
  // marker).
  void received(const Feedback::ConstPtr& feedback, Action action, bool slider = false, double fraction = 0.0);

  // The node's thread.
  void handleEvents(const ros::TimerEvent&);
  void stateReceived(const PaperState::ConstPtr& state);
  /// A point rviz reports on the (lifted) sheet marker, brought down onto the sheet.
  core::Vec3 onSheet(const geometry_msgs::Point& mouse_point) const;
  /// rviz's camera at `stamp` (the ViewCamera display's tf frame), when it is broadcast;
  /// the latest one when `stamp` is newer than what tf holds.
  std::optional<ViewCamera> camera(const ros::Time& stamp) const;
  /// The lowest height of the paper: the table it lies on (the margin's plane).
  double tableHeight() const;
  /// The line of sight through `point`: from the camera, or `view_direction` without one.
  core::Vec3 sight(const std::optional<ViewCamera>& camera, const core::Vec3& point) const;
  /// Where the crease being drawn ends: the pointer on the plane of the pressed face, seen
  /// from the eye (on the drag plane without a camera).
  core::Vec3 creaseEnd() const;
  /// The seed's view turn for the ring just pressed (rviz turns it back on release).
  void turnView();
  void turnViewBack();
  void press(const Feedback& feedback);
  void move(const Feedback& feedback);
  void release();
  void updateDrag();
  /// A press and release without a drag in rotate mode: on a crease it names the axis, off
  /// every crease it goes back to the automatic axis.
  std::string click();  // what to tell the user
  /// The face the rotate requests name: the pressed one, or about a crease named elsewhere
  /// the face of the turning flap next to it.
  int turningFace() const;
  /// The named axis, found again after a change (its end vertices keep their ids); -1 if gone.
  int namedAxis() const;
  /// The drag's markers (or none) with the named axis highlighted.
  void showMarkers(visualization_msgs::MarkerArray array);
  void menu(Action action, const Feedback& feedback);
  void setMode(Mode mode);
  void showPaper();
  void tell(const std::string& text, const core::Vec3& at);
  /// Says what a click or the menu picked, beside the paper (a text over the paper would take
  /// the next click there).
  void tellBeside(const std::string& text);
  void publishStatus(const ros::TimerEvent& = {});
  bool previewRotation(double angle);

  // Picking in a stack, folds on chosen creases and vertex drags (interaction_pick.cpp).
  /// What the last click picked and what lies under it, top layer first (layer_pick.h).
  struct Pick
  {
    enum class Kind
    {
      None,
      Crease,
      Face,
      Vertex,
    };
    Kind kind = Kind::None;
    core::Vec3 at = core::Vec3::Zero();
    std::vector<int> candidates;
    size_t index = 0;
    uint64_t revision = 0;
    int current() const
    {
      return kind == Kind::None || index >= candidates.size() ? -1 : candidates[index];
    }
  };
  /// The point on the paper a click or right-click at `feedback` is on (as a press finds it).
  core::Vec3 surfacePoint(const Feedback& feedback) const;
  /// The last pick of `kind`, when it is of this paper and `at` is where it was made.
  bool pickedHere(Pick::Kind kind, const core::Vec3& at) const;
  /// Fold mode: a click near a crease marks it (again: the next mark; where creases of several
  /// layers lie, the first click picks the top one), elsewhere it picks the face that stays.
  /// What to tell the user.
  std::string foldClick();
  std::string keepFaceAt(const core::Vec3& at);
  /// The next layer down under the last pick (or under `at`); what to tell the user.
  std::string nextLayer(const core::Vec3& at);
  /// The face the marks' fold keeps in place, or -1.
  int keptFace() const;
  /// Starts the animated fold on the marked creases to ±`angle`; what to tell the user.
  std::string startFold(double angle);
  /// The next frame of the animated fold; the last one commits it.
  void animateFold();
  bool previewFold(double fraction, std::string& message);
  /// Drag mode: the vertex under the press (or the one picked there), and its drag.
  void pressVertex();
  core::Vec3 vertexTarget() const;
  void updateVertexDrag();
  std::string releaseVertex();
  /// Where the faces cannot follow flat but bent paper reaches, the curved model takes the
  /// drag over (SPEC §4.3): the vertex held at `target` on `curved_drag`, the bent sheet shown.
  void bend(const core::Vec3& target);
  /// The curved model lets go: the bent sheet is hidden and springs back to the state.
  void stopBending();
  void curvedSheetReceived(const visualization_msgs::MarkerArray::ConstPtr& sheet);
  /// Marks, the face that stays and the picked layer, drawn.
  void showPicks();

  core::CreaseMarks marks_;
  std::optional<core::Vec2> keep_point_;  // the face that stays: a crease-pattern point inside it
  Pick pick_;
  bool picked_layers_only_ = false;  // a rotation turns the picked face's own layers only
  bool snapping_ = true;             // a drawn line snaps (Fig. 6); off: exactly as drawn
  /// The snapping a drawn line gets: none when switched off.
  core::SnapSettings lineSnap() const;
  std::optional<core::FlatFoldRequest> folding_;  // the fold being animated
  int fold_frame_ = 0;
  int fold_frames_ = 8;
  int dragged_vertex_ = -1;
  core::Vec3 vertex_at_press_ = core::Vec3::Zero();
  std::optional<core::Vec3> vertex_previewed_;  // the last target a preview took
  std::string vertex_refusal_;
  bool bending_ = false;  // the drag is the curved model's: rigid faces cannot follow there
  ros::Time bent_since_;
  ros::Publisher curved_drag_pub_;
  ros::Subscriber curved_sheet_sub_;
  interactive_markers::MenuHandler::EntryHandle fold_entry_ = 0, drag_entry_ = 0, layers_entry_ = 0,
                                                snap_entry_ = 0;
  ros::ServiceClient flat_fold_, drag_vertex_;

  // The fold slider (fold_slider.h).
  /// The handle where the paper is folded, or no slider for a paper without driven creases.
  void showSlider();
  void slide(const Feedback& feedback);
  /// The percent shown and, when it moved since the last one, a preview asked for.
  void updateSlider();
  void releaseSlider();
  /// Folds to `fraction` (committed); what to tell the user.
  std::string foldByAssignment(double fraction);
  /// Asks paper_model to colour by strain, or not; what to tell the user.
  std::string toggleStrainColours();
  void strainColoursChanged(const dynamic_reconfigure::Config::ConstPtr& config);

  ros::NodeHandle nh_;
  InteractionStyle style_;
  core::SnapSettings snap_;
  bool snap_radius_set_ = false;
  core::Vec3 view_direction_{ 0, 0, -1 };  // without a camera
  std::string camera_frame_ = "rviz_camera";
  double camera_timeout_ = 2.0;  // a camera frame older than this (s) is rviz gone
  bool view_turn_ = true;
  tf2_ros::Buffer tf_buffer_;
  tf2_ros::TransformListener tf_listener_;
  bool camera_known_ = false;  // when the sheet marker was last sent (its drag plane depends on it)
  double min_crease_length_ = 0.01;
  double layer_gap_ = 0.002;  // as paper_model draws coincident layers apart
  double pick_lift_ = 0.004;

  interactive_markers::InteractiveMarkerServer server_;
  interactive_markers::MenuHandler menu_;
  interactive_markers::MenuHandler::EntryHandle crease_entry_ = 0, rotate_entry_ = 0, strain_entry_ = 0;
  ros::Subscriber state_sub_, strain_colours_sub_;
  ros::Publisher markers_pub_, status_pub_, view_turn_pub_, slider_pub_;
  ros::ServiceClient crease_, rotate_, squash_, undo_, redo_, reset_, pin_, fold_, paper_model_reconfigure_;
  ros::Timer timer_, status_timer_;

  std::mutex mutex_;  // guards the queue and the counters the server's thread writes
  std::deque<Event> events_;
  uint64_t received_ = 0, coalesced_ = 0;

  Mode mode_ = Mode::Crease;
  std::optional<core::Paper> paper_;
  uint64_t revision_ = 0;
  std::vector<int> pinned_;
  bool paper_changed_ = false;  // a new state came during a drag: show it after the release

  // The drag in progress.
  bool dragging_ = false;
  bool moved_ = false;
  core::Vec3 press_ = core::Vec3::Zero(), pointer_ = core::Vec3::Zero();
  core::Vec3 grab_ = core::Vec3::Zero();  // where rviz grabbed the sheet marker: pointer_ is on the ray through it
  int press_face_ = -1;
  std::optional<ViewCamera> press_camera_;
  bool view_turned_ = false;
  core::Vec3 pose_at_press_ = core::Vec3::Zero();
  double reach_ = 0.0;  // how far the pointer went from the press: a click goes nowhere
  ros::Time pointer_stamp_;
  std::optional<core::RotationRing> ring_;
  std::string ring_refusal_;  // why the press turns nothing, said on release unless it names an axis
  int crease_at_press_ = -1;
  std::array<int, 2> named_axis_{ -1, -1 };  // the end vertices of the crease named by hand
  double angle_ = 0.0, previewed_angle_ = 0.0;
  bool previewed_ = false;

  // The fold slider.
  bool slider_enabled_ = true;
  SliderStyle slider_style_;
  SliderTrack track_;
  bool slider_shown_ = false;
  bool slider_changed_ = false;  // a new state came during a drag: show the slider after it
  bool slider_dragging_ = false, slider_moved_ = false;
  double slider_fraction_ = 0.0, fraction_at_press_ = 0.0;
  std::optional<double> slider_previewed_;  // the fraction last previewed in this drag
  std::string slider_refusal_;              // why the last preview was refused
  /// The fraction the slider committed and the revision it made: the handle stays there.
  std::optional<std::pair<uint64_t, double>> committed_fraction_;
  bool colour_by_strain_ = false;  // as paper_model's dynamic_reconfigure says

  uint64_t applied_ = 0;
  ros::Time applied_stamp_;
  double apply_seconds_ = 0.0;
  std::string message_;
};

}  // namespace virtual_origami

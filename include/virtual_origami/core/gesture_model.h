// The mouse gestures on the paper (SPEC §5), without ROS: presses, moves and releases on the
// sheet and on the fold slider, and the menu's choices, in; the requests to paper_model
// (gesture_requests.h) and what to draw (guides, picks, messages, the view turn) out, through
// GestureOutputs (gesture_outputs.h). One explicit state machine: what the mouse holds, entered and left in
// `enter` only. The interaction node is its adapter (ROS feedback in, service calls and markers
// out); tests drive it directly (gesture_model_test.cpp).
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "virtual_origami/core/chosen_creases.h"
#include "virtual_origami/core/compound_fold.h"
#include "virtual_origami/core/drag.h"
#include "virtual_origami/core/gesture_outputs.h"
#include "virtual_origami/core/gesture_requests.h"
#include "virtual_origami/core/paper.h"
#include "virtual_origami/core/snap.h"
#include "virtual_origami/core/view_camera.h"

namespace virtual_origami::core
{
/// What a drag on the sheet does.
enum class GestureMode
{
  Crease,  // draw a crease line
  Rotate,  // turn a face about a crease
  Fold,    // mark creases, pick the face that stays, fold (SPEC §3.7)
  Drag,    // drag a vertex (SPEC §3.6)
  Flap,    // drag a flap: the squash, petal or reverse fold it makes is inferred (compound_fold.h)
};
const char* modeName(GestureMode mode);  // "crease", "rotate", "fold", "drag", "flap"

/// What the mouse holds. Idle between gestures; one state per kind of drag. The transitions:
///   Idle --press--> DrawingLine | TurningFace | TurningNothing | PickingFold | HoldingVertex | DraggingFlap
///   HoldingVertex <--rigid faces follow / do not, bent paper does--> Bending
///   Idle --slider press--> Sliding;  Idle --Fold on the marked creases--> FoldingMarks
///   any --release, last frame, mode change--> Idle (a new press or input finishes the fold first)
/// Leaving Bending lets the curved model go; leaving a turn turns the view back (`enter`).
enum class GestureState
{
  Idle,
  DrawingLine,     // crease mode: the line from the press to the pointer
  TurningFace,     // rotate mode: the pressed face on its ring
  TurningNothing,  // rotate mode: a press no face turns from (a click names or frees the axis)
  PickingFold,     // fold mode: a press, a click marks a crease or picks the face that stays
  HoldingVertex,   // drag mode: the pressed vertex (or none) follows the pointer on rigid faces
  Bending,         // drag mode: the curved model holds the vertex where rigid faces cannot follow
  Sliding,         // the fold slider's handle
  FoldingMarks,    // the fold on the marked creases, animated frame by frame
  DraggingFlap,    // flap mode: the fold the pressed flap makes to the pointer, previewed
};

/// Where the mouse is, as rviz reports it on the sheet marker (in the paper frame).
struct Pointer
{
  std::optional<Vec3> mouse_point;      // the point under the mouse, when rviz found one
  Vec3 marker_position = Vec3::Zero();  // where the drag moved the sheet marker
  std::optional<ViewCamera> camera;     // rviz's camera at that moment, when it is known
};

struct GestureSettings
{
  SnapSettings snap;
  bool snap_radius_set = false;            // otherwise the radius follows the paper's scale
  double min_crease_length = 0.01;         // of the paper's scale: a shorter drag is a click
  double layer_gap = 0.002;                // as paper_model draws coincident layers apart
  int fold_frames = 8;                     // frames of the animated fold on the marked creases
  bool view_turn = true;                   // the seed's view turn in rotate mode
  Vec3 view_direction{ 0, 0, -1 };         // without a camera
  GestureMode mode = GestureMode::Crease;  // at the start
  // The slider held still this long (s) after its last move: its previews catch up with it.
  double slider_catch_up_after = 0.1;
};

/// What the interaction status reports of the gestures.
struct GestureStatus
{
  int picked_edge = -1, picked_face = -1, picked_vertex = -1;
  uint32_t picked_layer = 0, layers = 0;
  std::vector<int> marked_edges;
  std::vector<double> marked_angles;
  bool bending = false, dragging = false;
};

class GestureModel
{
public:
  /// `clock`: seconds, for the time in state.
  GestureModel(GestureSettings settings, GestureOutputs& outputs, std::function<double()> clock);

  // Inputs.
  /// A new state of the paper (its revision and pinned vertices).
  void paperChanged(Paper paper, uint64_t revision, std::vector<int> pinned);
  void press(const Pointer& pointer);
  /// The pointer moved: taken up by the next `update` (moves coalesce).
  void move(const Pointer& pointer);
  void release(const Pointer& pointer);
  /// Applies the latest move: the guides, and the preview it asks for.
  void update();
  /// The slider's handle pressed, moved to and released at a fraction.
  void slidePress();
  void slideMove(double fraction);
  void slideRelease(double fraction);
  /// The slider's handle held still (`slider_catch_up_after` since its last move): one more
  /// preview at its fraction while the previews fall behind it and still come nearer.
  /// A fast slide's frames (one solver step each) lag the handle; while it rests they go on to
  /// it, so the paper shown comes to where the handle is and its release has less left to fold.
  /// True when it asked for a preview.
  bool catchUpSlider();
  /// The next frame of the animated fold; `finishFold`: all the frames left, at once.
  void tick();
  void finishFold();

  // The menu's choices; `at` is the right-click.
  void chooseMode(GestureMode mode, const Pointer& at);
  void command(PaperCommand command, const Pointer& at);
  /// Pins the vertex nearest the right-click, or releases the pin nearest it.
  void pin(const Pointer& at, bool release);
  void foldByAssignment(double fraction, const Pointer& at);
  /// The next layer down under the last pick (or under the right-click).
  void nextLayer(const Pointer& at);
  /// The next layer up under the last pick; with nothing picked there, the bottom layer; from the
  /// top layer none.
  void previousLayer(const Pointer& at);
  void keepFace(const Pointer& at);
  /// Starts the animated fold on the marked creases to ±`angle` (π: flat; π/2: a right angle).
  void foldMarks(double angle, const Pointer& at);
  void clearMarks(const Pointer& at);
  void toggleSnapping(const Pointer& at);
  /// Fold-by-assignment commits (the slider's release, the menu's fractions) keep a state the
  /// service would refuse as wrong for paper (strained, crossing), as Origami Simulator shows it.
  void toggleKeepRefusedFolds(const Pointer& at);
  void togglePickedLayersOnly(const Pointer& at);
  /// A flap dragged over a line makes the outside reverse fold (the tip wrapped round the
  /// layers) instead of the inside one (turned in between them).
  void toggleOutsideReverse(const Pointer& at);
  /// A bent drag let go keeps the bend (the curved model's sheet becomes the paper's state)
  /// instead of springing back.
  void toggleKeepBend(const Pointer& at);
  /// The sheet marker changed for another reason (strain colours): sent now or after the drag.
  void refreshSheet();

  // What the node shows.
  GestureMode mode() const
  {
    return mode_;
  }
  GestureState state() const
  {
    return state_;
  }
  double timeInState() const;
  bool snapping() const
  {
    return snapping_;
  }
  bool keepRefusedFolds() const
  {
    return keep_refused_folds_;
  }
  bool outsideReverse() const
  {
    return outside_reverse_;
  }
  bool keepBend() const
  {
    return keep_bend_;
  }
  bool pickedLayersOnly() const
  {
    return picked_layers_only_;
  }
  bool dragging() const;  // a drag on the sheet (not the slider, not the fold's animation)
  const std::optional<Paper>& paper() const
  {
    return paper_;
  }
  uint64_t revision() const
  {
    return revision_;
  }
  /// How high paper_model draws the top layer.
  double drawnTop() const
  {
    return drawn_top_;
  }
  /// The sheet marker's lift when it was last shown: where rviz reports mouse points.
  double shownLift() const
  {
    return shown_lift_;
  }
  /// Where the slider's handle stays: the fraction last committed here, or the paper's own.
  double sliderFraction() const
  {
    return slider_fraction_;
  }
  /// Drag and slider updates applied (each a preview asked for, or guides drawn).
  uint64_t updates() const
  {
    return updates_;
  }
  GestureStatus status() const;

private:
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
    Vec3 at = Vec3::Zero();
    std::vector<int> candidates;
    size_t index = 0;
    uint64_t revision = 0;
    int current() const
    {
      return kind == Kind::None || index >= candidates.size() ? -1 : candidates[index];
    }
  };

  /// The one place the state changes: leaving Bending lets the curved model go, leaving a
  /// turn turns the view back.
  void enter(GestureState state);
  void emit(GestureOutput output)
  {
    outputs_.show(std::move(output));
  }
  void tell(const std::string& text, const Vec3& at)
  {
    emit(Message{ text, at, Message::Place::At });
  }
  void tellBeside(const std::string& text)
  {
    emit(Message{ text, Vec3::Zero(), Message::Place::Beside });
  }
  PaperReply send(const PaperRequest& request)
  {
    return outputs_.send(request);
  }
  /// A reply's message when it refuses or is not answered; empty when it succeeds.
  static std::string refusal(const PaperReply& reply)
  {
    return reply.success ? "" : reply.message;
  }

  // Points (gesture_model.cpp).
  Vec3 onSheet(const Vec3& mouse_point) const;
  Vec3 sight(const std::optional<ViewCamera>& camera, const Vec3& point) const;
  /// The point on the paper a click or right-click is on (as a press finds it).
  Vec3 surfacePoint(const Pointer& pointer) const;
  /// The right-click on the sheet (zero without a mouse point).
  Vec3 rightClick(const Pointer& at) const;
  double tableHeight() const;
  Vec3 creaseEnd() const;
  SnapSettings lineSnap() const;
  bool clicked() const
  {
    return reach_ < settings_.min_crease_length * paper_->scale();
  }

  void setMode(GestureMode mode);
  void showSheet();
  void showSlider();

  // Sheet drags (gesture_model.cpp).
  void updateDrag();
  void pressRotate();
  void updateRing();
  bool previewRotation(double angle);
  std::string releaseLine();
  std::string releaseTurn();
  std::string clickAxis();
  int turningFace() const;
  int namedAxis() const;
  void showGuides(Guides guides);
  void turnView();

  // Picks, marks and vertex drags (gesture_picks.cpp).
  bool pickedHere(Pick::Kind kind, const Vec3& at) const;
  std::string foldClick();
  std::string keepFaceAt(const Vec3& at);
  /// One layer down (`down`) or up from the pick at `at`; what to tell the user.
  std::string walkLayers(const Vec3& at, bool down);
  int keptFace() const;
  std::string startFold(double angle);
  bool previewFold(double fraction, std::string& message);
  void animateFold();
  void showPicks();
  void pressVertex();
  Vec3 vertexTarget() const;
  void updateVertexDrag();
  void bend(const Vec3& target);
  std::string releaseVertex(bool bent);

  // Folds by dragging a flap (gesture_flap.cpp).
  void pressFlap();
  /// The fold a resolved flap drag makes (the outside reverse fold when chosen) and its name.
  std::pair<const FlatFoldRequest*, CompoundKind> flapFold(const CompoundFolds::Resolved& fold) const;
  Vec3 flapTarget() const;
  void updateFlap();
  std::string releaseFlap();

  // The fold slider (gesture_slider.cpp).
  void updateSlider();
  /// Folds to `fraction` (committed); what to tell the user.
  std::string commitFold(double fraction);

  GestureSettings settings_;
  GestureOutputs& outputs_;
  std::function<double()> clock_;

  GestureState state_ = GestureState::Idle;
  double entered_ = 0.0;  // when the state was entered (clock seconds)
  GestureMode mode_ = GestureMode::Crease;
  bool snapping_ = true;             // a drawn line snaps (Fig. 6); off: exactly as drawn
  bool keep_bend_ = false;           // a bent drag let go keeps the bend
  bool keep_refused_folds_ = false;  // fold-by-assignment commits keep what the service would refuse
  bool picked_layers_only_ = false;  // a rotation turns the picked face's own layers only
  bool outside_reverse_ = false;     // a flap drag's reverse fold wraps the tip round the layers

  std::optional<Paper> paper_;
  uint64_t revision_ = 0;
  std::vector<int> pinned_;
  // The pickable copy floats over every drawn layer; rviz reports mouse points on the copy last shown.
  double pick_lift_ = 0.004, drawn_top_ = 0.0, shown_lift_ = 0.005;
  bool sheet_stale_ = false;   // a change came during a drag: the sheet is sent after it
  bool slider_stale_ = false;  // likewise the slider

  // The press and the pointer since.
  Vec3 press_ = Vec3::Zero(), pointer_ = Vec3::Zero();
  Vec3 grab_ = Vec3::Zero();  // where rviz grabbed the sheet marker: pointer_ is on the ray through it
  Vec3 pose_at_press_ = Vec3::Zero();
  int press_face_ = -1;
  std::optional<ViewCamera> press_camera_, pointer_camera_;
  double reach_ = 0.0;         // how far the pointer went from the press: a click goes nowhere
  bool move_pending_ = false;  // a move not yet taken up by `update`
  bool view_turned_ = false;

  // Rotate mode.
  std::optional<RotationRing> ring_;
  std::string ring_refusal_;  // why the press turns nothing, said on release unless it names an axis
  int crease_at_press_ = -1;
  std::array<int, 2> named_axis_{ -1, -1 };  // the end vertices of the crease named by hand
  double angle_ = 0.0;
  std::optional<double> previewed_angle_;

  // Fold mode and picks.
  CreaseMarks marks_;
  std::optional<Vec2> keep_point_;  // the face that stays: a crease-pattern point inside it
  Pick pick_;
  std::optional<FlatFoldRequest> folding_;  // the fold being animated
  int fold_frame_ = 0;

  // Drag mode.
  int dragged_vertex_ = -1;
  Vec3 vertex_at_press_ = Vec3::Zero();
  std::optional<Vec3> vertex_previewed_;  // the last target a preview took
  std::string vertex_refusal_;

  // Flap mode: the folds the pressed flap can make, and the one previewed (outcome, fraction).
  std::optional<CompoundFolds> flap_;
  std::string flap_refusal_;
  std::optional<std::pair<size_t, double>> flap_previewed_;

  // The fold slider.
  double slider_fraction_ = 0.0, fraction_at_press_ = 0.0;
  std::optional<double> slider_previewed_;  // the fraction last previewed in this drag
  double slider_moved_at_ = 0.0;            // clock seconds of the handle's last move
  // How far (rad, RMS) the nearest preview at the handle's fraction fell short of it, and how many
  // previews since came no nearer.
  double slider_behind_ = 0.0;
  int slider_stalled_ = 0;
  /// The fraction the slider committed and the revision it made: the handle stays there.
  std::optional<std::pair<uint64_t, double>> committed_fraction_;

  uint64_t updates_ = 0;
};

}  // namespace virtual_origami::core

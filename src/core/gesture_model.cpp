#include "virtual_origami/core/gesture_model.h"

#include <algorithm>
#include <cctype>
#include <cmath>

#include "virtual_origami/core/axis.h"
#include "virtual_origami/core/fold_fraction.h"
#include "virtual_origami/core/geometry.h"
#include "virtual_origami/core/layers.h"

namespace virtual_origami::core
{
namespace
{
/// A turn smaller than this (radians) is no turn: nothing is previewed or committed.
constexpr double kNoTurn = 1e-3;
}  // namespace

const char* modeName(GestureMode mode)
{
  switch (mode)
  {
    case GestureMode::Crease:
      return "crease";
    case GestureMode::Rotate:
      return "rotate";
    case GestureMode::Fold:
      return "fold";
    case GestureMode::Drag:
      return "drag";
    case GestureMode::Flap:
      return "flap";
  }
  return "";
}

GestureModel::GestureModel(GestureSettings settings, GestureOutputs& outputs, std::function<double()> clock)
  : settings_(std::move(settings)), outputs_(outputs), clock_(std::move(clock)), mode_(settings_.mode)
{
  settings_.fold_frames = std::max(1, settings_.fold_frames);
  entered_ = clock_();
}

void GestureModel::enter(GestureState state)
{
  if (state == state_)
    return;
  if (state_ == GestureState::Bending)
    emit(CurvedHold{});  // the curved model lets go; the bent sheet springs back to the state
  if (view_turned_)
  {
    emit(ViewTurn{});  // no camera: the view before the turn
    view_turned_ = false;
  }
  state_ = state;
  entered_ = clock_();
}

double GestureModel::timeInState() const
{
  return clock_() - entered_;
}

bool GestureModel::dragging() const
{
  return state_ != GestureState::Idle && state_ != GestureState::Sliding && state_ != GestureState::FoldingMarks;
}

void GestureModel::paperChanged(Paper paper, uint64_t revision, std::vector<int> pinned)
{
  paper_ = std::move(paper);
  revision_ = revision;
  pinned_ = std::move(pinned);
  if (!settings_.snap_radius_set)
    settings_.snap.radius = SnapSettings{}.radius * paper_->scale();
  const std::vector<int> levels = stackLevels(*paper_);
  const int top = levels.empty() ? 0 : *std::max_element(levels.begin(), levels.end());
  pick_lift_ = (top + 1) * settings_.layer_gap + 0.002 * paper_->scale();
  drawn_top_ = top * settings_.layer_gap;
  if (dragging() || state_ == GestureState::Sliding)
  {
    sheet_stale_ = true;  // re-sending a marker now would end the drag in rviz
    slider_stale_ = true;
  }
  else
  {
    showSheet();
    showSlider();
  }
  showPicks();
}

void GestureModel::refreshSheet()
{
  if (dragging() || state_ == GestureState::Sliding)
    sheet_stale_ = true;  // the sheet after the drag
  else
    showSheet();
}

void GestureModel::showSheet()
{
  if (!paper_)
    return;
  shown_lift_ = pick_lift_;
  sheet_stale_ = false;
  emit(SheetShown{});
}

void GestureModel::showSlider()
{
  slider_stale_ = false;
  if (!paper_)
    return;
  if (hasDrivenCreases(*paper_))  // without them there is no slider: it is taken away
    slider_fraction_ = committed_fraction_ && committed_fraction_->first == revision_ ? committed_fraction_->second :
                                                                                        foldFraction(*paper_);
  emit(SliderShown{});
}

Vec3 GestureModel::onSheet(const Vec3& mouse_point) const
{
  return mouse_point - Vec3(0, 0, shown_lift_);
}

Vec3 GestureModel::rightClick(const Pointer& at) const
{
  return at.mouse_point ? onSheet(*at.mouse_point) : Vec3::Zero();
}

Vec3 GestureModel::sight(const std::optional<ViewCamera>& camera, const Vec3& point) const
{
  if (camera)
  {
    const Vec3 ray = camera->rayTo(point);
    if (ray.allFinite())
      return ray;
  }
  return settings_.view_direction.normalized();
}

Vec3 GestureModel::surfacePoint(const Pointer& pointer) const
{
  if (!paper_ || !pointer.mouse_point)
    return Vec3::Zero();
  if (pointer.camera)
    return onSurface(*paper_, *pointer.mouse_point, sight(pointer.camera, *pointer.mouse_point));
  return onSurface(*paper_, onSheet(*pointer.mouse_point), settings_.view_direction);
}

double GestureModel::tableHeight() const
{
  double z = paper_->vertices.empty() ? 0.0 : paper_->vertices[0].folded.z();
  for (const Vertex& v : paper_->vertices)
    z = std::min(z, v.folded.z());
  return z;
}

Vec3 GestureModel::creaseEnd() const
{
  if (!pointer_camera_)
    return pointer_;
  // Off the paper (on the margin) the line is drawn on the table under it.
  const Vec3 normal = press_face_ >= 0 ? paper_->faceNormal(press_face_) : Vec3::UnitZ();
  return alongSightOnto(*pointer_camera_, pointer_, press_, normal).value_or(pointer_);
}

SnapSettings GestureModel::lineSnap() const
{
  SnapSettings snap = settings_.snap;
  if (!snapping_)
    snap.radius = 0.0;
  return snap;
}

void GestureModel::press(const Pointer& pointer)
{
  enter(GestureState::Idle);
  if (!paper_ || !pointer.mouse_point)
    return;
  press_camera_ = pointer_camera_ = pointer.camera;
  if (press_camera_)
  {
    // rviz's point lies on the pickable copy, a little towards the eye: along the sight line
    // onto the face the eye sees there.
    grab_ = *pointer.mouse_point;
    press_ = onSurface(*paper_, grab_, sight(press_camera_, grab_));
    if (press_ == grab_)  // on no face: on the margin, which lies on the table under the paper
      press_ = alongSightOnto(*press_camera_, grab_, Vec3(0, 0, tableHeight()), Vec3::UnitZ()).value_or(grab_);
  }
  else
    grab_ = press_ = onSurface(*paper_, onSheet(*pointer.mouse_point), settings_.view_direction);
  pointer_ = grab_;
  press_face_ = faceAt(*paper_, press_, 1e-6 * paper_->scale());
  pose_at_press_ = pointer.marker_position;
  angle_ = 0.0;
  previewed_angle_.reset();
  reach_ = 0.0;
  move_pending_ = false;
  ring_.reset();
  ring_refusal_.clear();
  crease_at_press_ = -1;
  switch (mode_)
  {
    case GestureMode::Crease:
      enter(GestureState::DrawingLine);
      break;
    case GestureMode::Rotate:
      pressRotate();
      break;
    case GestureMode::Fold:
      enter(GestureState::PickingFold);
      break;
    case GestureMode::Drag:
      enter(GestureState::HoldingVertex);
      pressVertex();
      break;
    case GestureMode::Flap:
      enter(GestureState::DraggingFlap);
      pressFlap();
      break;
  }
  if (state_ != GestureState::TurningNothing)  // the drag goes on in rviz, but turns nothing
    updateDrag();
}

void GestureModel::pressRotate()
{
  crease_at_press_ = creaseNear(*paper_, press_, settings_.snap.radius);
  // A layer picked here (Next layer down) turns instead of the top one.
  const int face = pickedHere(Pick::Kind::Face, press_) ? pick_.current() : -1;
  Expected<RotationRing> ring =
      rotationRing(*paper_, press_, sight(press_camera_, press_), face, namedAxis(), !picked_layers_only_);
  if (!ring)
  {
    ring_refusal_ = ring.message();  // said on release
    enter(GestureState::TurningNothing);
    return;
  }
  ring_ = *ring;
  enter(GestureState::TurningFace);
  turnView();
}

void GestureModel::turnView()
{
  if (!settings_.view_turn || !press_camera_ || !ring_ || !ring_->edge_on)
    return;
  const std::optional<ViewCamera> turned =
      turnedView(*press_camera_, press_, paper_->faceCentroid(ring_->face), ring_->axis_b - ring_->axis_a);
  if (!turned)
    return;
  emit(ViewTurn{ turned });
  view_turned_ = true;
}

void GestureModel::move(const Pointer& pointer)
{
  if (!dragging())
    return;
  // The drag plane carries the marker along: the pointer is the grab point moved as far as it,
  // on the line of sight through the mouse.
  const Vec3 moved = pointer.marker_position - pose_at_press_;
  pointer_ = grab_ + moved;
  pointer_camera_ = pointer.camera;
  reach_ = std::max(reach_, moved.norm());
  move_pending_ = true;
}

void GestureModel::update()
{
  if (!move_pending_)
    return;
  if (state_ == GestureState::Sliding)
    updateSlider();
  else if (dragging())
    updateDrag();
}

void GestureModel::updateDrag()
{
  move_pending_ = false;
  switch (state_)
  {
    case GestureState::DrawingLine:
      showGuides(Guides{ creaseDrag(*paper_, press_, creaseEnd(), lineSnap()), std::nullopt, 0.0, std::nullopt });
      break;
    case GestureState::HoldingVertex:
    case GestureState::Bending:
      updateVertexDrag();
      break;
    case GestureState::TurningFace:
      updateRing();
      break;
    case GestureState::DraggingFlap:
      updateFlap();
      break;
    default:
      break;
  }
  ++updates_;
}

void GestureModel::updateRing()
{
  if (pointer_camera_)
  {
    // The view may have turned since the press (turnView): seen from the side now, the face
    // follows the pointer's sight line onto the ring's plane.
    const Vec3 d = (ring_->axis_b - ring_->axis_a).normalized();
    ring_->edge_on = std::abs(pointer_camera_->rayTo(ring_->press).dot(d)) < 0.5;
  }
  angle_ = ringAngle(*ring_, pointer_, sight(pointer_camera_, pointer_), angle_);
  // No preview of no turn: paper_model draws it from a rotated copy, which does not keep the
  // order of the layers the turn would part (a click redrew a 4-layer stack at 2 heights).
  // Back at no turn after a preview, the preview of 0 puts the paper back.
  const bool turned = std::abs(angle_) > kNoTurn;
  if (turned ? !previewed_angle_ || std::abs(angle_ - *previewed_angle_) > 1e-4 :
               previewed_angle_ && *previewed_angle_ != 0.0)
    previewRotation(turned ? angle_ : 0.0);
  showGuides(Guides{ std::nullopt, ring_, angle_, std::nullopt });
}

bool GestureModel::previewRotation(double angle)
{
  const PaperReply reply =
      send(RotateCall{ turningFace(), ring_->axis_edge, ring_->press, angle, false, picked_layers_only_ });
  if (!reply.success)
    return false;
  previewed_angle_ = angle;
  return true;
}

namespace
{
/// paper_model's answer as a sentence of its own.
std::string sentence(std::string text)
{
  if (!text.empty())
    text[0] = static_cast<char>(std::toupper(static_cast<unsigned char>(text[0])));
  if (!text.empty() && text.back() != '.')
    text += '.';
  return text;
}
}  // namespace

void GestureModel::release(const Pointer& pointer)
{
  if (!dragging())
    return;
  move(pointer);
  if (move_pending_)
    updateDrag();
  const GestureState was = state_;
  // Kept before the curved model is let go (entering Idle lets it go, and it springs back).
  std::optional<PaperReply> kept;
  if (was == GestureState::Bending && keep_bend_)
    kept = send(CommandCall{ PaperCommand::KeepBend });
  enter(GestureState::Idle);
  showGuides(Guides{});
  std::string message;
  bool beside = false;  // what a click picked is said beside the paper, clear of the next click
  switch (was)
  {
    case GestureState::PickingFold:
      message = clicked() ? foldClick() : "In fold mode click on creases to mark them; drag in the other modes.";
      beside = clicked();
      break;
    case GestureState::HoldingVertex:
    case GestureState::Bending:
      if (kept && kept->success)
      {
        dragged_vertex_ = -1;
        pick_ = Pick{};
        showPicks();
        message = sentence(kept->message);
      }
      else
        message = releaseVertex(was == GestureState::Bending) +
                  (kept ? " " + sentence(kept->message) : "");
      break;
    case GestureState::TurningFace:
    case GestureState::TurningNothing:
      message = clicked() ? clickAxis() : ring_ ? releaseTurn() : ring_refusal_;
      break;
    case GestureState::DrawingLine:
      message = releaseLine();
      break;
    case GestureState::DraggingFlap:
      message = releaseFlap();
      break;
    default:
      break;
  }
  if (!message.empty() && beside)
    tellBeside(message);
  else
    tell(message, pointer_);  // an empty one: done, or nothing to do, an earlier refusal no longer applies
  emit(SheetReleased{ sheet_stale_ });
  sheet_stale_ = false;
  if (slider_stale_)
    showSlider();
  showPicks();  // the clearing above took the marks with it
}

std::string GestureModel::releaseLine()
{
  const CreaseDrag drag = creaseDrag(*paper_, press_, creaseEnd(), lineSnap());
  if (drag.length() < settings_.min_crease_length * paper_->scale())
    return "";
  CreaseCall call{ drag.start.point, drag.end.point, std::nullopt };
  if (press_camera_)  // through stacked layers of a 3D form, the layers under the line as the eye sees them
    call.eye = press_camera_->eye;
  return refusal(send(call));  // a refusal says why; a crease shows itself
}

std::string GestureModel::releaseTurn()
{
  // The angle last shown is the one committed; a press without a turn commits nothing and
  // draws nothing new.
  const double angle = previewed_angle_.value_or(0.0);
  if (std::abs(angle) > kNoTurn)
    return refusal(send(RotateCall{ turningFace(), ring_->axis_edge, ring_->press, angle, true, picked_layers_only_ }));
  if (previewed_angle_ && *previewed_angle_ != 0.0)
    previewRotation(0.0);
  return "";
}

std::string GestureModel::clickAxis()
{
  const int named = namedAxis();
  std::string message;
  if (crease_at_press_ >= 0 && crease_at_press_ != named)
  {
    named_axis_ = paper_->edges[crease_at_press_].vertices;
    message = "The axis: this crease. Drag a part of the paper to turn it about the crease; click off the "
              "creases for the automatic axis.";
  }
  else if (named >= 0)
  {
    named_axis_ = { -1, -1 };
    message = "The automatic axis again.";
  }
  else if (!ring_)
    message = ring_refusal_;
  showGuides(Guides{});
  return message;
}

int GestureModel::turningFace() const
{
  // rotate turns a face about a crease of its own: about a crease named elsewhere, the face
  // of the flap next to it.
  const Edge& hinge = paper_->edges[ring_->axis_edge];
  if (hinge.faces[0] == ring_->face || hinge.faces[1] == ring_->face)
    return ring_->face;
  for (int f : hinge.faces)
    if (std::count(ring_->moving_faces.begin(), ring_->moving_faces.end(), f))
      return f;
  return ring_->face;
}

int GestureModel::namedAxis() const
{
  if (!paper_ || named_axis_[0] < 0)
    return -1;
  for (size_t e = 0; e < paper_->edges.size(); ++e)
  {
    const Edge& edge = paper_->edges[e];
    if (edge.isCrease() && ((edge.vertices[0] == named_axis_[0] && edge.vertices[1] == named_axis_[1]) ||
                            (edge.vertices[0] == named_axis_[1] && edge.vertices[1] == named_axis_[0])))
      return static_cast<int>(e);
  }
  return -1;
}

void GestureModel::showGuides(Guides guides)
{
  const int named = mode_ == GestureMode::Rotate ? namedAxis() : -1;
  if (named >= 0)
  {
    const Edge& edge = paper_->edges[named];
    guides.named_axis.emplace(paper_->vertices[edge.vertices[0]].folded, paper_->vertices[edge.vertices[1]].folded);
  }
  emit(std::move(guides));
}

void GestureModel::setMode(GestureMode mode)
{
  mode_ = mode;
  enter(GestureState::Idle);
  showSheet();
  showGuides(Guides{});
  showPicks();
}

void GestureModel::chooseMode(GestureMode mode, const Pointer& at)
{
  setMode(mode);
  const char* said = "";
  switch (mode)
  {
    case GestureMode::Crease:
      said = "crease mode";
      break;
    case GestureMode::Rotate:
      said = "rotate mode";
      break;
    case GestureMode::Fold:
      said = "Fold mode: click creases to mark them valley, mountain or unfold; click the face that stays; then "
             "Fold on the marked creases.";
      break;
    case GestureMode::Drag:
      said = "Drag mode: press on a vertex and drag it.";
      break;
    case GestureMode::Flap:
      said = "Flap mode: press on a flap and drag it where it should lie; the squash, petal or reverse fold "
             "that takes it there folds flat on release.";
      break;
  }
  tell(said, rightClick(at));
}

void GestureModel::command(PaperCommand command, const Pointer& at)
{
  const std::string said = send(CommandCall{ command }).message;
  if (!said.empty())
    tell(said, rightClick(at));
}

void GestureModel::pin(const Pointer& at, bool release)
{
  if (!paper_ || !at.mouse_point)
    return;
  const Vec3 click = rightClick(at);
  // The vertex nearest the right-click: any vertex to pin, a pinned one to release.
  int nearest = -1;
  double best = 0.1 * paper_->scale();
  for (size_t v = 0; v < paper_->vertices.size(); ++v)
  {
    const bool candidate = !release || std::count(pinned_.begin(), pinned_.end(), static_cast<int>(v)) > 0;
    const double d = (paper_->vertices[v].folded - click).norm();
    if (candidate && d < best)
    {
      best = d;
      nearest = static_cast<int>(v);
    }
  }
  const std::string said = nearest < 0 ? (release ? "no pin near the click" : "no vertex near the click") :
                                         send(PinCall{ nearest, release }).message;
  if (!said.empty())
    tell(said, click);
}

void GestureModel::toggleSnapping(const Pointer& at)
{
  snapping_ = !snapping_;
  showSheet();  // the menu's check mark
  tell(snapping_ ? "A drawn line snaps to vertices and divisions." : "A drawn line creases exactly as drawn.",
       rightClick(at));
}

void GestureModel::toggleKeepRefusedFolds(const Pointer& at)
{
  keep_refused_folds_ = !keep_refused_folds_;
  showSheet();  // the menu's check mark
  tell(keep_refused_folds_ ? "Folds by assignment are kept even when strained or crossing, their figures said." :
                             "Folds by assignment that strain or cross the paper are refused.",
       rightClick(at));
}

void GestureModel::toggleKeepBend(const Pointer& at)
{
  keep_bend_ = !keep_bend_;
  showSheet();  // the menu's check mark
  tell(keep_bend_ ? "A bent drag let go keeps the bend: the paper stays where the curved model bent it." :
                    "A bent drag let go springs back.",
       rightClick(at));
}

void GestureModel::togglePickedLayersOnly(const Pointer& at)
{
  picked_layers_only_ = !picked_layers_only_;
  showSheet();
  tell(picked_layers_only_ ? "A turn carries the picked layers only." : "A turn carries the whole stack on the face.",
       rightClick(at));
}

GestureStatus GestureModel::status() const
{
  GestureStatus status;
  const bool fresh = pick_.revision == revision_;
  status.picked_edge = fresh && pick_.kind == Pick::Kind::Crease ? pick_.current() : -1;
  status.picked_face = mode_ == GestureMode::Fold              ? keptFace() :
                       fresh && pick_.kind == Pick::Kind::Face ? pick_.current() :
                                                                 -1;
  status.picked_vertex = fresh && pick_.kind == Pick::Kind::Vertex ? pick_.current() : -1;
  status.bending = state_ == GestureState::Bending;
  status.picked_layer = fresh && pick_.kind != Pick::Kind::None ? static_cast<uint32_t>(pick_.index + 1) : 0;
  status.layers = fresh ? static_cast<uint32_t>(pick_.candidates.size()) : 0;
  if (paper_)
    for (const auto& [edge, mark] : marks_.edges(*paper_))
    {
      status.marked_edges.push_back(edge);
      status.marked_angles.push_back(markAngle(mark));
    }
  status.dragging = state_ != GestureState::Idle;
  return status;
}

}  // namespace virtual_origami::core

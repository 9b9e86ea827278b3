// The gesture model's picking in stacks (SPEC §3.8), folds on chosen creases (§3.7) and vertex
// drags (§3.6): core/layer_pick.h and core/chosen_creases.h under the mouse.
#include <algorithm>
#include <cmath>

#include "virtual_origami/core/gesture_model.h"
#include "virtual_origami/core/layer_pick.h"

namespace virtual_origami::core
{
namespace
{
const char* markName(CreaseMark mark)
{
  switch (mark)
  {
    case CreaseMark::Valley:
      return "valley";
    case CreaseMark::Mountain:
      return "mountain";
    case CreaseMark::Unfold:
      return "unfold";
    case CreaseMark::None:
      break;
  }
  return "not marked";
}

std::string layerOf(size_t index, size_t count)
{
  return "layer " + std::to_string(index + 1) + " of " + std::to_string(count);
}
}  // namespace

bool GestureModel::pickedHere(Pick::Kind kind, const Vec3& at) const
{
  return pick_.kind == kind && pick_.revision == revision_ && (pick_.at - at).norm() <= settings_.snap.radius;
}

std::string GestureModel::foldClick()
{
  const Vec3 view = sight(press_camera_, press_);
  if (pickedHere(Pick::Kind::Crease, press_))
  {
    // Again on the crease just picked: its next mark, whichever layer it is in.
    const int edge = pick_.current();
    const CreaseMark mark = nextMark(marks_.markOf(*paper_, edge));
    marks_.mark(*paper_, edge, mark);
    showPicks();
    return std::string("Crease ") + markName(mark) + " (" + layerOf(pick_.index, pick_.candidates.size()) + ").";
  }
  const std::vector<int> creases = creasesUnder(*paper_, press_, view, settings_.snap.radius);
  if (creases.empty())
    return keepFaceAt(press_);
  pick_ = Pick{ Pick::Kind::Crease, press_, creases, 0, revision_ };
  if (creases.size() > 1)
  {
    // Creases of several layers lie here: the click only picks the top one, so that a mark
    // goes only where the user has seen the pick.
    showPicks();
    return std::to_string(creases.size()) + " creases lie here: click again to mark this one (" +
           layerOf(0, creases.size()) + "), or Next layer down.";
  }
  const CreaseMark mark = nextMark(marks_.markOf(*paper_, creases[0]));
  marks_.mark(*paper_, creases[0], mark);
  showPicks();
  return std::string("Crease ") + markName(mark) + ".";
}

void GestureModel::keepFace(const Pointer& at)
{
  press_camera_ = at.camera;
  const GestureMode was = mode_;
  mode_ = GestureMode::Fold;  // the face that stays belongs to the marks
  const std::string said = keepFaceAt(surfacePoint(at));
  if (was != GestureMode::Fold)
    setMode(GestureMode::Fold);
  if (!said.empty())
    tellBeside(said);
}

std::string GestureModel::keepFaceAt(const Vec3& at)
{
  if (!paper_)
    return "";
  const std::vector<int> faces = facesUnder(*paper_, at, sight(press_camera_, at));
  if (faces.empty())
  {
    pick_ = Pick{};  // a click on nothing lets go of the pick
    showPicks();
    return "No paper here: click on a face to keep it in place.";
  }
  pick_ = Pick{ Pick::Kind::Face, at, faces, 0, revision_ };
  if (mode_ == GestureMode::Fold)
    keep_point_ = creasePatternPoint(*paper_, faces[0]);
  showPicks();
  return mode_ == GestureMode::Fold ? "This face stays (" + layerOf(0, faces.size()) + ")." :
                                      "Picked the face here (" + layerOf(0, faces.size()) + ").";
}

void GestureModel::nextLayer(const Pointer& at)
{
  press_camera_ = at.camera;
  const std::string said = walkLayers(surfacePoint(at), true);
  if (!said.empty())
    tellBeside(said);
}

void GestureModel::previousLayer(const Pointer& at)
{
  press_camera_ = at.camera;
  const std::string said = walkLayers(surfacePoint(at), false);
  if (!said.empty())
    tellBeside(said);
}

std::string GestureModel::walkLayers(const Vec3& at, bool down)
{
  if (!paper_)
    return "";
  const Vec3 view = sight(press_camera_, at);
  if (!pickedHere(pick_.kind, at) || pick_.kind == Pick::Kind::None)
  {
    // Nothing picked here yet: the layers under the pointer, top first; the top one is where a
    // click picks, so up from it there is nothing.
    const std::vector<int> creases =
        mode_ == GestureMode::Fold ? creasesUnder(*paper_, at, view, settings_.snap.radius) : std::vector<int>{};
    Pick under;
    if (mode_ == GestureMode::Drag)
      under = Pick{ Pick::Kind::Vertex, at, verticesUnder(*paper_, at, view, settings_.snap.radius), 0, revision_ };
    else if (!creases.empty())
      under = Pick{ Pick::Kind::Crease, at, creases, 0, revision_ };
    else
      under = Pick{ Pick::Kind::Face, at, facesUnder(*paper_, at, view), 0, revision_ };
    if (under.candidates.empty())
    {
      pick_ = Pick{};
      showPicks();
      return "Nothing here to pick.";
    }
    if (!down)
      return "No layer above this one: a click here picks the top layer.";
    pick_ = std::move(under);
  }
  if (down && pick_.index + 1 >= pick_.candidates.size())
    return "No layer below this one.";
  if (!down && pick_.index == 0)
    return "No layer above this one.";
  pick_.index = down ? pick_.index + 1 : pick_.index - 1;
  if (pick_.kind == Pick::Kind::Face && mode_ == GestureMode::Fold)
    keep_point_ = creasePatternPoint(*paper_, pick_.current());
  showPicks();
  return "Picked " + layerOf(pick_.index, pick_.candidates.size()) + ".";
}

int GestureModel::keptFace() const
{
  if (!paper_ || !keep_point_)
    return -1;
  return faceContaining(*paper_, *keep_point_);
}

void GestureModel::clearMarks(const Pointer& at)
{
  marks_.clear();
  keep_point_.reset();
  pick_ = Pick{};
  showPicks();
  tell("Marks cleared.", rightClick(at));
}

void GestureModel::foldMarks(double angle, const Pointer& at)
{
  const std::string said = startFold(angle);
  if (!said.empty())
    tell(said, rightClick(at));
}

std::string GestureModel::startFold(double angle)
{
  if (!paper_)
    return "";
  if (marks_.edges(*paper_).empty())
    return "No crease marked: in fold mode click on creases to mark them valley, mountain or unfold.";
  if (keptFace() < 0)
    return "Pick the face that stays first: click on it (away from the creases), or Keep the face here.";
  std::optional<FlatFoldRequest> request = chosenCreasesFold(*paper_, marks_, keptFace(), angle);
  if (!request)
    return "";
  folding_ = std::move(*request);
  fold_frame_ = 0;
  std::string message;
  // The first frame says at once whether the creases fold at all.
  if (!previewFold(1.0 / settings_.fold_frames, message))
  {
    folding_.reset();
    return message;
  }
  fold_frame_ = 1;
  enter(GestureState::FoldingMarks);
  return "";
}

bool GestureModel::previewFold(double fraction, std::string& message)
{
  const PaperReply reply = send(FlatFoldCall{ *folding_, std::min(fraction, 1.0), fraction >= 1.0 });
  if (!reply.success)
    message = reply.message;
  return reply.success;
}

void GestureModel::tick()
{
  animateFold();
}

void GestureModel::finishFold()
{
  while (state_ == GestureState::FoldingMarks)  // the user goes on: the fold first, at once
    animateFold();
}

void GestureModel::animateFold()
{
  if (state_ != GestureState::FoldingMarks)
    return;
  ++fold_frame_;
  std::string message;
  const bool done = fold_frame_ >= settings_.fold_frames;
  if (!previewFold(done ? 1.0 : static_cast<double>(fold_frame_) / settings_.fold_frames, message) && !message.empty())
  {
    folding_.reset();
    enter(GestureState::Idle);
    tell(message, pointer_);
    return;
  }
  if (done)
  {
    folding_.reset();
    enter(GestureState::Idle);
    marks_.clear();
    keep_point_.reset();
    pick_ = Pick{};
    showPicks();
  }
}

void GestureModel::pressVertex()
{
  dragged_vertex_ = -1;
  vertex_previewed_.reset();
  vertex_refusal_.clear();
  if (pickedHere(Pick::Kind::Vertex, press_))
    dragged_vertex_ = pick_.current();
  else
  {
    const std::vector<int> under = verticesUnder(*paper_, press_, sight(press_camera_, press_), settings_.snap.radius);
    if (!under.empty())
      pick_ = Pick{ Pick::Kind::Vertex, press_, under, 0, revision_ };
    dragged_vertex_ = under.empty() ? -1 : under[0];
  }
  if (dragged_vertex_ < 0)
    vertex_refusal_ = "No vertex here: press on a corner of a face to drag it.";
  else
    vertex_at_press_ = paper_->vertices[dragged_vertex_].folded;
  showPicks();
}

Vec3 GestureModel::vertexTarget() const
{
  if (pointer_camera_)  // in the plane through the vertex facing the eye, on the pointer's sight line
    return alongSightOnto(*pointer_camera_, pointer_, vertex_at_press_, pointer_camera_->rayTo(vertex_at_press_))
        .value_or(vertex_at_press_);
  return vertex_at_press_ + (pointer_ - grab_);
}

void GestureModel::updateVertexDrag()
{
  if (dragged_vertex_ < 0)
    return;
  const Vec3 target = vertexTarget();
  if (vertex_previewed_ && (*vertex_previewed_ - target).norm() < 1e-6 * paper_->scale())
    return;
  const PaperReply reply = send(DragVertexCall{ dragged_vertex_, target, false });
  if (!reply.success && reply.answered && reply.curved_reaches)
    return bend(target);  // rigid faces first; where they cannot follow, the curved model
  enter(GestureState::HoldingVertex);
  vertex_refusal_ = refusal(reply);
  if (reply.success)
    vertex_previewed_ = target;
}

void GestureModel::bend(const Vec3& target)
{
  const bool first = state_ != GestureState::Bending;
  enter(GestureState::Bending);  // before the hold: the bent sheets since the state's entry are this drag's
  emit(CurvedHold{ dragged_vertex_, target });
  vertex_refusal_.clear();
  if (first)
    tell("The faces cannot stay flat there: the paper bends. Let go and it springs back.", target);
}

std::string GestureModel::releaseVertex(bool bent)
{
  if (dragged_vertex_ < 0)
    return vertex_refusal_;
  if (clicked())
  {
    showPicks();
    return "Picked a vertex (" + layerOf(pick_.index, pick_.candidates.size()) + "); drag it.";
  }
  // The press's own preview (the vertex where it lies) moves nothing: no history entry for it.
  const bool moved = vertex_previewed_ && (*vertex_previewed_ - vertex_at_press_).norm() > 1e-9 * paper_->scale();
  if (!moved || !vertex_refusal_.empty())  // where the pointer ended no shape follows
  {
    dragged_vertex_ = -1;
    if (bent)
      return "Let go: the bent paper springs back, as it was.";
    if (!vertex_refusal_.empty())
      return vertex_refusal_;
    return vertex_previewed_ ? "The vertex is back where it was: nothing changed." :
                               "The paper cannot follow the vertex there.";
  }
  std::string message = refusal(send(DragVertexCall{ dragged_vertex_, *vertex_previewed_, true }));
  if (message.empty() && bent)
    message = "Let go: the bend springs back; the faces stay where they could follow flat.";
  dragged_vertex_ = -1;
  pick_ = Pick{};
  showPicks();
  return message;
}

void GestureModel::showPicks()
{
  if (!paper_)
    return;
  const bool fresh = pick_.revision == revision_;
  Picks picks;
  picks.marks = marks_.edges(*paper_);
  picks.picked_edge = fresh && pick_.kind == Pick::Kind::Crease ? pick_.current() : -1;
  picks.keep_face = mode_ == GestureMode::Fold ? keptFace() : -1;
  picks.face = fresh && pick_.kind == Pick::Kind::Face && mode_ != GestureMode::Fold ? pick_.current() : -1;
  picks.vertex = fresh && pick_.kind == Pick::Kind::Vertex ? pick_.current() : -1;
  emit(std::move(picks));
}

}  // namespace virtual_origami::core

// The interaction node's picking in stacks (SPEC §3.8), folds on chosen creases (§3.7) and
// vertex drags (§3.6): the ROS side of core/layer_pick.h and core/chosen_creases.h.
#include <algorithm>
#include <cmath>

#include <virtual_origami/DragVertex.h>
#include <virtual_origami/VertexTarget.h>
#include <virtual_origami/FlatFold.h>

#include "virtual_origami/core/layer_pick.h"
#include "virtual_origami/ros/conversions.h"
#include "virtual_origami/ros/interaction_node.h"

namespace virtual_origami
{
namespace
{
/// Calls a service; false (and the reason in `message`) when it cannot be reached.
template <class Service>
bool reach(ros::ServiceClient& client, Service& srv, std::string& message)
{
  if (client.call(srv))
    return true;
  message = client.getService() + " did not answer; is paper_model running?";
  return false;
}

const char* markName(core::CreaseMark mark)
{
  switch (mark)
  {
    case core::CreaseMark::Valley:
      return "valley";
    case core::CreaseMark::Mountain:
      return "mountain";
    case core::CreaseMark::Unfold:
      return "unfold";
    case core::CreaseMark::None:
      break;
  }
  return "not marked";
}

std::string layerOf(size_t index, size_t count)
{
  return "layer " + std::to_string(index + 1) + " of " + std::to_string(count);
}
}  // namespace

core::Vec3 InteractionNode::surfacePoint(const Feedback& feedback) const
{
  if (!paper_ || !feedback.mouse_point_valid)
    return core::Vec3::Zero();
  const std::optional<ViewCamera> seen = camera(feedback.header.stamp);
  if (seen)
  {
    const core::Vec3 grab = toVec3(feedback.mouse_point);
    return core::onSurface(*paper_, grab, sight(seen, grab));
  }
  return core::onSurface(*paper_, onSheet(feedback.mouse_point), view_direction_);
}

bool InteractionNode::pickedHere(Pick::Kind kind, const core::Vec3& at) const
{
  return pick_.kind == kind && pick_.revision == revision_ && (pick_.at - at).norm() <= snap_.radius;
}

std::string InteractionNode::foldClick()
{
  const core::Vec3 view = sight(press_camera_, press_);
  if (pickedHere(Pick::Kind::Crease, press_))
  {
    // Again on the crease just picked: its next mark, whichever layer it is in.
    const int edge = pick_.current();
    const core::CreaseMark mark = core::nextMark(marks_.markOf(*paper_, edge));
    marks_.mark(*paper_, edge, mark);
    showPicks();
    return std::string("Crease ") + markName(mark) + " (" + layerOf(pick_.index, pick_.candidates.size()) + ").";
  }
  const std::vector<int> creases = core::creasesUnder(*paper_, press_, view, snap_.radius);
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
  const core::CreaseMark mark = core::nextMark(marks_.markOf(*paper_, creases[0]));
  marks_.mark(*paper_, creases[0], mark);
  showPicks();
  return std::string("Crease ") + markName(mark) + ".";
}

std::string InteractionNode::keepFaceAt(const core::Vec3& at)
{
  if (!paper_)
    return "";
  const std::vector<int> faces = core::facesUnder(*paper_, at, sight(press_camera_, at));
  if (faces.empty())
  {
    pick_ = Pick{};  // a click on nothing lets go of the pick
    showPicks();
    return "No paper here: click on a face to keep it in place.";
  }
  pick_ = Pick{ Pick::Kind::Face, at, faces, 0, revision_ };
  if (mode_ == Mode::Fold)
    keep_point_ = core::creasePatternPoint(*paper_, faces[0]);
  showPicks();
  return mode_ == Mode::Fold ? "This face stays (" + layerOf(0, faces.size()) + ")." :
                               "Picked the face here (" + layerOf(0, faces.size()) + ").";
}

std::string InteractionNode::nextLayer(const core::Vec3& at)
{
  if (!paper_)
    return "";
  const core::Vec3 view = sight(press_camera_, at);
  if (!pickedHere(pick_.kind, at) || pick_.kind == Pick::Kind::None)
  {
    // Nothing picked here yet: the layers under the right-click, top first.
    const std::vector<int> creases =
        mode_ == Mode::Fold ? core::creasesUnder(*paper_, at, view, snap_.radius) : std::vector<int>{};
    if (mode_ == Mode::Drag)
      pick_ = Pick{ Pick::Kind::Vertex, at, core::verticesUnder(*paper_, at, view, snap_.radius), 0, revision_ };
    else if (!creases.empty())
      pick_ = Pick{ Pick::Kind::Crease, at, creases, 0, revision_ };
    else
      pick_ = Pick{ Pick::Kind::Face, at, core::facesUnder(*paper_, at, view), 0, revision_ };
    if (pick_.candidates.empty())
    {
      pick_ = Pick{};
      showPicks();
      return "Nothing here to pick.";
    }
  }
  if (pick_.index + 1 >= pick_.candidates.size())
    return "No layer below this one.";
  ++pick_.index;
  if (pick_.kind == Pick::Kind::Face && mode_ == Mode::Fold)
    keep_point_ = core::creasePatternPoint(*paper_, pick_.current());
  showPicks();
  return "Picked " + layerOf(pick_.index, pick_.candidates.size()) + ".";
}

int InteractionNode::keptFace() const
{
  if (!paper_ || !keep_point_)
    return -1;
  return core::faceContaining(*paper_, *keep_point_);
}

std::string InteractionNode::startFold(double angle)
{
  if (!paper_)
    return "";
  if (marks_.edges(*paper_).empty())
    return "No crease marked: in fold mode click on creases to mark them valley, mountain or unfold.";
  if (keptFace() < 0)
    return "Pick the face that stays first: click on it (away from the creases), or Keep the face here.";
  std::optional<core::FlatFoldRequest> request = core::chosenCreasesFold(*paper_, marks_, keptFace(), angle);
  if (!request)
    return "";
  folding_ = std::move(*request);
  fold_frame_ = 0;
  std::string message;
  // The first frame says at once whether the creases fold at all.
  if (!previewFold(1.0 / fold_frames_, message))
  {
    folding_.reset();
    return message;
  }
  fold_frame_ = 1;
  return "";
}

bool InteractionNode::previewFold(double fraction, std::string& message)
{
  FlatFold srv;
  for (const core::CreaseLineAngle& line : folding_->creases)
  {
    srv.request.starts.push_back(toPoint(core::Vec3(line.start.x(), line.start.y(), 0.0)));
    srv.request.ends.push_back(toPoint(core::Vec3(line.end.x(), line.end.y(), 0.0)));
    srv.request.angles.push_back(line.angle);
  }
  srv.request.fixed = toPoint(core::Vec3(folding_->fixed_point.x(), folding_->fixed_point.y(), 0.0));
  srv.request.commit = fraction >= 1.0;
  srv.request.fraction = std::min(fraction, 1.0);
  if (!reach(flat_fold_, srv, message))
    return false;
  if (!srv.response.success)
  {
    message = srv.response.message;
    return false;
  }
  return true;
}

void InteractionNode::animateFold()
{
  if (!folding_)
    return;
  ++fold_frame_;
  std::string message;
  const bool done = fold_frame_ >= fold_frames_;
  if (!previewFold(done ? 1.0 : static_cast<double>(fold_frame_) / fold_frames_, message) && !message.empty())
  {
    folding_.reset();
    tell(message, pointer_);
    return;
  }
  if (done)
  {
    folding_.reset();
    marks_.clear();
    keep_point_.reset();
    pick_ = Pick{};
    showPicks();
  }
}

void InteractionNode::pressVertex()
{
  dragged_vertex_ = -1;
  vertex_previewed_.reset();
  vertex_refusal_.clear();
  if (pickedHere(Pick::Kind::Vertex, press_))
    dragged_vertex_ = pick_.current();
  else
  {
    const std::vector<int> under = core::verticesUnder(*paper_, press_, sight(press_camera_, press_), snap_.radius);
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

core::Vec3 InteractionNode::vertexTarget() const
{
  const std::optional<ViewCamera> now = camera(pointer_stamp_);
  if (now)  // in the plane through the vertex facing the eye, on the pointer's sight line
    return alongSightOnto(*now, pointer_, vertex_at_press_, now->rayTo(vertex_at_press_)).value_or(vertex_at_press_);
  return vertex_at_press_ + (pointer_ - grab_);
}

void InteractionNode::updateVertexDrag()
{
  if (dragged_vertex_ < 0)
    return;
  const core::Vec3 target = vertexTarget();
  if (vertex_previewed_ && (*vertex_previewed_ - target).norm() < 1e-6 * paper_->scale())
    return;
  DragVertex srv;
  srv.request.vertex = dragged_vertex_;
  srv.request.position = toPoint(target);
  srv.request.commit = false;
  std::string message;
  if (!reach(drag_vertex_, srv, message) || !srv.response.success)
  {
    // Rigid faces first; where they cannot follow, the curved model, when one is running.
    if (message.empty() && srv.response.curved_reaches && curved_drag_pub_.getNumSubscribers() > 0)
      return bend(target);
    stopBending();
    vertex_refusal_ = message.empty() ? srv.response.message : message;
    return;
  }
  stopBending();
  vertex_refusal_.clear();
  vertex_previewed_ = target;
}

void InteractionNode::bend(const core::Vec3& target)
{
  VertexTarget held;
  held.header.frame_id = style_.frame_id;
  held.header.stamp = ros::Time::now();
  held.vertex = dragged_vertex_;
  held.position = toPoint(target);
  curved_drag_pub_.publish(held);
  vertex_refusal_.clear();
  if (bending_)
    return;
  bending_ = true;
  bent_since_ = held.header.stamp;
  tell("The faces cannot stay flat there: the paper bends. Let go and it springs back.", target);
}

void InteractionNode::stopBending()
{
  if (!bending_)
    return;
  bending_ = false;
  VertexTarget let_go;
  let_go.header.frame_id = style_.frame_id;
  let_go.header.stamp = ros::Time::now();
  let_go.vertex = -1;
  curved_drag_pub_.publish(let_go);
  visualization_msgs::MarkerArray hide;
  for (const char* ns : { "bent_sheet", "bent_sheet_back", "bent_sheet_edges" })
  {
    visualization_msgs::Marker m;
    m.header = let_go.header;
    m.ns = ns;
    m.action = visualization_msgs::Marker::DELETE;
    hide.markers.push_back(m);
  }
  markers_pub_.publish(hide);
}

void InteractionNode::curvedSheetReceived(const visualization_msgs::MarkerArray::ConstPtr& sheet)
{
  if (!bending_ || sheet->markers.empty() || sheet->markers.front().header.stamp < bent_since_)
    return;  // only the sheet bent after the mouse: the state's own sheet is the Curved sheet display's
  visualization_msgs::MarkerArray shown = *sheet;
  for (visualization_msgs::Marker& m : shown.markers)
    m.ns = "bent_sheet" + m.ns.substr(std::string("curved_mesh").size());
  markers_pub_.publish(shown);
}

std::string InteractionNode::releaseVertex()
{
  const bool clicked = reach_ < min_crease_length_ * paper_->scale();
  if (dragged_vertex_ < 0)
    return vertex_refusal_;
  if (clicked)
  {
    showPicks();
    return "Picked a vertex (" + layerOf(pick_.index, pick_.candidates.size()) + "); drag it.";
  }
  const bool bent = bending_;
  stopBending();
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
  DragVertex srv;
  srv.request.vertex = dragged_vertex_;
  srv.request.position = toPoint(*vertex_previewed_);
  srv.request.commit = true;
  std::string message;
  if (reach(drag_vertex_, srv, message) && !srv.response.success)
    message = srv.response.message;
  else if (message.empty() && bent)
    message = "Let go: the bend springs back; the faces stay where they could follow flat.";
  dragged_vertex_ = -1;
  pick_ = Pick{};
  showPicks();
  return message;
}

void InteractionNode::showPicks()
{
  if (!paper_)
    return;
  const int picked_edge = pick_.kind == Pick::Kind::Crease && pick_.revision == revision_ ? pick_.current() : -1;
  visualization_msgs::MarkerArray array =
      chosenCreaseMarkers(*paper_, marks_.edges(*paper_), picked_edge, mode_ == Mode::Fold ? keptFace() : -1, style_,
                          ros::Time::now());
  const bool fresh = pick_.revision == revision_;
  const int face = fresh && pick_.kind == Pick::Kind::Face && mode_ != Mode::Fold ? pick_.current() : -1;
  const int vertex = fresh && pick_.kind == Pick::Kind::Vertex ? pick_.current() : -1;
  const visualization_msgs::MarkerArray picked = pickMarkers(*paper_, face, vertex, style_, ros::Time::now());
  array.markers.insert(array.markers.end(), picked.markers.begin(), picked.markers.end());
  markers_pub_.publish(array);
}

}  // namespace virtual_origami

// The gesture model's outputs, carried out: its requests as paper_model's service calls (one
// helper for them all), what it shows as markers, the view turn and the curved model's hold.
#include <cstdio>

#include <dynamic_reconfigure/Reconfigure.h>
#include <geometry_msgs/PoseStamped.h>
#include <std_srvs/Trigger.h>
#include <virtual_origami/Crease.h>
#include <virtual_origami/DragVertex.h>
#include <virtual_origami/FlatFold.h>
#include <virtual_origami/FoldByAssignment.h>
#include <virtual_origami/PinVertex.h>
#include <virtual_origami/Rotate.h>
#include <virtual_origami/VertexTarget.h>

#include "virtual_origami/core/fold_fraction.h"
#include "virtual_origami/ros/conversions.h"
#include "virtual_origami/ros/interaction_node.h"
#include "virtual_origami/ros/interaction_text.h"
#include "virtual_origami/ros/service_call.h"

namespace virtual_origami
{
namespace
{
/// Characters per line of a message: a short column stays inside the view.
constexpr size_t kMessageWidth = 32;

/// Calls a service; false (and the reason in `message`) when it cannot be reached.
template <class Service>
bool call(ros::ServiceClient& client, Service& srv, std::string& message)
{
  if (callService(client.getService(), srv))
    return true;
  message = client.getService() + " did not answer; is paper_model running?";
  return false;
}

/// paper_model's answer to a call of one of its services.
template <class Service>
core::PaperReply reply(ros::ServiceClient& client, Service& srv)
{
  core::PaperReply r;
  r.answered = call(client, srv, r.message);
  if (r.answered)
  {
    r.success = srv.response.success;
    r.message = srv.response.message;
  }
  return r;
}

/// paper_model's answer on a kept connection (`client`, opened when it is not): a call that
/// fails on it is made once more on a new connection, which is then kept.
template <class Service>
core::PaperReply keptReply(ros::ServiceClient& client, const std::string& service, Service& srv)
{
  if (!client.isValid())
    client = ros::NodeHandle().serviceClient<Service>(service, /*persistent=*/true);
  core::PaperReply r;
  if (!client.call(srv))
  {
    client = ros::NodeHandle().serviceClient<Service>(service, /*persistent=*/true);
    if (!client.call(srv))
    {
      client.shutdown();
      r.message = service + " did not answer; is paper_model running?";
      return r;
    }
  }
  r.answered = true;
  r.success = srv.response.success;
  r.message = srv.response.message;
  return r;
}

geometry_msgs::Point onTable(const core::Vec2& p)
{
  return toPoint(core::Vec3(p.x(), p.y(), 0.0));
}

/// Sized with the sheet, as the sheet's own markers are for a 1 m square.
SliderStyle scaledTo(const std::optional<core::Paper>& paper, SliderStyle style)
{
  const double scale = paper ? paper->scale() : 1.0;
  style.handle_size *= scale;
  style.line_width *= scale;
  style.text_size *= scale;
  return style;
}

/// The drag's guides: the line with its snaps or the ring, else none; and the named axis.
visualization_msgs::MarkerArray guideMarkers(const core::Guides& g, const InteractionStyle& style, const ros::Time& now)
{
  visualization_msgs::MarkerArray array = g.line ? creaseDragMarkers(*g.line, style, now) :
                                          g.ring ? rotationDragMarkers(*g.ring, g.angle, style, now) :
                                                   clearedMarkers(style, now);
  if (g.named_axis)
  {
    const visualization_msgs::MarkerArray axis =
        namedAxisMarkers(g.named_axis->first, g.named_axis->second, style, now);
    array.markers.insert(array.markers.end(), axis.markers.begin(), axis.markers.end());
  }
  return array;
}

visualization_msgs::MarkerArray picksMarkers(const core::Paper& paper, const core::Picks& p,
                                             const InteractionStyle& style, const ros::Time& now)
{
  visualization_msgs::MarkerArray array = chosenCreaseMarkers(paper, p.marks, p.picked_edge, p.keep_face, style, now);
  const visualization_msgs::MarkerArray picked = pickMarkers(paper, p.face, p.vertex, style, now);
  array.markers.insert(array.markers.end(), picked.markers.begin(), picked.markers.end());
  return array;
}

/// The goal the ViewCamera display turns rviz's view to; without a frame: back to the view
/// before the turn.
geometry_msgs::PoseStamped viewTurnGoal(const core::ViewTurn& turn, const std::string& frame_id, const ros::Time& now)
{
  geometry_msgs::PoseStamped goal;
  goal.header.stamp = now;
  if (!turn.to)
    return goal;
  goal.header.frame_id = frame_id;
  goal.pose.position = toPoint(turn.to->eye);
  const Eigen::Quaterniond q(turn.to->axes);
  goal.pose.orientation.w = q.w();
  goal.pose.orientation.x = q.x();
  goal.pose.orientation.y = q.y();
  goal.pose.orientation.z = q.z();
  return goal;
}

/// Removes the bent sheet shown while the curved model held the vertex.
visualization_msgs::MarkerArray bentSheetHidden(const std_msgs::Header& header)
{
  visualization_msgs::MarkerArray hide;
  for (const char* ns : { "bent_sheet", "bent_sheet_back", "bent_sheet_edges" })
  {
    visualization_msgs::Marker m;
    m.header = header;
    m.ns = ns;
    m.action = visualization_msgs::Marker::DELETE;
    hide.markers.push_back(m);
  }
  return hide;
}

template <class... Ts>
struct Overloaded : Ts...
{
  using Ts::operator()...;
};
template <class... Ts>
Overloaded(Ts...) -> Overloaded<Ts...>;
}  // namespace

core::PaperReply InteractionNode::send(const core::PaperRequest& request)
{
  return std::visit(Overloaded{
                        [&](const core::CreaseCall& c) {
                          Crease srv;
                          srv.request.start = toPoint(c.start);
                          srv.request.end = toPoint(c.end);
                          srv.request.has_eye = c.eye.has_value();
                          if (c.eye)
                            srv.request.eye = toPoint(*c.eye);
                          srv.request.snap =
                              false;  // snapped by the gesture already: what was drawn is what is creased
                          return reply(crease_, srv);
                        },
                        [&](const core::RotateCall& c) {
                          Rotate srv;
                          srv.request.face = c.face;
                          srv.request.axis_edge = c.axis_edge;
                          srv.request.click = toPoint(c.click);
                          srv.request.angle = c.angle;
                          srv.request.commit = c.commit;
                          srv.request.picked_layers_only = c.picked_layers_only;
                          return reply(rotate_, srv);
                        },
                        [&](const core::FlatFoldCall& c) {
                          FlatFold srv;
                          for (const core::CreaseLineAngle& line : c.fold.creases)
                          {
                            srv.request.starts.push_back(onTable(line.start));
                            srv.request.ends.push_back(onTable(line.end));
                            srv.request.angles.push_back(line.angle);
                          }
                          srv.request.fixed = onTable(c.fold.fixed_point);
                          srv.request.commit = c.commit;
                          srv.request.fraction = c.fraction;
                          return reply(flat_fold_, srv);
                        },
                        [&](const core::DragVertexCall& c) {
                          DragVertex srv;
                          srv.request.vertex = c.vertex;
                          srv.request.position = toPoint(c.position);
                          srv.request.commit = c.commit;
                          core::PaperReply r = reply(drag_vertex_, srv);
                          // Bent paper reaches there, and a curved model listens to bend it.
                          r.curved_reaches =
                              r.answered && srv.response.curved_reaches && curved_drag_pub_.getNumSubscribers() > 0;
                          return r;
                        },
                        [&](const core::FoldByAssignmentCall& c) {
                          FoldByAssignment srv;
                          srv.request.fraction = c.fraction;
                          srv.request.preview = c.preview;
                          srv.request.keep = c.keep;
                          core::PaperReply r = c.preview ? keptReply(fold_previews_, fold_.getService(), srv) :
                                                           reply(fold_, srv);
                          r.revision = srv.response.revision;
                          if (r.answered)
                            r.angle_error = srv.response.angle_error;
                          return r;
                        },
                        [&](const core::CommandCall& c) {
                          std_srvs::Trigger srv;
                          ros::ServiceClient& client = c.command == core::PaperCommand::Squash   ? squash_ :
                                                       c.command == core::PaperCommand::Undo     ? undo_ :
                                                       c.command == core::PaperCommand::Redo     ? redo_ :
                                                       c.command == core::PaperCommand::KeepBend ? keep_bend_ :
                                                                                                   reset_;
                          return reply(client, srv);
                        },
                        [&](const core::PinCall& c) {
                          PinVertex srv;
                          srv.request.vertex = c.vertex;
                          srv.request.release = c.release;
                          return reply(pin_, srv);
                        },
                    },
                    request);
}

void InteractionNode::show(const core::GestureOutput& output)
{
  style_.drawn_top = model_.drawnTop();
  const ros::Time now = ros::Time::now();
  std::visit(Overloaded{
                 [&](const core::Guides& g) { markers_pub_.publish(guideMarkers(g, style_, now)); },
                 [&](const core::Picks& p) { markers_pub_.publish(picksMarkers(*model_.paper(), p, style_, now)); },
                 [&](const core::Message& m) { tell(m); },
                 [&](const core::ViewTurn& t) { view_turn_pub_.publish(viewTurnGoal(t, style_.frame_id, now)); },
                 [&](const core::CurvedHold& h) {
                   VertexTarget held;  // vertex -1: let go
                   held.header.frame_id = style_.frame_id;
                   held.header.stamp = now;
                   held.vertex = h.vertex;
                   held.position = toPoint(h.target);
                   curved_drag_pub_.publish(held);
                   if (h.vertex < 0)
                     markers_pub_.publish(bentSheetHidden(held.header));
                 },
                 [&](const core::SheetShown&) { showPaper(); },
                 [&](const core::SheetReleased& r) {
                   // rviz keeps the marker where the drag left it: put it back under the sheet.
                   geometry_msgs::Pose identity;
                   identity.orientation.w = 1.0;
                   server_.setPose(style_.marker_name, identity);
                   if (r.reshow)
                     showPaper();
                   else
                     server_.applyChanges();
                 },
                 [&](const core::SliderShown&) { showSlider(); },
                 [&](const core::SliderMoved& s) {
                   if (slider_shown_)
                     slider_pub_.publish(
                         sliderMarkers(track_, s.fraction, scaledTo(model_.paper(), slider_style_), now));
                 },
             },
             output);
}

void InteractionNode::showPaper()
{
  if (!model_.paper())
    return;
  const core::GestureMode mode = model_.mode();
  const std::string description = mode == core::GestureMode::Crease ? "crease: drag a line" :
                                  mode == core::GestureMode::Rotate ? "rotate: drag a face" :
                                  mode == core::GestureMode::Fold   ? "fold: click creases, then Fold" :
                                  mode == core::GestureMode::Flap   ? "flap: drag a flap where it should lie" :
                                                                      "drag: drag a vertex";
  style_.pick_lift = model_.shownLift();
  // With the camera known the drag plane faces the view: the pointer is on the mouse's sight
  // line wherever it goes (a plane along the sheet is missed by sight lines above its horizon).
  camera_known_ = camera(ros::Time::now()).has_value();
  style_.view_facing_drag = camera_known_;
  server_.insert(paperInteractiveMarker(*model_.paper(), description, style_),
                 [this](const Feedback::ConstPtr& f) { received(f); });
  setCheckMarks();
  server_.applyChanges();
}

void InteractionNode::showSlider()
{
  const std::optional<core::Paper>& paper = model_.paper();
  if (!slider_enabled_ || !paper)
    return;
  if (!core::hasDrivenCreases(*paper))
  {
    if (slider_shown_)
    {
      server_.erase(slider_style_.marker_name);
      server_.applyChanges();
      slider_pub_.publish(sliderRemoved(slider_style_, ros::Time::now()));
      slider_shown_ = false;
    }
    return;
  }
  const SliderStyle style = scaledTo(paper, slider_style_);
  track_ = sliderTrack(*paper, style);
  server_.insert(sliderHandle(track_, model_.sliderFraction(), style),
                 [this](const Feedback::ConstPtr& f) { received(f, {}, true); });
  server_.applyChanges();
  slider_pub_.publish(sliderMarkers(track_, model_.sliderFraction(), style, ros::Time::now()));
  slider_shown_ = true;
}

core::Vec3 InteractionNode::rightClick(const Feedback& feedback) const
{
  return feedback.mouse_point_valid ? core::Vec3(toVec3(feedback.mouse_point) - core::Vec3(0, 0, style_.pick_lift)) :
                                      core::Vec3::Zero();
}

void InteractionNode::tell(const core::Message& said)
{
  if (said.text.empty())
  {
    message_.clear();  // done, or nothing to do: an earlier refusal no longer applies
    return;
  }
  ROS_INFO("interaction: %s", said.text.c_str());
  message_ = forTheUser(said.text);
  const std::string lines = wrapLines(message_, kMessageWidth);
  const std::optional<core::Paper>& paper = model_.paper();
  const ros::Time now = ros::Time::now();
  switch (said.place)
  {
    case core::Message::Place::Beside:  // clear of the next click
      if (paper)
        markers_pub_.publish(messageMarker(lines, besideAnchor(*paper, lines, style_), style_, now));
      break;
    case core::Message::Place::At:
    case core::Message::Place::Slider: {
      const core::Vec3 at =
          said.place == core::Message::Place::Slider ? sliderPoint(track_, model_.sliderFraction()) : said.at;
      const core::Vec3 anchor = paper ? messageAnchor(*paper, at, lines, style_) : at;
      markers_pub_.publish(messageMarker(lines, anchor, style_, now));
      break;
    }
  }
}

std::string InteractionNode::toggleStrainColours()
{
  dynamic_reconfigure::Reconfigure srv;
  dynamic_reconfigure::BoolParameter colour;
  colour.name = "colour_by_strain";
  colour.value = !colour_by_strain_;
  srv.request.config.bools.push_back(colour);
  std::string message;
  if (!call(paper_model_reconfigure_, srv, message))
    return message;
  double scale = 0.0;
  for (const auto& b : srv.response.config.bools)
    if (b.name == "colour_by_strain")
      colour_by_strain_ = b.value;
  for (const auto& d : srv.response.config.doubles)
    if (d.name == "strain_scale")
      scale = d.value;
  showPaper();  // the menu's check mark
  if (!colour_by_strain_)
    return "faces in their front and back colours";
  char text[128];
  std::snprintf(text, sizeof text, "faces coloured by strain: blue none, red %g or more", scale);
  return text;
}

void InteractionNode::strainColoursChanged(const dynamic_reconfigure::Config::ConstPtr& config)
{
  for (const auto& b : config->bools)
    if (b.name == "colour_by_strain" && b.value != colour_by_strain_)
    {
      colour_by_strain_ = b.value;
      model_.refreshSheet();  // the check mark, after a drag
    }
}

void InteractionNode::curvedSheetReceived(const visualization_msgs::MarkerArray::ConstPtr& sheet)
{
  // Only the sheet bent since the drag began bending: the state's own sheet is the Curved
  // sheet display's.
  if (model_.state() != core::GestureState::Bending || sheet->markers.empty() ||
      sheet->markers.front().header.stamp < ros::Time::now() - ros::Duration(model_.timeInState()))
    return;
  visualization_msgs::MarkerArray shown = *sheet;
  for (visualization_msgs::Marker& m : shown.markers)
    m.ns = "bent_sheet" + m.ns.substr(std::string("curved_mesh").size());
  markers_pub_.publish(shown);
}

}  // namespace virtual_origami

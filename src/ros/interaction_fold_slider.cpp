// The interaction node's fold slider and strain colours (see interaction_node.h): the handle
// beside the sheet previews a fold by assignment while it moves and commits it on release.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include <dynamic_reconfigure/Reconfigure.h>
#include <virtual_origami/FoldByAssignment.h>

#include "virtual_origami/core/fold_fraction.h"
#include "virtual_origami/ros/conversions.h"
#include "virtual_origami/ros/interaction_node.h"

namespace virtual_origami
{
namespace
{
/// Fractions are committed to 0.1 %: what the percent shows is what is recorded.
double tidy(double fraction) { return std::round(std::clamp(fraction, 0.0, 1.0) * 1000.0) / 1000.0; }

template <class Service>
bool call(ros::ServiceClient& client, Service& srv, std::string& message)
{
  if (client.call(srv))
    return true;
  message = client.getService() + " did not answer; is paper_model running?";
  return false;
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
}  // namespace

void InteractionNode::showSlider()
{
  slider_changed_ = false;
  if (!slider_enabled_ || !paper_)
    return;
  if (!core::hasDrivenCreases(*paper_))
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
  const SliderStyle style = scaledTo(paper_, slider_style_);
  track_ = sliderTrack(*paper_, style);
  slider_fraction_ = committed_fraction_ && committed_fraction_->first == revision_ ? committed_fraction_->second :
                                                                                       core::foldFraction(*paper_);
  server_.insert(sliderHandle(track_, slider_fraction_, style),
                 [this](const Feedback::ConstPtr& f) { received(f, Action::None, true); });
  server_.applyChanges();
  slider_pub_.publish(sliderMarkers(track_, slider_fraction_, style, ros::Time::now()));
  slider_shown_ = true;
}

void InteractionNode::slide(const Feedback& feedback)
{
  if (!slider_shown_)
    return;
  switch (feedback.event_type)
  {
    case Feedback::MOUSE_DOWN:
      slider_dragging_ = true;
      slider_moved_ = false;
      fraction_at_press_ = slider_fraction_;
      slider_previewed_.reset();
      slider_refusal_.clear();
      break;
    case Feedback::POSE_UPDATE:
      if (!slider_dragging_)
        return;
      slider_fraction_ = tidy(sliderFraction(track_, toVec3(feedback.pose.position)));
      slider_moved_ = true;
      break;
    case Feedback::MOUSE_UP:
      if (!slider_dragging_)
        return;
      slider_fraction_ = tidy(sliderFraction(track_, toVec3(feedback.pose.position)));
      releaseSlider();
      break;
    default:
      break;
  }
}

void InteractionNode::updateSlider()
{
  const ros::WallTime start = ros::WallTime::now();
  slider_moved_ = false;
  slider_pub_.publish(sliderMarkers(track_, slider_fraction_, scaledTo(paper_, slider_style_), ros::Time::now()));
  // One preview per batch of feedback: the call waits for the solver, and the poses that came
  // meanwhile were coalesced into the latest, so previews go as fast as the solver keeps up.
  if (!slider_previewed_ || *slider_previewed_ != slider_fraction_)
  {
    FoldByAssignment srv;
    srv.request.fraction = slider_fraction_;
    srv.request.preview = true;
    std::string message;
    if (call(fold_, srv, message) && srv.response.success)
    {
      slider_previewed_ = slider_fraction_;
      slider_refusal_.clear();
    }
    else
    {
      slider_refusal_ = message.empty() ? srv.response.message : message;
      ROS_DEBUG("interaction: fold preview at %.3f refused: %s", slider_fraction_, slider_refusal_.c_str());
    }
  }
  ++applied_;
  apply_seconds_ = (ros::WallTime::now() - start).toSec();
}

void InteractionNode::releaseSlider()
{
  slider_dragging_ = false;
  std::string message;
  // A press without a move commits nothing; once a preview is drawn, the release commits.
  if (slider_previewed_ || slider_fraction_ != fraction_at_press_)
    message = foldByAssignment(slider_fraction_);
  if (!message.empty())
    tell(message, sliderPoint(track_, slider_fraction_));
  if (paper_changed_ && !dragging_)
    showPaper();
  if (slider_changed_)
    showSlider();
  else  // rviz keeps the handle where the drag left it; the percent stays with it
    slider_pub_.publish(sliderMarkers(track_, slider_fraction_, scaledTo(paper_, slider_style_), ros::Time::now()));
}

std::string InteractionNode::foldByAssignment(double fraction)
{
  FoldByAssignment srv;
  srv.request.fraction = fraction;
  srv.request.preview = false;
  std::string message;
  if (!call(fold_, srv, message))
    return message;
  if (srv.response.success)
    committed_fraction_ = std::make_pair(srv.response.revision, fraction);
  return srv.response.message;
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
      if (dragging_ || slider_dragging_)
        paper_changed_ = true;  // the check mark after the drag
      else
        showPaper();
    }
}

}  // namespace virtual_origami

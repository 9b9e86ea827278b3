// Markers that show the paper in rviz. Pure functions: a paper in, messages out.
#pragma once

#include <string>

#include <ros/time.h>
#include <std_msgs/ColorRGBA.h>
#include <visualization_msgs/MarkerArray.h>

#include "virtual_origami/core/paper.h"

namespace virtual_origami
{
struct MarkerStyle
{
  std::string frame_id = "paper";
  double layer_gap = 0.002;     // between coincident layers of a flat fold, in metres
  double side_offset = 0.0004;  // front and back surfaces of one layer, apart
  double line_width = 0.004;
  /// Both sides of every face in the colour of its strain (strain_colours.h) instead of the
  /// sheet's front and back colours: where a pattern does not fold rigidly.
  bool colour_by_strain = false;
  double strain_scale = 1e-2;  // the strain drawn full red
};

std_msgs::ColorRGBA rgba(float r, float g, float b, float a = 1.0f);

/// The start of every marker of this package: `type` in namespace `ns`, at the origin of
/// `frame_id` and locked to it, scaled by `scale` (a line's width) in `color`.
visualization_msgs::Marker baseMarker(const std::string& frame_id, const ros::Time& stamp, const std::string& ns,
                                      int type, double scale = 1.0, const std_msgs::ColorRGBA& color = rgba(1, 1, 1));

/// Namespaces: `front` and `back` (TRIANGLE_LIST, the two sides of every face in their own
/// colours or coloured by strain, coincident layers lifted by their stack level), `mountain`, `valley`, `crease`
/// (unassigned/flat), `boundary` (LINE_LIST).
visualization_msgs::MarkerArray paperMarkers(const core::Paper& paper, const MarkerStyle& style,
                                             const ros::Time& stamp);

}  // namespace virtual_origami

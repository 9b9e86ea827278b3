// The fold-by-assignment slider in rviz: a handle the mouse moves along a track beside the
// sheet, from 0 % (flat) to 100 % (every driven crease at its target). Pure functions: the
// handle is an interactive marker with one MOVE_AXIS control; the track and the percent are
// plain markers (they change during a drag, and re-sending an interactive marker then breaks it).
#pragma once

#include <string>

#include <ros/time.h>
#include <visualization_msgs/InteractiveMarker.h>
#include <visualization_msgs/MarkerArray.h>

#include "virtual_origami/core/paper.h"

namespace virtual_origami
{
struct SliderTrack
{
  core::Vec3 start = core::Vec3::Zero();  // 0 %
  core::Vec3 end = core::Vec3::UnitX();   // 100 %
};

struct SliderStyle
{
  std::string frame_id = "paper";
  std::string marker_name = "fold_slider";
  double gap = 0.15;  // of the sheet's scale, between the crease pattern and the track
  double handle_size = 0.04;
  double line_width = 0.006;
  double text_size = 0.04;
};

/// The track along x, under the crease pattern's lowest y by `gap`, as long as the crease pattern
/// is wide, in the table's plane z = 0. It stays put while the paper folds.
SliderTrack sliderTrack(const core::Paper& paper, const SliderStyle& style);

/// The fraction of the point's projection along the track, clamped to its ends: −1 (−100 %, the
/// opposite assignment, as Origami Simulator's slider offers) at the start, 0 (flat) at the
/// middle, 1 (100 %) at the end.
double sliderFraction(const SliderTrack& track, const core::Vec3& point);

/// The point of `fraction` (−1 to 1) on the track.
core::Vec3 sliderPoint(const SliderTrack& track, double fraction);

/// The handle at `fraction` along the track, movable only along it (its x axis).
visualization_msgs::InteractiveMarker sliderHandle(const SliderTrack& track, double fraction,
                                                   const SliderStyle& style);

/// The track (namespace `fold_slider_track`, a LINE_LIST whose first two points are its −100 %
/// and 100 % ends, then ticks every 25 %) and the percent over the handle (`fold_slider_percent`).
visualization_msgs::MarkerArray sliderMarkers(const SliderTrack& track, double fraction, const SliderStyle& style,
                                              const ros::Time& stamp);

/// Removes the slider's plain markers (a paper without driven creases has no slider).
visualization_msgs::MarkerArray sliderRemoved(const SliderStyle& style, const ros::Time& stamp);

}  // namespace virtual_origami

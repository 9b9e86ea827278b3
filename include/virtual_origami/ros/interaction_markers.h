// Markers of the mouse interaction. Pure functions: the paper or a drag in, messages out.
// The paper itself is an interactive marker the mouse presses and drags; everything shown
// while dragging (the drawn line, snapping guides, axis, ring) is a plain marker on a topic
// of its own, since re-sending an interactive marker during a drag breaks the drag.
#pragma once

#include <string>

#include <ros/time.h>
#include <visualization_msgs/InteractiveMarker.h>
#include <visualization_msgs/MarkerArray.h>

#include "virtual_origami/core/chosen_creases.h"
#include "virtual_origami/core/drag.h"
#include "virtual_origami/core/paper.h"

namespace virtual_origami
{
struct InteractionStyle
{
  std::string frame_id = "paper";
  std::string marker_name = "paper";
  double margin = 0.1;        // of the sheet's scale: a press just off the sheet still starts a line
  double line_width = 0.006;  // in metres
  double point_size = 0.025;
  double text_size = 0.04;
  /// The pickable copy of the sheet, all but invisible (paper_model's markers show the sheet):
  /// rviz gives a marker of alpha 0 a default colour of its own, half opaque.
  float pick_alpha = 0.01f;
  /// The pickable copies float this far off both sides of every face (along its normal): rviz
  /// picks the nearest surface, and the sheet's own markers (layers drawn apart) must not hide
  /// them from the mouse, from any view.
  double pick_lift = 0.005;
  /// How high paper_model draws the top layer of the paper (its layers drawn apart), below
  /// `pick_lift`.
  double drawn_top = 0.0;
  /// The drag plane through the grab point faces the view (the pointer stays on the mouse's
  /// sight line from any view); otherwise it lies along the sheet (z of `frame_id`).
  bool view_facing_drag = false;
};

/// The sheet as rviz's Interact tool sees it: its folded faces, each off both its sides by
/// `pick_lift`, and a margin around them as a TRIANGLE_LIST in one MOVE_PLANE control (drag
/// plane facing the view, or along z of `frame_id`). rviz reports mouse points on the copies:
/// along the sight line onto the paper (or, flat and seen from above, `pick_lift` down).
visualization_msgs::InteractiveMarker paperInteractiveMarker(const core::Paper& paper, const std::string& description,
                                                             const InteractionStyle& style);

// The drag's markers are drawn `pick_lift` above where they are, over the sheet's own markers.

/// The line being drawn from its snapped start to its snapped end, and the guides of Fig. 6:
/// the snapped points, an edge's division points, the angle's division directions.
visualization_msgs::MarkerArray creaseDragMarkers(const core::CreaseDrag& drag, const InteractionStyle& style,
                                                  const ros::Time& stamp);

/// The automatic axis highlighted, the ring about it through the press point (Fig. 10), the
/// spoke to where the pressed point is turned, and the angle in degrees.
visualization_msgs::MarkerArray rotationDragMarkers(const core::RotationRing& ring, double angle,
                                                    const InteractionStyle& style, const ros::Time& stamp);

/// The crease named as the axis by hand, highlighted until it is released (namespace `named_axis`).
visualization_msgs::MarkerArray namedAxisMarkers(const core::Vec3& a, const core::Vec3& b,
                                                 const InteractionStyle& style, const ros::Time& stamp);

/// Fold on chosen creases: the marked creases in their colours (valley blue, mountain red, unfold
/// grey dashed), the crease the last click picked highlighted, the face that stays outlined in
/// green (namespace `marks`).
visualization_msgs::MarkerArray chosenCreaseMarkers(const core::Paper& paper,
                                                    const std::vector<std::pair<int, core::CreaseMark>>& marks,
                                                    int picked_edge, int keep_face, const InteractionStyle& style,
                                                    const ros::Time& stamp);

/// The layer picked in a stack: the face outlined, or the vertex a drag holds (namespace `pick`).
visualization_msgs::MarkerArray pickMarkers(const core::Paper& paper, int face, int vertex,
                                            const InteractionStyle& style, const ros::Time& stamp);

/// A short text for the user at `at` (why a drag was refused, what the menu did), one or more
/// lines.
visualization_msgs::MarkerArray messageMarker(const std::string& text, const core::Vec3& at,
                                              const InteractionStyle& style, const ros::Time& stamp);

/// Where a text said about `at` stays over the paper, which the view shows: `at` moved inside
/// the paper's extent far enough for the text's lines to fit (centred there when they do not),
/// over its highest point.
core::Vec3 messageAnchor(const core::Paper& paper, const core::Vec3& at, const std::string& text,
                         const InteractionStyle& style);

/// Where a text about the pick stays: beside the paper, past the far edge of its extent along y,
/// so that it covers no place the user clicks on next (rviz gives a click on a text to the text).
core::Vec3 besideAnchor(const core::Paper& paper, const std::string& text, const InteractionStyle& style);

/// Removes every marker of the interaction (a DELETEALL).
visualization_msgs::MarkerArray clearedMarkers(const InteractionStyle& style, const ros::Time& stamp);

}  // namespace virtual_origami

// Mouse drags turned into operations (seed 000 §3.3): a drawn crease line with its snapping
// guides, and a face turning about its automatic axis with the angle read off a ring.
// Input is points in the `paper` frame: the press point on the folded surface and the pointer
// on the drag plane (the plane through the press point that the view projects the mouse onto).
#pragma once

#include <cmath>
#include <vector>

#include "virtual_origami/core/crease.h"
#include "virtual_origami/core/paper.h"
#include "virtual_origami/core/result.h"
#include "virtual_origami/core/rotate.h"
#include "virtual_origami/core/snap.h"

namespace virtual_origami::core
{
/// `point` moved along the view onto the face the eye sees there (seed §3.3.2 step 1: of the
/// faces under the pointer, the nearest to the eye; coincident layers by their stack order).
/// Mouse points from a depth buffer are off the surface by some millimetres; unchanged when
/// no face is there.
Vec3 onSurface(const Paper& paper, const Vec3& point, const Vec3& view_direction);

/// A crease being drawn, like a line in a 2D draw tool: both ends snapped (Fig. 6); the end
/// may snap to the angle divisions at the start when the start is a vertex.
struct CreaseDrag
{
  Snap start, end;
  /// The crease exactly as drawn: the snapped ends, no further snapping.
  CreaseRequest request() const;
  double length() const
  {
    return (end.point - start.point).norm();
  }
};

CreaseDrag creaseDrag(const Paper& paper, const Vec3& press, const Vec3& pointer, const SnapSettings& settings);

/// The ring a pressed face turns on (Fig. 10): in the plane perpendicular to the axis
/// through the press point P, centred on the axis. Angles on the ring are measured from `u`
/// (away from the axis, on P's side as seen) towards `w` (towards the viewer).
struct RotationRing
{
  int face = -1;
  int axis_edge = -1;
  std::vector<int> moving_faces;  // the flap that turns rigidly, or just `face` (the solver moves the rest)
  Vec3 axis_a = Vec3::Zero(), axis_b = Vec3::Zero();  // the axis crease's folded end points
  Vec3 press = Vec3::Zero();
  Vec3 centre = Vec3::Zero();  // foot of the press point on the axis line
  Vec3 u = Vec3::Zero(), w = Vec3::Zero();
  double radius = 0.0;
  double press_angle = 0.0;  // the press point on the ring, in [-π/2, π/2]
  /// Request angle (the axis crease's fold-angle change, positive valley) per radian the
  /// pressed point travels from u towards w.
  double turn_sign = 1.0;
  /// Request angles that keep every hinge crease within ±180° (past that layers would cross).
  double min_angle = -2 * M_PI, max_angle = 2 * M_PI;
  /// True when the view looks at the ring nearly edge-on (the seed's Fig. 11 case, and always
  /// so from straight above a flat sheet): the angle then follows the pointer's distance
  /// from the axis instead of its direction around the ring.
  bool edge_on = false;
};

/// The face under the press (or `face`), its automatic axis (or `axis_edge`) and the ring.
/// `view_direction` points from the eye into the scene. Fails when nothing is under the
/// press, the face has no crease to turn about, or the press lies on the axis.
/// The ring's limits are those of the faces the turn carries each way (`carry_stack` as in
/// RotateRequest).
Expected<RotationRing> rotationRing(const Paper& paper, const Vec3& press, const Vec3& view_direction, int face = -1,
                                    int axis_edge = -1, bool carry_stack = true);

/// How near a half turn the pointer's angle snaps to it (radians, 3°).
constexpr double kHalfTurnSnap = 3.0 * M_PI / 180.0;

/// The request angle for the pointer, within the ring's limits. Seen from the side, the
/// pointer's ray meets the ring's plane and the angle follows it around (unwrapped next to
/// `previous`). Seen edge-on, the pointer's distance from the axis maps linearly onto a half
/// turn: at the press point 0, over the axis a quarter turn, at the mirror image of the
/// press point a half turn — every angle is reachable at the same rate, where following the
/// projection would jump near 0° and 180° (the seed turns the view there; a server cannot).
/// Within kHalfTurnSnap of a half turn the angle is exactly ±π (where the ring's limits allow).
double ringAngle(const RotationRing& ring, const Vec3& pointer, const Vec3& view_direction, double previous = 0.0);

/// Where the pressed point is when the face has turned by the request angle `angle`.
Vec3 ringPoint(const RotationRing& ring, double angle);

}  // namespace virtual_origami::core

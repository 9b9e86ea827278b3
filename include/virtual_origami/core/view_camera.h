// The view the mouse works in: rviz's camera (broadcast by the virtual_origami/ViewCamera
// display) as the gestures see it, and the seed's view turn (seed 000 §3.3.3, Fig. 11).
// Plain geometry in the `paper` frame.
#pragma once

#include <optional>

#include <Eigen/Geometry>

#include "virtual_origami/core/paper.h"

namespace virtual_origami::core
{
/// A camera: the eye and its axes as columns (x right, y down, z along the line of sight).
struct ViewCamera
{
  Vec3 eye = Vec3::Zero();
  Eigen::Matrix3d axes = Eigen::Matrix3d::Identity();

  /// The line of sight through `point`, from the eye.
  Vec3 rayTo(const Vec3& point) const
  {
    return (point - eye).normalized();
  }
  Vec3 forward() const
  {
    return axes.col(2);
  }
};

/// Where the line of sight through `point` meets the plane through `origin` with normal
/// `normal`; none when it runs along the plane or meets it behind the eye.
std::optional<Vec3> alongSightOnto(const ViewCamera& camera, const Vec3& point, const Vec3& origin, const Vec3& normal);

/// The seed's view turn: when the line of sight to the press P runs nearly across the axis
/// direction d, a face turning about d jumps with small pointer moves. The camera turned
/// about the line through the face centre C and P (the smallest turn, up to 75°, either
/// way) until the sight line to P meets d at |cos| ≥ `min_cos`, then levelled (rviz's orbit
/// views have no roll) and moved so that P keeps its place in the picture (its camera
/// coordinates stay). Where no turn about C–P reaches (a low oblique view, C–P near the sight
/// line), the camera orbits about the vertical through P and tilts, the smallest turn first, so
/// an edge-on ring gets a usable view from any view. None when the view is fine as it is or no
/// such turn exists.
std::optional<ViewCamera> turnedView(const ViewCamera& camera, const Vec3& press, const Vec3& centre,
                                     const Vec3& axis_direction, double min_cos = 0.6);

}  // namespace virtual_origami::core

// Rigid-origami kinematics: folded positions from fold angles (exact, zero strain).
#pragma once

#include <vector>

#include <Eigen/Geometry>

#include "virtual_origami/core/paper.h"
#include "virtual_origami/core/result.h"

namespace virtual_origami::core
{
/// The rigid transform taking a face from the crease pattern (x, y, 0) to its folded pose,
/// fitted to its current folded vertices (least squares, Kabsch).
Eigen::Isometry3d facePose(const Paper& paper, int face);

/// The turn of the face across `edge` from `face` by `fold_angle` (radians, FOLD sign), in
/// crease-pattern coordinates: with the edge's left face held, the right face turns by
/// −fold_angle about its first vertex → its second.
Eigen::Isometry3d hingeTransform(const Paper& paper, int edge, int face, double fold_angle);

/// Places every face by composing rigid turns about the creases along a spanning tree of
/// faces from `root_face` (which gets `root_pose`), each crease turned by its entry of
/// `fold_angles` (radians, FOLD sign). Fails, naming the vertex, when the angles do not
/// close (two faces put a shared vertex more than `tolerance` apart).
Expected<std::vector<Vec3>> foldedPositionsFromAngles(const Paper& paper, const std::vector<double>& fold_angles,
                                                      int root_face, const Eigen::Isometry3d& root_pose,
                                                      double tolerance);

}  // namespace virtual_origami::core

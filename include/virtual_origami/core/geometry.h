// Small geometric helpers over Eigen values.
#pragma once

#include <vector>

#include "virtual_origami/core/paper.h"
#include "virtual_origami/core/positions.h"

namespace virtual_origami::core
{
/// `point` turned by `angle` (right hand) about the line through `origin` along unit `axis`.
Vec3 rotateAbout(const Vec3& point, const Vec3& origin, const Vec3& axis, double angle);

/// Distance from a point to the segment [a, b].
double pointSegmentDistance(const Vec3& point, const Vec3& a, const Vec3& b);

/// Closest point of the folded face to `point`, and whether `point` projects inside it.
struct FaceProjection
{
  Vec3 closest = Vec3::Zero();
  double distance = 0.0;
  bool inside = false;  // the projection onto the face's plane falls inside the polygon
};
FaceProjection projectOntoFace(const Paper& paper, int face, const Vec3& point);

/// The face under `point`: of the faces within `max_distance`, the one whose plane passes
/// nearest, ties broken towards the top (largest z). -1 if none.
int faceAt(const Paper& paper, const Vec3& point, double max_distance);

bool allFinite(const Vec3& v);

/// The rotation that best turns centred points onto centred targets (least squares, Kabsch),
/// from their covariance Σ (p − p̄)(q − q̄)ᵀ: a proper one (no mirror), also where the points lie
/// in a plane.
Eigen::Matrix3d bestFitRotation(const Eigen::Matrix3d& covariance);

/// How far apart two shapes of the same points are, wherever each lies (two pins leave a sheet
/// free to turn about their line): the distances of corresponding points (columns) after the
/// rigid motion that best fits `points` onto `target` (Kabsch).
struct ShapeDistance
{
  double rms = 0.0;
  double largest = 0.0;
};
ShapeDistance shapeDistance(const Positions& points, const Positions& target);

}  // namespace virtual_origami::core

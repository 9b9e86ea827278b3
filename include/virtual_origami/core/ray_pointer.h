// The pointer of a tool that reports the line of sight through the mouse (rviz's Fold tool,
// ToolEvent) rather than a point on the sheet marker: turned into the gesture model's Pointer
// exactly as rviz's Interact tool reports the sheet marker (interaction_markers.cpp). The mouse
// point lies on the pickable copy, `lift` towards the eye from the face the eye sees, or on the
// margin around the paper; a drag moves the marker on the plane through the grab point facing
// the camera (the sheet control's VIEW_FACING MOVE_PLANE). One gesture at a time: a press grabs,
// a release or `letGo` lets go.
#pragma once

#include <optional>

#include "virtual_origami/core/gesture_model.h"
#include "virtual_origami/core/paper.h"
#include "virtual_origami/core/view_camera.h"

namespace virtual_origami::core
{
/// The line of sight through the mouse: from the camera's eye along `direction`.
struct SightRay
{
  ViewCamera camera;
  Vec3 direction = Vec3::UnitZ();
};

/// How the sheet marker lies over the paper: its lift over the faces and its margin (a
/// fraction of the paper's scale) on the table around them.
struct PickableSheet
{
  double lift = 0.005;
  double margin = 0.1;
};

/// Where the sight line meets the pickable sheet: on the face the eye sees there, `lift` towards
/// the eye, else on the margin; none off the paper and its margin (where rviz picks no marker)
/// or for a ray that is not finite.
std::optional<Vec3> sheetPointOnRay(const Paper& paper, const SightRay& ray, const PickableSheet& sheet);

class RayPointer
{
public:
  /// A press: the pointer at the point the ray meets (none: the press misses the paper, as a
  /// click beside the sheet marker in rviz sends no feedback); grabs it for the drag.
  Pointer press(const Paper& paper, const SightRay& ray, const PickableSheet& sheet);
  /// A move of the held press: the marker on the drag plane.
  Pointer move(const SightRay& ray);
  /// The release: as a move, with the point the ray meets; lets go.
  Pointer release(const Paper& paper, const SightRay& ray, const PickableSheet& sheet);
  /// A pointer without a drag (the wheel, a key, a double click): the point the ray meets.
  static Pointer at(const Paper& paper, const SightRay& ray, const PickableSheet& sheet);
  void letGo()
  {
    grab_.reset();
    moved_ = Vec3::Zero();
  }
  bool holding() const
  {
    return grab_.has_value();
  }

private:
  std::optional<Vec3> grab_;
  Vec3 moved_ = Vec3::Zero();  // the marker's last position on the drag plane
};

}  // namespace virtual_origami::core

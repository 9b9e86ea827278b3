// What the FOLD reader and writer agree on beyond the FOLD specification: this project's own
// fields, and fold angles in degrees. Private to fold_reader.cpp and fold_writer.cpp.
#pragma once

#include <cmath>

namespace virtual_origami::core
{
/// Our own frame field: the crease pattern of a standalone folded-form frame.
inline constexpr const char* kCreasePatternKey = "virtual_origami:vertices_creasePattern";
// Where each crease is meant to go (Edge::target_angle), degrees or null: kept apart from
// edges_foldAngle, which says where the creases are in the frame written.
inline constexpr const char* kTargetAngleKey = "virtual_origami:edges_targetFoldAngle";
// Which edges are facets (compliant_faces.h: inside a face of the paper, bending without being
// creases; a kept bend's mesh), true or false: written only when a facet is in the file.
inline constexpr const char* kFacetKey = "virtual_origami:edges_facet";

inline double toRadians(double degrees)
{
  return degrees * (M_PI / 180.0);
}

/// The degrees whose conversion back by toRadians gives exactly `radians` when a nearby double
/// does, so fold angles survive a write and read bit for bit.
inline double toDegrees(double radians)
{
  const double degrees = radians * (180.0 / M_PI);
  double up = degrees, down = degrees;
  for (int step = 0; step < 8; ++step)
  {
    if (toRadians(up) == radians)
      return up;
    if (toRadians(down) == radians)
      return down;
    up = std::nextafter(up, HUGE_VAL);
    down = std::nextafter(down, -HUGE_VAL);
  }
  return degrees;
}

}  // namespace virtual_origami::core

// Creasing (seed 000 §3.3.1): a drawn line cuts every face it crosses completely, in
// every layer under it; new vertices at the crossings, faces split, edges re-wired.
#pragma once

#include <optional>
#include <vector>

#include "virtual_origami/core/paper.h"
#include "virtual_origami/core/result.h"
#include "virtual_origami/core/snap.h"

namespace virtual_origami::core
{
struct CreaseRequest
{
  Vec3 start = Vec3::Zero();  // in the `paper` frame, on the folded surface
  Vec3 end = Vec3::Zero();
  /// With an eye point the cut is the wedge between the rays from the eye through the two
  /// ends; without, the strip of the plane through the line and the top face's normal.
  std::optional<Vec3> eye;
  bool snap = false;
};

struct CreaseResult
{
  std::vector<int> new_edges;     // the new crease edges
  std::vector<int> new_vertices;
  std::vector<int> split_faces;   // faces that were cut (each keeps its id for one half)
  Snap start_snap, end_snap;      // what snapping did to the two ends
};

/// Creases `paper` in place on success; on failure it is untouched and the message says why.
Expected<CreaseResult> crease(Paper& paper, const CreaseRequest& request, const SnapSettings& snap_settings = {});

}  // namespace virtual_origami::core

// Folds that move several creases at once and end flat: squash, petal and reverse folds.
// A simple rotation turns one flap about one line; these fold creases on different lines
// together, so no single turn can make them. The new state follows from the fold angles alone
// (rigid faces, kinematics.h): the creases named go to their new angles, every other crease
// keeps its angle, and the faces are placed from one face that stays where it is.
#pragma once

#include <vector>

#include "virtual_origami/core/paper.h"
#include "virtual_origami/core/result.h"

namespace virtual_origami::core
{
/// Every crease edge lying on the crease-pattern segment [start, end] gets `angle` (radians,
/// FOLD sign: π valley flat, −π mountain flat, 0 unfolded).
struct CreaseLineAngle
{
  Vec2 start = Vec2::Zero();
  Vec2 end = Vec2::Zero();
  double angle = 0.0;
};

struct FlatFoldRequest
{
  std::vector<CreaseLineAngle> creases;
  /// The face under this crease-pattern point keeps its folded place.
  Vec2 fixed_point = Vec2::Zero();
};

struct FlatFoldResult
{
  std::vector<int> changed_edges;  // creases whose angle the request set to a new value
  std::vector<int> moved_faces;    // faces whose folded place changed
};

/// Sets the named creases' angles and re-places every face rigidly from the fixed face. Fails,
/// leaving `paper` untouched, when a segment names no crease, an angle is outside [−π, π],
/// the fixed point is off the sheet, or the angles do not close (a vertex would tear: the
/// request is not a fold of this paper). Layer orders between faces that moved and faces that
/// did not are dropped (a flat fold re-stacks them; the faces' 3D places stay exact).
Expected<FlatFoldResult> flatFold(Paper& paper, const FlatFoldRequest& request);

}  // namespace virtual_origami::core

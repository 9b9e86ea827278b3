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

/// The face whose crease-pattern polygon holds `point` (the face that stays is named so), or -1.
int faceContaining(const Paper& paper, const Vec2& point);

/// Sets the named creases' angles and re-places every face rigidly from the fixed face (whose
/// vertices keep their positions bit for bit). Fails,
/// leaving `paper` untouched, when no crease is named, a segment names no crease, a value is
/// not finite, an angle is outside [−π, π], the fixed point is off the sheet, or the angles do
/// not close (a vertex would tear: the request is not a fold of this paper; the message then
/// begins "the chosen creases do not fold flat"). Layer orders between faces that moved and
/// faces that did not are dropped (a flat fold re-stacks them; the faces' 3D places stay exact).
Expected<FlatFoldResult> flatFold(Paper& paper, const FlatFoldRequest& request);

/// The paper `fraction` (0 to 1) of the way through the flat fold `request`, for a preview that
/// shows the faces turning: exactly `paper` at 0 and exactly flatFold's result at 1; fails as
/// flatFold does (and on a fraction outside [0, 1]), so a frame is shown only of a fold that can
/// be made.
///
/// In between, every crease's fold angle goes linearly from its current value to its final one,
/// and each face is placed by the turns about the creases along the walk (walkFaces) from the
/// fixed face, as the final fold is (kinematics.h): the face's rigid motion from its current
/// place is the one those turns give, applied to its current vertices. The fixed face never
/// moves. A fold of several creases at once (a squash, a petal fold) does not stay rigid in
/// between: faces the walk reaches along different creases may put a shared vertex in
/// different places. Such a vertex goes where the face reached first (fewest creases from the
/// fixed face) puts it, the faces as far as that from the fixed face averaged: the faces near
/// the fixed face turn rigidly, the far ones stretch a little until the fold closes at 1.
/// Crease angles in the frame are the interpolated ones; layer orders are the current ones
/// without the pairs the fold separates (as flatFold drops them).
Expected<Paper> flatFoldFrame(const Paper& paper, const FlatFoldRequest& request, double fraction);

}  // namespace virtual_origami::core

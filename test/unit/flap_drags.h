// Drags of the crane's flaps (crane_reference.h) as a person makes them: pressed at a point of
// the flap and let go where the reference folding puts that point, the face that stays (the one
// compound_fold.h keeps) in its place. For compound_fold_test and gesture_model_test.
#pragma once

#include <Eigen/Geometry>

#include "crane_reference.h"
#include "virtual_origami/core/compound_fold.h"
#include "virtual_origami/core/flat_fold.h"
#include "virtual_origami/core/kinematics.h"

namespace virtual_origami::core::test
{
/// `after` moved rigidly so that `face` lies where it lies in `before` (the same topology).
inline Paper alignedOn(const Paper& after, const Paper& before, int face)
{
  const std::vector<int>& vs = before.faces[face].vertices;
  Eigen::Matrix3Xd from(3, vs.size()), to(3, vs.size());
  for (size_t i = 0; i < vs.size(); ++i)
  {
    from.col(static_cast<Eigen::Index>(i)) = after.vertices[vs[i]].folded;
    to.col(static_cast<Eigen::Index>(i)) = before.vertices[vs[i]].folded;
  }
  Eigen::Isometry3d motion;
  motion.matrix() = Eigen::umeyama(from, to, false);
  Paper out = after;
  for (Vertex& v : out.vertices)
    v.folded = motion * v.folded;
  return out;
}

/// Largest distance between the same vertices of two states.
inline double largestOffset(const Paper& a, const Paper& b)
{
  double largest = 0.0;
  for (size_t v = 0; v < a.vertices.size(); ++v)
    largest = std::max(largest, (a.vertices[v].folded - b.vertices[v].folded).norm());
  return largest;
}

struct FlapDrag
{
  int face = -1;               // the face pressed
  Vec3 press = Vec3::Zero();   // where
  Vec3 target = Vec3::Zero();  // where the reference puts that point, the face that stays in place
  Paper after;                 // the reference's state after the step, that face in place
};

/// The drag of the reference's step `step` (1-based) pressing the crease-pattern point `cp`.
inline FlapDrag flapDrag(const std::vector<Paper>& states, int step, const Vec2& cp)
{
  const Paper& before = states[step - 1];
  FlapDrag drag;
  drag.face = faceContaining(before, cp);
  drag.press = facePose(before, drag.face) * Vec3(cp.x(), cp.y(), 0.0);
  const Expected<CompoundFolds> folds = CompoundFolds::at(before, drag.face, drag.press);
  drag.after = alignedOn(states[step], before, folds ? folds->fixedFace() : drag.face);
  drag.target = facePose(drag.after, drag.face) * Vec3(cp.x(), cp.y(), 0.0);
  return drag;
}

}  // namespace virtual_origami::core::test

// A fold by one drag (compound_fold.h) checked against a reference script's flat fold: the flap
// pressed at a crease-pattern point and dragged to where the script's next state puts that
// point infers the script's fold — the same creases with the same directions, of the kind a
// person calls it — and folds the script's paper to 1e-6. For the models' tests
// (flapping_bird_test, frog_base_test); compound_fold_test checks the crane the same way.
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "flap_drags.h"
#include "virtual_origami/core/compound_fold.h"
#include "virtual_origami/core/fold_sequence.h"
#include "virtual_origami/core/geometry.h"

namespace virtual_origami::core::test
{
/// The script's angle for the crease `line` (a crease edge's ends), or NaN when it names none.
inline double scriptAngle(const FlatFoldRequest& script, const CreaseLineAngle& line)
{
  const auto on = [](const Vec2& p, const CreaseLineAngle& l) {
    return pointSegmentDistance(Vec3(p.x(), p.y(), 0), Vec3(l.start.x(), l.start.y(), 0),
                                Vec3(l.end.x(), l.end.y(), 0)) < 1e-9;
  };
  for (const CreaseLineAngle& r : script.creases)
    if (on(line.start, r) && on(line.end, r))
      return r.angle;
  return NAN;
}

/// Drags the flap at `cp` in step `step` (1-based) of `script` (its states `states`) to where the
/// script puts it and checks the fold inferred against the script's.
inline void expectTheScriptsFold(const FoldSequence& script, const std::vector<Paper>& states, int step, const Vec2& cp,
                                 CompoundKind kind)
{
  SCOPED_TRACE("step " + std::to_string(step) + ": " + script.steps[step - 1].note);
  ASSERT_EQ(script.steps[step - 1].operation.kind, Operation::Kind::FlatFold);
  const Paper& before = states[step - 1];
  const FlapDrag drag = flapDrag(states, step, cp);
  ASSERT_GE(drag.face, 0) << "no face at (" << cp.transpose() << ")";
  Expected<CompoundFolds> folds = CompoundFolds::at(before, drag.face, drag.press);
  ASSERT_TRUE(folds.ok()) << folds.message();
  const auto chosen = folds->nearestResolved(drag.target);
  ASSERT_TRUE(chosen.has_value()) << "the drag folds nothing";
  const auto& [choice, fold] = *chosen;
  EXPECT_LT(choice.miss, 1e-9);
  EXPECT_NEAR(choice.fraction, 1.0, 1e-9);
  EXPECT_EQ(fold.kind, kind) << compoundKindName(fold.kind);
  // The script's creases, each with the script's direction, and no other.
  const FlatFoldRequest& reference = script.steps[step - 1].operation.flat_fold;
  size_t reference_edges = 0;
  for (const Edge& e : before.edges)
  {
    const CreaseLineAngle edge{ before.vertices[e.vertices[0]].crease_pattern,
                                before.vertices[e.vertices[1]].crease_pattern, 0.0 };
    reference_edges += e.isCrease() && !std::isnan(scriptAngle(reference, edge));
  }
  EXPECT_EQ(fold.request.creases.size(), reference_edges);
  for (const CreaseLineAngle& line : fold.request.creases)
    EXPECT_EQ(line.angle, scriptAngle(reference, line))
        << "(" << line.start.transpose() << ")–(" << line.end.transpose() << ")";
  // The paper it folds: the script's, the face that stays in place.
  Paper folded = before;
  const Expected<FlatFoldResult> result = flatFold(folded, fold.request);
  ASSERT_TRUE(result.ok()) << result.message();
  EXPECT_LE(largestOffset(folded, drag.after), 1e-6);
  EXPECT_FALSE(folded.face_orders.empty());  // the layers stacked
}

}  // namespace virtual_origami::core::test

// Pressing the model flat (seed 000 §3.4).
#pragma once

#include "virtual_origami/core/paper.h"
#include "virtual_origami/core/result.h"
#include "virtual_origami/core/shape_solver.h"

namespace virtual_origami::core
{
struct SquashResult
{
  bool exact = false;  // flattened rigidly (every crease to 0 or ±180°) without a solver
  SolveReport solve;   // when the seed's way was taken: project to the table, then solve
};

/// Presses the model onto the table plane (z = 0 of `paper`). First rigidly: every crease
/// goes to the nearer of 0 and ±180°, and the faces are placed by those angles from the
/// most level face, which is exact when the result closes. Otherwise as in the seed: every
/// vertex is dropped onto the table and `solver` restores the face shapes; without a
/// solver that fails. On failure `paper` is untouched.
Expected<SquashResult> squash(Paper& paper, ShapeSolver* solver = nullptr);

}  // namespace virtual_origami::core

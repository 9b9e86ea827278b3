// How far a paper is folded by assignment, read back from its crease angles: where the fold
// slider's handle sits, and where a replay's animation of a fold by assignment starts.
#pragma once

#include "virtual_origami/core/paper.h"

namespace virtual_origami::core
{
/// The fraction f that best fits every driven crease's fold angle to f · its target
/// (creaseTargets; least squares), clamped to −1 to 1 (−1: every crease at the opposite of its target); 0 without driven creases.
double foldFraction(const Paper& paper);

/// True when some crease has a target (creaseTargets) to fold towards.
bool hasDrivenCreases(const Paper& paper);

}  // namespace virtual_origami::core

// Keeping the layer order of flat-folded states (FOLD `faceOrders`) as the paper is creased
// and folded: which faces lie flat on each other, and which is above.
#pragma once

#include <vector>

#include "virtual_origami/core/paper.h"

namespace virtual_origami::core
{
/// Whether two faces lie flat on each other: in one plane (normals parallel or opposite)
/// and overlapping with positive area. `tolerance` is a length.
bool facesStacked(const Paper& paper, int face, int other, double tolerance);

/// Where `other` lies relative to `face` by the recorded orders, FOLD sign: +1 above (on
/// the side `face`'s front normal points to), −1 below, 0 when no entry names the pair. An
/// entry recorded the other way round is turned into this one.
int faceOrder(const Paper& paper, int face, int other);

/// Records `other` above (+1) or below (−1) `face`, replacing any entry of the pair.
void setFaceOrder(Paper& paper, int face, int other, int above);

/// Drops every entry of a pair that involves a face in `faces` (one flag per face) and one
/// outside it.
void clearFaceOrdersAcross(Paper& paper, const std::vector<char>& faces);

/// Drops the entries whose faces no longer lie stacked (or that name missing faces).
void pruneFaceOrders(Paper& paper, double tolerance);

/// After a crease split `parent`, leaving part of it as `child`: the child gets the parent's
/// entries (it lies where the parent lay, facing the same way). Entries of pairs that no
/// longer overlap are for pruneFaceOrders to drop.
void inheritFaceOrders(Paper& paper, int parent, int child);

}  // namespace virtual_origami::core

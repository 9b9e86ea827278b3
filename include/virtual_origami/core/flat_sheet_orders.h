// Paper continues across a crease left unfolded (0°): the two faces beside it are one flat sheet,
// and a sheet cannot change sides of another layer where it continues. The layer-order rules of
// layer_order.h judge folded creases; this checks a recorded order at the unfolded ones (the
// tortilla–tortilla rule of flat-folding).
#pragma once

#include <string>
#include <vector>

#include "virtual_origami/core/paper.h"

namespace virtual_origami::core
{
/// Two stacked pairs whose orders (FOLD sign, each along its first face's front normal) must
/// agree and do not: order(face, other) must be `relation` × order(face2, other2). `face` and
/// `face2` are one flat sheet across an unfolded crease, as are `other` and `other2` (or `other2`
/// is `other` itself, a layer the crease runs through; relation +1); or `face` and `face2` are
/// the two faces of a fold and `other` = `other2` a sheet flat across the fold's line, which may
/// not lie between them (relation −1: the fold's faces face opposite ways).
struct SheetOrderClash
{
  int face = -1, other = -1;
  int face2 = -1, other2 = -1;
  int relation = 1;
  /// Names the faces and where they lie on the sheet.
  std::string message;
};

/// Every clash of `paper`'s recorded orders (pairs with no recorded order are not judged):
/// - a layer that an unfolded crease runs through (inside it, off its sides) lies on one side
///   of both faces of the crease;
/// - two sheets flat across unfolded creases on one line of the folded paper keep one order on
///   both sides of it;
/// - a sheet flat across an unfolded crease on the line of a fold does not lie between the fold's
///   two faces (it would go through the fold's bend).
/// `tolerance` is a length (as facesStacked).
std::vector<SheetOrderClash> sheetOrderClashes(const Paper& paper, double tolerance);

}  // namespace virtual_origami::core

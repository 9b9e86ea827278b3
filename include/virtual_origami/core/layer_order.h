// The layer order of a flat-folded state: which of two overlapping faces lies on top, for every
// pair, found from what paper cannot do rather than from how it got there. A face folded flat
// over a crease lies on the side its mountain or valley says; no layer passes through a fold
// (taco–taco, taco–tortilla); with `unfolded_sheets`, faces joined by an unfolded (0°) crease are
// one flat sheet, which no layer passes through either: a layer lies above both or below both
// where it meets them there, two such sheets keep one order on both sides of their line
// (tortilla–tortilla), and such a sheet does not lie between the two faces of a fold on its line;
// and three overlapping layers stack one way (transitivity). The pairs are
// boolean variables, the rules clauses, solved by unit propagation and backtracking.
#pragma once

#include <vector>

#include "virtual_origami/core/paper.h"
#include "virtual_origami/core/result.h"

namespace virtual_origami::core
{
struct LayerOrderOptions
{
  /// Pairs whose order is known and must hold (e.g. layers that moved together in a fold).
  std::vector<FaceOrder> kept;
  /// A length: faces within it of one plane and overlapping by more than it are stacked.
  double tolerance = 1e-7;
  /// The search gives up after this many guesses (a stack with no order found in time is
  /// reported as such, not as impossible).
  long max_guesses = 200000;
  /// Stacks of more faces than this are not ordered (the checks grow with its cube: a flat
  /// Miura-ori of 100 faces in one stack takes 0.08 s, of 400 faces 1.3 s).
  int max_faces = 250;
  /// Stacks of more overlapping pairs than this are not ordered either (0: no such bound). The
  /// checks grow with the overlapping triples, which a sparse stack has few of: a flat-folded
  /// waterbomb tessellation's stack of 330 faces (16,049 pairs) is ordered in 0.36 s, a flat
  /// Miura-ori's of 156 faces, every pair overlapping (12,090), in 0.47 s. The search for stacks
  /// stops as soon as one has more, so a sheet folded flat into millions of pairs is answered at
  /// once.
  int max_pairs = 0;
  /// Whether faces joined by an unfolded crease are held to be one sheet (tortilla–tortilla).
  /// flatFold holds them so (the crane, flapping bird and frog base scripts obey it), and so does
  /// fold by assignment for its flat results (on Origami Simulator's library it changes none);
  /// off by default for the other callers.
  bool unfolded_sheets = false;
};

struct LayerOrder
{
  /// One entry per stacked pair, FOLD sign (faceOrders).
  std::vector<FaceOrder> orders;
  int stacked_pairs = 0;
  /// False when a stack was too large or the search gave up: `orders` then leaves that stack out
  /// and `incomplete` says why.
  bool complete = true;
  std::string incomplete;
};

/// Orders every pair of stacked faces of `paper` (folded positions and fold angles as they are;
/// creases within kFlatAngleTolerance of ±π count as folded flat). Fails only when no order
/// exists (no stacking of the layers folds flat), naming a rule that clashes (faces by id and
/// where they lie on the sheet, creases by id and crease-pattern ends).
Expected<LayerOrder> solveLayerOrder(const Paper& paper, const LayerOrderOptions& options = {});

/// Whether `orders` obey the rules above for `paper` (a check of any recorded order): empty when
/// they do, else what breaks. `unfolded_sheets`: as LayerOrderOptions says.
std::string layerOrderViolation(const Paper& paper, const std::vector<FaceOrder>& orders, double tolerance = 1e-7,
                                bool unfolded_sheets = false);

}  // namespace virtual_origami::core

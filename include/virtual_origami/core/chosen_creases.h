// Fold on chosen creases (SPEC §3.7): the user marks creases of the folded model valley,
// mountain or unfold and picks the face that stays; the marks become a flat fold (flat_fold.h).
#pragma once

#include <optional>
#include <vector>

#include "virtual_origami/core/flat_fold.h"
#include "virtual_origami/core/paper.h"

namespace virtual_origami::core
{
enum class CreaseMark
{
  None,
  Valley,
  Mountain,
  Unfold,
};

/// The mark a click on a marked crease gives it: valley, mountain, unfold, none, valley, …
CreaseMark nextMark(CreaseMark mark);

/// A marked crease, by its ends in the crease pattern (edge ids change when the paper does).
struct MarkedCrease
{
  Vec2 start = Vec2::Zero(), end = Vec2::Zero();
  CreaseMark mark = CreaseMark::None;
};

/// The marks the user made, at most one per crease.
class CreaseMarks
{
public:
  /// The crease's mark now (None when unmarked or not a crease).
  CreaseMark markOf(const Paper& paper, int edge) const;
  /// Marks `edge` (None: unmarks it).
  void mark(const Paper& paper, int edge, CreaseMark mark);
  void clear() { marks_.clear(); }
  bool empty() const { return marks_.empty(); }
  const std::vector<MarkedCrease>& marks() const { return marks_; }
  /// The marked creases of `paper` with their marks (marks of creases it no longer has left out).
  std::vector<std::pair<int, CreaseMark>> edges(const Paper& paper) const;

private:
  std::vector<MarkedCrease> marks_;
};

/// The angle a mark asks for: ±`fold` for valley and mountain (π: flat; π/2: a right angle),
/// 0 for unfold.
double markAngle(CreaseMark mark, double fold = M_PI);

/// A crease-pattern point inside `face` (its crease-pattern centroid): where a face is named by
/// a point, as the flat fold's face that stays is.
Vec2 creasePatternPoint(const Paper& paper, int face);

/// The flat fold the marks ask for, the face under `fixed_face`'s crease-pattern centroid
/// staying. Empty when nothing is marked.
std::optional<FlatFoldRequest> chosenCreasesFold(const Paper& paper, const CreaseMarks& marks, int fixed_face,
                                                 double fold = M_PI);

}  // namespace virtual_origami::core

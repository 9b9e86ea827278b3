// Folds by one drag, as paper is folded (seed 000 Fig. 14: a squash and a petal fold made by
// turning one face and letting the others follow). The user presses a flap of the flat model
// and drags it to where it should lie; the creases are inferred: among the flat folds that
// change only creases around the pressed face — the creases at one of its corners (a squash),
// or along a line through one of its edges with the creases meeting that line (a petal fold,
// inside and outside reverse folds) — the one whose pressed point's way the pointer is on.
// The result is a flat fold on chosen creases (flat_fold.h), previewed and committed as the
// marked-creases fold is.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "virtual_origami/core/flat_fold.h"
#include "virtual_origami/core/paper.h"
#include "virtual_origami/core/result.h"

namespace virtual_origami::core
{
/// The kind of a compound fold, as the user calls it.
enum class CompoundKind
{
  Squash,          // the creases at one vertex: a flap opened and pressed flat
  Petal,           // a layer lifted over a line, its sides folding in under it
  InsideReverse,   // a flap's tip turned in between its layers
  OutsideReverse,  // a flap's tip turned round outside its layers
  Reverse,         // a flap's tip turned back along a line, its layers apart
  Fold,            // another fold of the creases around the pressed face
};
const char* compoundKindName(CompoundKind kind);  // "squash fold", "petal fold", ...

/// One way the pressed flap can fold flat: the creases it changes (their new state: folded
/// flat or unfolded, the fold direction chosen on resolving) and where the pressed point lands.
struct CompoundOutcome
{
  std::vector<int> edges;    // the creases it changes
  std::vector<char> folded;  // per edge: folded flat after (1) or unfolded (0)
  Vec3 landing = Vec3::Zero();
  double disturbance = 0.0;       // how far the fold moves the paper: the vertices' distances summed
  std::vector<int> line_creases;  // the creases on the line, for a fold along one
  bool from_line = false;         // the creases meet a line through the pressed face's edge
  bool patch = false;             // ... within the pressed layer only (a petal fold)
};

/// The flat folds a drag from `press` on `face` can make, worked out at the press. Fails when
/// the paper does not lie flat (every crease at 0 or ±180°), the face is not one of its faces,
/// or a point or the side is not finite. The face that stays is the one farthest from the
/// pressed face on the sheet.
class CompoundFolds
{
public:
  /// `eye_side`: towards the eye. A squash or petal fold keeps the flap on the side it was
  /// pressed from (the eye's, or the far one for the bottom layer); a reverse fold turns the tip
  /// in between the layers.
  static Expected<CompoundFolds> at(const Paper& paper, int face, const Vec3& press,
                                    const Vec3& eye_side = Vec3::UnitZ());

  const std::vector<CompoundOutcome>& outcomes() const
  {
    return outcomes_;
  }
  int fixedFace() const
  {
    return fixed_face_;
  }

  /// The outcome the pointer drags: the one whose way (the pressed point's, from the press to
  /// its landing) passes nearest `pointer` — of ways passing alike (within 2 % of the paper's
  /// scale), the one landing nearest it, then the one moving the rest of the paper least — and
  /// how far along its way the pointer is (0 at the press, 1 at the landing). Outcomes `resolve`
  /// found no fold directions for are passed over.
  struct Choice
  {
    size_t outcome = 0;
    double fraction = 0.0;
    double miss = 0.0;  // how far the landing is from the pointer
  };
  std::optional<Choice> nearest(const Vec3& pointer) const;

  /// The flat fold of an outcome, its fold directions chosen (every vertex folds flat and the
  /// layers stack), and its kind. Fails when no choice of directions folds flat. Cached.
  struct Resolved
  {
    FlatFoldRequest request;
    CompoundKind kind = CompoundKind::Fold;
    /// For an inside reverse fold, the outside one along the same creases (the pressed point
    /// lands at the same place), when the layers let the tip wrap round them.
    std::optional<FlatFoldRequest> outside;
  };
  Expected<Resolved> resolve(size_t outcome);
  /// `nearest`, resolved: the nearest outcome that folds flat.
  std::optional<std::pair<Choice, Resolved>> nearestResolved(const Vec3& pointer);

private:
  Paper paper_;
  int face_ = -1, fixed_face_ = -1;
  Vec3 press_ = Vec3::Zero(), side_ = Vec3::UnitZ();
  std::vector<CompoundOutcome> outcomes_;
  std::vector<std::optional<Expected<Resolved>>> resolved_;
};

}  // namespace virtual_origami::core

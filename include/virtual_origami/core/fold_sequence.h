// Fold-sequence files: folding written down as steps (JSON), to author without the mouse.
//
//   {"title": "…", "size": 1.0, "solver": "newton",
//    "steps": [{"crease": {"start": [x, y], "end": [x, y]}, "note": "…"},
//              {"rotate": {"click": [x, y, z], "angle_deg": 20, "repeat": 6}},
//              {"squash": {}}, {"undo": {}}, {"redo": {}},
//              {"flat_fold": {"creases": [{"start": [x, y], "end": [x, y], "angle_deg": 180}, …],
//                             "fixed": [x, y]}}]}
//
// Points are in the `paper` frame, 2D or 3D; a crease may add "eye" and "snap"; a rotation
// may name "face" and "axis_edge" instead of clicking, and "repeat" turns the same face about
// the same axis again (one history step each), so a solver follows a large fold in stages.
// A flat fold (squash, petal, reverse fold: see flat_fold.h) names its creases and the face
// that stays by crease-pattern points; it is committed as the session's flat_fold operation
// (the paper_model's `flat_fold` service), so bags and replays carry it like any other.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "virtual_origami/core/flat_fold.h"
#include "virtual_origami/core/result.h"
#include "virtual_origami/core/session.h"

namespace virtual_origami::core
{
struct FoldStep
{
  Operation operation;  // a flat fold's request in operation.flat_fold
  /// A flat fold step: its request again (the same as operation.flat_fold), for callers that ask
  /// a step whether it is one.
  std::optional<FlatFoldRequest> flat_fold;
  int repeat = 1;
  std::string note;
};

struct FoldSequence
{
  std::string title;
  double size = 1.0;
  std::string solver = "newton";  // for folds that move faces not carried rigidly
  std::vector<FoldStep> steps;
};

/// Fails with a message naming the step and field at fault.
Expected<FoldSequence> parseFoldSequence(const std::string& text);

/// The state after every operation (front: the unfolded sheet; a repeated rotation gives one
/// state per turn), or the first step that failed. `solver` is the one the sequence names
/// (solvers/solver_factory.h makes it; null: refused, naming it).
Expected<std::vector<Paper>> foldSequence(const FoldSequence& sequence, Session& session,
                                          std::shared_ptr<ShapeSolver> solver);

}  // namespace virtual_origami::core

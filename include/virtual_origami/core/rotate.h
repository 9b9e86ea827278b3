// Turning a face about a crease (seed 000 §3.3.2–3.3.3), carrying its flap along.
#pragma once

#include <utility>
#include <vector>

#include "virtual_origami/core/assignment_fold.h"
#include "virtual_origami/core/paper.h"
#include "virtual_origami/core/result.h"
#include "virtual_origami/core/shape_solver.h"

namespace virtual_origami::core
{
struct RotateRequest
{
  int face = -1;       // -1: the face under `click`
  int axis_edge = -1;  // -1: the automatic axis of seed §3.3.2
  Vec3 click = Vec3::Zero();
  /// Radians by which the axis crease's fold angle changes; positive folds valley (FOLD).
  double angle = 0.0;
  /// Carry the flap: the layers stacked with the face on its side of the axis that the turn
  /// would otherwise pass through, by the recorded layer order (seed Fig. 15).
  bool carry_stack = true;
};

struct RotateResult
{
  int face = -1;
  int axis_edge = -1;
  std::vector<int> moved_faces;  // turned rigidly with the face (its flap, or the layers carried)
  bool used_solver = false;
  /// The last stage's report, with the iterations and seconds of every stage summed.
  SolveReport solve;
};

/// A crease driver that gives the rigid solver its start on a large model: the solver otherwise
/// starts from the face turned alone and the rest where it was, which on a big mechanism is far
/// from where it ends (a 40 × 40 Miura-ori's first 10° corner turn took Newton 174 iterations).
/// Each stage first drives the turned creases to their new angles with the face across the
/// axis and the held vertices anchored and every other crease free, through soft faces
/// (`face_stiffness`), then hands those positions (the turned faces as the turn places them) to
/// the solver, which closes the faces exactly. Only from `min_vertices` up: a small model's
/// solve is fast from any start.
struct TurnGuide
{
  CreaseDriver* driver = nullptr;
  size_t min_vertices = 1000;
  double face_stiffness = 100.0;
  /// The guide's balance (the driver's tolerance: no vertex would move more than this times the
  /// sheet's scale) and its step limit, in place of the driver's own for the call. The guide is a
  /// start for the solver, which closes the faces quadratically from there; near the flat sheet
  /// it crept to its balance (a 5,000-vertex Miura-ori's 2° turn: 479 steps, 35 s), so its steps
  /// are bounded, and a guide stopped short of balance (not diverged) is still the start. Ten
  /// steps: at 10,000 vertices a drag's later previews then take 0.7–0.8 s against 2–2.7 s at 20,
  /// the solver closing in 3–4 iterations; at 6 the solver needs up to 62 (docs/SOLVERS.md). The balance
  /// stays 1e-9: from a guide balanced to 1e-8 or 1e-6 (cheaper) the solver ends further along
  /// the near-flat sheet's soft modes, and a drag's last preview no longer lies within 1e-9 of
  /// the sheet of the turn committed at once (Session.ATurnCommittedAfterItsPreviews…: 1.06e-9).
  double tolerance = 1e-9;
  int max_iterations = 10;
};

/// A solved state of the same turn (`face` about `axis_edge` as rotate() resolves the request,
/// the same carry_stack and held vertices) at the request angle `angle`: a drag's last preview.
/// The solver's stages go on from it instead of from the model where it lies on the way (same
/// sign, nearer the turn than the model): a preview solves the mouse's last step, not the turn.
struct TurnStart
{
  const Paper* paper = nullptr;
  double angle = 0.0;
  int face = -1, axis_edge = -1;  // the turn it was made by
  /// Solved states of the same turn before `paper` (the drag's previews before it, oldest first,
  /// each with its request angle, nearer the model). The first stage starts where the parabola
  /// through `paper` and the two states before it (the model itself, at no turn, when only one
  /// is given) reaches the turn; with none, the guide gives the start.
  std::vector<std::pair<const Paper*, double>> before;
};

/// Turns the face about its axis. When the creases collinear with the axis cut the sheet in
/// two, the face's whole side (every layer connected to it there) turns rigidly, which is
/// exact; with `carry_stack`, so do the layers stacked on that side in the turn's way, each
/// with its own connected part. Otherwise the face turns alone (with the layers in its way)
/// and `solver` moves the rest of the model, every layer (with the turned faces and the
/// face across the axis held, and `held` vertices); without a solver that fails. The solver
/// follows a large turn in stages of at most 10° (smaller where a crease swings fast), each
/// started from the last, so one call ends on the branch the same turn in small calls does;
/// each stage has the solver's own limits (a time budget counts per stage). The layer
/// order (face_orders) follows: faces folded flat onto others lie on the side they came
/// from, and entries of faces no longer stacked are dropped. On failure `paper` is untouched.
/// `looser_tolerance` > 0 (a drag's preview): the solver's stages converge at that strain where
/// it is looser than the solver's own (ShapeSolver::solveLoosely).
Expected<RotateResult> rotate(Paper& paper, const RotateRequest& request, ShapeSolver* solver = nullptr,
                              const std::vector<int>& held = {}, const TurnGuide& guide = {},
                              const TurnStart& start = {}, double looser_tolerance = 0.0);

/// The faces rotate() turns with `face` about `axis_edge` by the request angle `angle` (its sign
/// decides which layers a turn carries): its side with the layers carried where the axis parts it
/// from the rest, else the face with the layers in its way.
std::vector<int> turnedFaces(const Paper& paper, int face, int axis_edge, double angle, bool carry_stack = true);

/// The faces that turn rigidly with `face` about `axis_edge`, or empty when the axis does
/// not separate them from the rest.
std::vector<int> flapOf(const Paper& paper, int face, int axis_edge);

}  // namespace virtual_origami::core

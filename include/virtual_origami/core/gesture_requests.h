// What a gesture asks of paper_model, as plain values: the interaction node sends each as the
// service call of the same name, a test records them. The reply says whether the paper took it.
#pragma once

#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <variant>

#include "virtual_origami/core/flat_fold.h"
#include "virtual_origami/core/paper.h"

namespace virtual_origami::core
{
/// `crease`: the line exactly as drawn (snapped by the gesture already); through the layers the
/// eye sees under it when the eye is known.
struct CreaseCall
{
  Vec3 start = Vec3::Zero(), end = Vec3::Zero();
  std::optional<Vec3> eye;
};

/// `rotate`: a preview while dragging, one commit on release.
struct RotateCall
{
  int face = -1;
  int axis_edge = -1;
  Vec3 click = Vec3::Zero();
  double angle = 0.0;
  bool commit = false;
  bool picked_layers_only = false;
};

/// `flat_fold`: a frame of the animated fold on the marked creases; the last one commits.
struct FlatFoldCall
{
  FlatFoldRequest fold;
  double fraction = 1.0;
  bool commit = false;
};

/// `drag_vertex`: a preview while dragging, one commit on release.
struct DragVertexCall
{
  int vertex = -1;
  Vec3 position = Vec3::Zero();
  bool commit = false;
};

/// `fold_by_assignment`: the slider's previews and commit, and the menu's fractions.
struct FoldByAssignmentCall
{
  double fraction = 0.0;
  bool preview = false;
  bool keep = false;  // commit a state the service would refuse (strained, crossing), its figures said
};

/// The services without parameters.
enum class PaperCommand
{
  Squash,
  Undo,
  Redo,
  Reset,
  KeepBend,  // the bent sheet the curved model shows becomes the paper's state (kept_bend.h)
};
struct CommandCall
{
  PaperCommand command = PaperCommand::Undo;
};

/// `pin`: pins a vertex, or releases its pin.
struct PinCall
{
  int vertex = -1;
  bool release = false;
};

using PaperRequest =
    std::variant<CreaseCall, RotateCall, FlatFoldCall, DragVertexCall, FoldByAssignmentCall, CommandCall, PinCall>;

struct PaperReply
{
  /// False when paper_model did not answer; `message` then says so.
  bool answered = true;
  bool success = false;
  std::string message;
  uint64_t revision = 0;  // the paper's revision after a committed change
  /// drag_vertex: the rigid faces cannot follow, but bent paper reaches the target and a curved
  /// model is there to bend it.
  bool curved_reaches = false;
  /// fold_by_assignment: the driven creases' RMS distance (rad) from where the fraction asked
  /// them, as answered (a slider preview that fell behind its handle; NaN when not given).
  double angle_error = std::numeric_limits<double>::quiet_NaN();
};

}  // namespace virtual_origami::core

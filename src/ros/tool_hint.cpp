#include "virtual_origami/ros/tool_hint.h"

namespace virtual_origami
{
namespace
{
std::string creases(size_t n)
{
  return std::to_string(n) + (n == 1 ? " crease" : " creases");
}

std::string whatAClickDoes(core::GestureMode mode, const core::GestureStatus& status)
{
  switch (mode)
  {
    case core::GestureMode::Crease:
      return "Crease mode: drag a line across the paper to crease it.";
    case core::GestureMode::Rotate:
      return "Rotate mode: drag a face to turn it about its crease; click a crease to make it the axis.";
    case core::GestureMode::Drag:
      return "Drag mode: drag a vertex to move it.";
    case core::GestureMode::Fold:
      if (status.marked_edges.empty())
        return "Fold mode: click a crease to mark it valley (again: mountain, again: unmarked).";
      if (status.picked_face < 0)
        return "Fold mode: " + creases(status.marked_edges.size()) +
               " marked; click a crease to change its mark, or the face that stays.";
      return "Fold mode: " + creases(status.marked_edges.size()) +
             " marked, a face stays: Enter or a double click folds.";
  }
  return "";
}
}  // namespace

std::string toolHint(core::GestureMode mode, const core::GestureStatus& status)
{
  if (status.dragging)
    return "Release to finish the drag; Esc cancels it.";
  std::string hint = whatAClickDoes(mode, status);
  if (status.layers > 1)
    hint += " Layer " + std::to_string(status.picked_layer) + " of " + std::to_string(status.layers) +
            " under the pick: the wheel or Tab for the next one down.";
  return hint + " Keys: 1 crease, 2 rotate, 3 fold, 4 drag, Ctrl+Z undo, Ctrl+Y redo.";
}

}  // namespace virtual_origami

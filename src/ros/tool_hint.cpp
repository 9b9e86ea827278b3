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
      return "Crease mode: drag a line across the paper.";
    case core::GestureMode::Rotate:
      return "Rotate mode: drag a face to turn it; click a crease for the axis.";
    case core::GestureMode::Drag:
      return "Drag mode: drag a vertex.";
    case core::GestureMode::Flap:
      return "Flap mode: drag a flap where it should lie; it folds flat on release.";
    case core::GestureMode::Fold:
      if (status.marked_edges.empty())
        return "Fold mode: click a crease to mark it valley, again mountain, again none.";
      if (status.picked_face < 0)
        return "Fold mode: " + creases(status.marked_edges.size()) + " marked; click the face that stays.";
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
  const std::string hint = whatAClickDoes(mode, status);
  // One line in rviz's status bar: the layers under the pick, else the keys.
  if (status.layers > 1)
    return hint + " Layer " + std::to_string(status.picked_layer) + " of " + std::to_string(status.layers) +
           ": the wheel or Tab for the next down, the other way or Shift+Tab up.";
  return hint + " Keys: 1-5 mode, Ctrl+Z undo, Ctrl+Y redo.";
}

}  // namespace virtual_origami

#include "virtual_origami/ros/tool_keys.h"

#include <algorithm>
#include <cctype>

#include <virtual_origami/ToolEvent.h>

namespace virtual_origami
{
ToolAction toolKeyAction(const std::string& key, uint8_t modifiers)
{
  std::string k = key;
  std::transform(k.begin(), k.end(), k.begin(), [](unsigned char c) { return std::tolower(c); });
  const bool shift = modifiers & ToolEvent::SHIFT, control = modifiers & ToolEvent::CONTROL,
             alt = modifiers & ToolEvent::ALT;
  if (alt)
    return ToolAction::None;
  if (control)
  {
    if (k == "z")
      return shift ? ToolAction::Redo : ToolAction::Undo;
    if (k == "y")
      return ToolAction::Redo;
    return ToolAction::None;
  }
  // Qt names Shift+Tab "Backtab"; a Tab with Shift held is the same key.
  if (k == "backtab" || (k == "tab" && shift))
    return ToolAction::PreviousLayer;
  if (k == "tab")
    return ToolAction::NextLayer;
  if (k == "return" || k == "enter")
    return ToolAction::FoldMarks;
  if (k == "esc" || k == "escape")
    return ToolAction::Cancel;
  if (shift)
    return ToolAction::None;
  if (k == "1")
    return ToolAction::CreaseMode;
  if (k == "2")
    return ToolAction::RotateMode;
  if (k == "3")
    return ToolAction::FoldMode;
  if (k == "4")
    return ToolAction::DragMode;
  if (k == "5")
    return ToolAction::FlapMode;
  return ToolAction::None;
}

bool repeats(ToolAction action)
{
  return action == ToolAction::NextLayer || action == ToolAction::PreviousLayer;
}

}  // namespace virtual_origami

// The Fold tool's keys (docs/INTERACTION.md, "The Fold tool"): a key as Qt names it, with the
// modifiers held, to what it does in the gestures. Pure; the interaction node carries it out.
#pragma once

#include <cstdint>
#include <string>

namespace virtual_origami
{
enum class ToolAction
{
  None,
  NextLayer,      // Tab: the next layer down under the pointer (as the wheel turned away)
  PreviousLayer,  // Shift+Tab: the next layer up (as the wheel turned towards the user)
  FoldMarks,      // Enter: fold flat on the marked creases (as a double click)
  Cancel,         // Esc: let go of the drag, nothing committed
  Undo,           // Ctrl+Z
  Redo,           // Ctrl+Y, Ctrl+Shift+Z
  CreaseMode,     // 1
  RotateMode,     // 2
  FoldMode,       // 3
  DragMode,       // 4
  FlapMode,       // 5
};

/// `key` as Qt's QKeySequence names it ("Tab", "Return", "Z", "1"); `modifiers` as ToolEvent's
/// SHIFT | CONTROL | ALT. Keys with Alt, and unknown keys, do nothing.
ToolAction toolKeyAction(const std::string& key, uint8_t modifiers);

/// Whether a held key repeats its action: only walking the layers (either way) does; a held Enter or Ctrl+Z
/// must not fold or undo again and again.
bool repeats(ToolAction action);

}  // namespace virtual_origami

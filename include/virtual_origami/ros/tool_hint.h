// The Fold tool's status line: what a click on the paper does in the current mode, the layers
// under the pick, and the keys (InteractionStatus.hint; docs/INTERACTION.md, "The Fold tool").
#pragma once

#include <string>

#include "virtual_origami/core/gesture_model.h"

namespace virtual_origami
{
std::string toolHint(core::GestureMode mode, const core::GestureStatus& status);

}  // namespace virtual_origami

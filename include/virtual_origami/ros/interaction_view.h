// The view the mouse works in, as the interaction node names it: core/view_camera.h.
#pragma once

#include "virtual_origami/core/view_camera.h"

namespace virtual_origami
{
using core::alongSightOnto;
using core::turnedView;
using core::ViewCamera;
}  // namespace virtual_origami

// Replacing a file so that readers and crashes never see half of it: written beside the target
// under a new name (created exclusively, never through a link), synced, then renamed over it.
#pragma once

#include <string>

#include "virtual_origami/core/result.h"

namespace virtual_origami::core
{
/// Writes `text` as the file `name` of the open folder `folder` (a descriptor), keeping the
/// permissions of a file it replaces. Refuses, changing nothing, a target that is a symbolic
/// link, not a regular file, or read-only (no write permission, also when running as root).
/// Messages name the file as `shown`.
Status writeFileAt(int folder, const std::string& name, const std::string& text, const std::string& shown);

}  // namespace virtual_origami::core

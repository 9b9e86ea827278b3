// Replaying a recording into a running paper_model, as a moving folding diagram.
#pragma once

#include <string>

#include "virtual_origami/core/data_folder.h"
#include "virtual_origami/core/result.h"
#include "virtual_origami/ros/operation_client.h"
#include "virtual_origami/ros/recording.h"

namespace virtual_origami
{
struct ReplayOptions
{
  /// 1: as recorded; 2: twice as fast; 0: no pauses and no animation (as fast as it goes).
  double speed = 1.0;
  int animation_steps = 15;  // previews shown while a rotation turns or a fold by assignment folds
  /// paper_model's data folder: the first state is handed to its `load` there, by a relative name.
  std::string data_dir = core::defaultDataFolder();
};

/// Starts the model where the recording started (its first state, else a reset sheet) and
/// applies every recorded operation again; the result is the recorded final state.
core::Status replay(const Recording& recording, OperationClient& client, const ReplayOptions& options);

}  // namespace virtual_origami

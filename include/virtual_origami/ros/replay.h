// Replaying a recording into a running paper_model, as a moving folding diagram.
#pragma once

#include <cstddef>
#include <functional>
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
  /// The longest pause between two operations, in recorded seconds: two operations stamped
  /// 1e9 s apart replayed for 31 years (found by the round-3 probe).
  double max_gap = 5.0;
  /// Called after each operation applied: how many of how many.
  std::function<void(size_t done, size_t total)> progress;
};

/// Why the recording cannot be replayed, found before anything is applied: an operation of an
/// unknown type, or stamps that are not numbers. Empty when it can.
core::Status checkReplayable(const Recording& recording);

/// Starts the model where the recording started (its first state, else a reset sheet) and
/// applies every recorded operation again; the result is the recorded final state. A recording
/// checkReplayable refuses changes nothing; an operation refused on the way rolls the model back
/// to the paper it had before the replay (saved first, loaded back), and the answer says so.
core::Status replay(const Recording& recording, OperationClient& client, const ReplayOptions& options);

}  // namespace virtual_origami

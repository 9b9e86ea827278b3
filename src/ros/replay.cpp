#include "virtual_origami/ros/replay.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <set>
#include <string>

#include <ros/ros.h>

#include "virtual_origami/core/fold_fraction.h"
#include "virtual_origami/core/fold_io.h"
#include "virtual_origami/core/session.h"
#include "virtual_origami/ros/conversions.h"

namespace virtual_origami
{
namespace
{
core::Status startWhereTheRecordingStarted(const Recording& recording, OperationClient& client,
                                           const ReplayOptions& options)
{
  if (!recording.initial_state)
  {
    Operation reset;
    reset.type = "reset";
    return client.apply(reset);
  }
  const core::Expected<core::Paper> paper = fromMessage(*recording.initial_state);
  if (!paper)
    return core::failure("the recording's first state is broken: " + paper.message());
  const std::string name = "replay_start_" + std::to_string(::getpid()) + ".fold";
  const std::string path = options.data_dir + "/" + name;
  // Through the folder's descriptor, as paper_model reads it.
  const core::Expected<core::DataFolder> folder = core::DataFolder::open(options.data_dir);
  const core::Status written =
      folder ? folder->writeFile(name, core::formatFold(*paper, "replay start")) : core::failure(folder.message());
  if (!written)
    return written;
  const core::Status loaded = client.load(name);
  std::remove(path.c_str());
  return loaded;
}

/// A load of the paper the model has already is refused (a revision that changes nothing);
/// for a replay that is where it should be.
core::Status alreadyThere(const core::Status& loaded)
{
  if (!loaded && loaded.message().find(core::kNothingLoaded) != std::string::npos)
    return core::success();
  return loaded;
}

/// How far the paper was folded by assignment just before `op`, from the recorded state it
/// started from; none when the recording lacks that state.
std::optional<double> foldedBefore(const Recording& recording, const Operation& op)
{
  for (const PaperState& state : recording.states)
    if (state.revision + 1 == op.revision)
    {
      const core::Expected<core::Paper> paper = fromMessage(state);
      if (paper)
        return core::foldFraction(*paper);
    }
  return std::nullopt;
}
}  // namespace

core::Status checkReplayable(const Recording& recording)
{
  static const std::set<std::string> known{ "crease",    "rotate",     "squash", "undo", "redo",
                                            "reset",     "pin",        "pull",   "load", "fold_by_assignment",
                                            "flat_fold", "drag_vertex", "keep_bend" };
  for (size_t i = 0; i < recording.operations.size(); ++i)
  {
    const Operation& op = recording.operations[i];
    if (!known.count(op.type))
      return core::failure("operation " + std::to_string(i + 1) + " is of an unknown type \"" + op.type +
                           "\": nothing was replayed");
  }
  return core::success();
}

core::Status replay(const Recording& recording, OperationClient& client, const ReplayOptions& options)
{
  const core::Status replayable = checkReplayable(recording);
  if (!replayable)
    return replayable;
  // The paper as it is, to roll back to if an operation is refused on the way.
  const std::string before = "replay_before_" + std::to_string(::getpid()) + ".fold";
  const core::Status kept = client.save(before);
  if (!kept)
    return core::failure("cannot keep the paper to roll back to, so nothing was replayed: " + kept.message());
  const auto rollBack = [&](const std::string& why) {
    const core::Status restored = alreadyThere(client.load(before));
    std::remove((options.data_dir + "/" + before).c_str());
    return core::failure(why + (restored ? "; the paper is as it was before the replay" :
                                           "; it could not be rolled back: " + restored.message()));
  };
  const core::Status started = alreadyThere(startWhereTheRecordingStarted(recording, client, options));
  if (!started)
    return rollBack("the recording's first state: " + started.message());
  const bool animate = options.speed > 0;
  const double max_gap = std::max(0.0, options.max_gap);
  for (size_t i = 0; i < recording.operations.size(); ++i)
  {
    if (!ros::ok())
      return rollBack("stopped after " + std::to_string(i) + " of " + std::to_string(recording.operations.size()) +
                      " operations");
    const Operation& op = recording.operations[i];
    double gap = 0.0;  // seconds between this operation and the one before, as recorded, capped
    if (i > 0)
    {
      gap = (op.header.stamp - recording.operations[i - 1].header.stamp).toSec();
      gap = std::isfinite(gap) ? std::clamp(gap, 0.0, max_gap) : 0.0;
    }
    const double turn_time = animate ? std::min(1.0, std::max(0.3, gap)) / options.speed : 0.0;
    if (animate)
      ros::WallDuration(std::max(0.0, gap / options.speed - turn_time)).sleep();
    const std::optional<double> folded_from =
        animate && op.type == "fold_by_assignment" ? foldedBefore(recording, op) : std::nullopt;
    const core::Status applied = client.apply(op, animate ? options.animation_steps : 0, turn_time, folded_from);
    if (!applied)
      return rollBack("operation " + std::to_string(i + 1) + " of " + std::to_string(recording.operations.size()) +
                      " (" + op.type + "): " + applied.message());
    if (options.progress)
      options.progress(i + 1, recording.operations.size());
  }
  std::remove((options.data_dir + "/" + before).c_str());
  return core::success();
}

}  // namespace virtual_origami

#include "virtual_origami/ros/replay.h"

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <optional>

#include <ros/ros.h>

#include "virtual_origami/core/fold_fraction.h"
#include "virtual_origami/core/fold_io.h"
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
  const core::Status written = core::writeTextFile(path, core::formatFold(*paper, "replay start"));
  if (!written)
    return written;
  const core::Status loaded = client.load(name);
  std::remove(path.c_str());
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

core::Status replay(const Recording& recording, OperationClient& client, const ReplayOptions& options)
{
  const core::Status started = startWhereTheRecordingStarted(recording, client, options);
  if (!started)
    return started;
  const bool animate = options.speed > 0;
  for (size_t i = 0; i < recording.operations.size() && ros::ok(); ++i)
  {
    const Operation& op = recording.operations[i];
    double gap = 0.0;  // seconds between this operation and the one before, as recorded
    if (i > 0)
      gap = std::max(0.0, (op.header.stamp - recording.operations[i - 1].header.stamp).toSec());
    const double turn_time = animate ? std::min(1.0, std::max(0.3, gap)) / options.speed : 0.0;
    if (animate)
      ros::WallDuration(std::max(0.0, gap / options.speed - turn_time)).sleep();
    const std::optional<double> folded_from =
        animate && op.type == "fold_by_assignment" ? foldedBefore(recording, op) : std::nullopt;
    const core::Status applied = client.apply(op, animate ? options.animation_steps : 0, turn_time, folded_from);
    if (!applied)
      return core::failure("operation " + std::to_string(i + 1) + " (" + op.type + "): " + applied.message());
  }
  return core::success();
}

}  // namespace virtual_origami

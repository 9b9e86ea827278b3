// Applies recorded operations (virtual_origami/Operation) through a paper_model's services.
#pragma once

#include <optional>
#include <string>

#include <ros/node_handle.h>
#include <virtual_origami/Operation.h>

#include "virtual_origami/core/result.h"

namespace virtual_origami
{
class OperationClient
{
public:
  /// `ns`: the namespace of the paper_model's services, e.g. "/origami".
  explicit OperationClient(const std::string& ns);
  /// Waits until the services are offered; false after `seconds`.
  bool waitForServices(double seconds);
  /// Calls the service the operation came from with its parameters. A rotation is shown
  /// turning first through `animation_steps` previews spread over `animation_seconds`; so is a
  /// fold by assignment, from `folded_from` (how far the paper was folded before it) when known.
  core::Status apply(const Operation& operation, int animation_steps = 0, double animation_seconds = 0.0,
                     std::optional<double> folded_from = std::nullopt);
  /// Loads a paper (as a FOLD file) so that a replay starts where the recording started.
  core::Status load(const std::string& path);
  /// Saves the paper as it is (a replay keeps it to roll back to).
  core::Status save(const std::string& path);

private:
  ros::NodeHandle nh_;
};

}  // namespace virtual_origami

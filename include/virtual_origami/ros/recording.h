// Recordings of folding: the `operations` and `state` topics in a rosbag.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <virtual_origami/Operation.h>
#include <virtual_origami/PaperState.h>

#include "virtual_origami/core/result.h"

namespace virtual_origami
{
struct Recording
{
  std::vector<Operation> operations;
  std::vector<PaperState> states;
  /// The state the first operation started from, when the bag holds it.
  std::optional<PaperState> initial_state;
};

/// Reads every message on a topic ending in `/operations` or `/state`. A missing, corrupt or
/// unindexed bag is an error with a message (`rosbag reindex` mends the last).
core::Expected<Recording> readRecording(const std::string& path);

/// Appends messages to a bag so that each one is on disk as soon as it is written: the bag
/// is closed after every message, so a crash or kill -9 loses nothing already recorded.
class DurableBagWriter
{
public:
  explicit DurableBagWriter(std::string path) : path_(std::move(path)) {}
  core::Status write(const std::string& topic, const Operation& operation);
  core::Status write(const std::string& topic, const PaperState& state);
  const std::string& path() const { return path_; }

private:
  template <class Message>
  core::Status append(const std::string& topic, const Message& message);
  std::string path_;
  bool started_ = false;
};

}  // namespace virtual_origami

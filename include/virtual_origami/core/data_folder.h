// The folder where a node reads and writes the user's files (models, bags, journals). Any ROS
// client can call load and save, and ROS 1 has no authentication: paths are confined here so that
// a client cannot read or overwrite the node user's other files.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "virtual_origami/core/result.h"

namespace virtual_origami::core
{
/// `$ROS_HOME/virtual_origami`, or `~/.ros/virtual_origami` without ROS_HOME.
std::string defaultDataFolder();

class DataFolder
{
public:
  /// Creates `root` if need be. `extra` are further folders the launch allows on purpose.
  static Expected<DataFolder> open(const std::string& root, const std::vector<std::string>& extra = {});

  /// The file `path` names: a relative path resolves in the data folder. Refused: an empty path,
  /// `..`, and anything that is not inside the data folder or an extra folder once symlinks are
  /// followed. The answer is the path with every symlink resolved.
  Expected<std::string> resolve(const std::string& path) const;

  const std::string& root() const
  {
    return root_string_;
  }

private:
  std::filesystem::path root_;
  std::string root_string_;
  std::vector<std::filesystem::path> allowed_;  // root_ first, all canonical
};

}  // namespace virtual_origami::core

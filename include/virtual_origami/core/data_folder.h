// The folder where a node reads and writes the user's files (models, bags, journals). Any ROS
// client can call load and save, and ROS 1 has no authentication: paths are confined here so that
// a client cannot read or overwrite the node user's other files.
#pragma once

#include <cstddef>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "virtual_origami/core/result.h"

namespace virtual_origami::core
{
/// `$ROS_HOME/virtual_origami`, or `~/.ros/virtual_origami` without ROS_HOME.
std::string defaultDataFolder();

/// Refuses a path with a control character: a NUL ends the name every system call sees, so
/// "j.jsonl\0.fold" passes a check of the whole string as a .fold and writes j.jsonl.
Status checkPathCharacters(const std::string& path);

/// The largest file readFile reads unless told otherwise (both readers refuse beyond it too).
constexpr size_t kMaxReadBytes = size_t{ 64 } << 20;

class DataFolder
{
public:
  /// Creates `root` if need be and opens it (and each of `extra`, further folders the launch
  /// allows on purpose) once: files are reached from these descriptors, never by a whole path.
  static Expected<DataFolder> open(const std::string& root, const std::vector<std::string>& extra = {});

  /// The file `path` names: a relative path resolves in the data folder. Refused: an empty path,
  /// a control character, `..`, and anything that is not inside the data folder or an extra
  /// folder once symlinks are followed. The answer is the path with every symlink resolved. A
  /// check of a name the launch gives (the journal's); clients' files go through readFile and
  /// writeFile, which cannot be led outside by a swap between check and use.
  Expected<std::string> resolve(const std::string& path) const;

  /// The contents of the regular file `path` names. The path is walked one component at a time
  /// from the folder's descriptor (openat, O_NOFOLLOW): a symlink on the way is followed only
  /// while it stays inside an allowed folder, so a link swapped in meanwhile is refused, never
  /// followed out. Opened without blocking and refused unless a regular file (a FIFO, socket,
  /// device or folder), larger than `max_bytes`, or protected.
  Expected<std::string> readFile(const std::string& path, size_t max_bytes = kMaxReadBytes) const;
  /// Writes `text` to `path` atomically: a new temporary file in the target's folder (created
  /// exclusively, through that folder's descriptor), synced, then renamed over it (renameat),
  /// keeping its permissions. Refuses, changing nothing, a path walked as readFile's that ends
  /// in a symlink, a target that is not a regular file or is read-only, and a protected file.
  Status writeFile(const std::string& path, const std::string& text) const;

  /// Never a target of readFile or writeFile: `path` (resolved like resolve) and every name
  /// beside it that starts with its name (the journal's temporary and kept-aside copies).
  Status protect(const std::string& path);

  const std::string& root() const
  {
    return root_string_;
  }

  class Descriptor;
  /// Where a walk ends: the folder holding the file, opened, and the file's name in it.
  struct Place
  {
    std::shared_ptr<const Descriptor> folder;
    std::string name;
  };

private:
  struct Allowed
  {
    std::filesystem::path canonical, given;  // the folder's real path, and the one the launch named
    std::shared_ptr<const Descriptor> descriptor;
  };
  struct Protected
  {
    unsigned long device = 0, inode = 0;  // the folder holding it
    std::string name;
  };

  /// Walks `path` as readFile and writeFile do; `follow_last`: the last component may be a
  /// symlink (followed, confined, for a read).
  Expected<Place> locate(const std::string& path, bool follow_last) const;
  Status checkNotProtected(const Place& place, const std::string& path) const;

  std::filesystem::path root_;
  std::string root_string_;
  std::vector<Allowed> allowed_;  // root_ first
  std::vector<Protected> protected_;
};

}  // namespace virtual_origami::core

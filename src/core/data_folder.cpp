#include "virtual_origami/core/data_folder.h"

#include <cstdlib>
#include <system_error>

namespace virtual_origami::core
{
namespace fs = std::filesystem;

namespace
{
bool inside(const fs::path& path, const fs::path& folder)
{
  auto p = path.begin();
  for (auto f = folder.begin(); f != folder.end(); ++f, ++p)
    if (p == path.end() || *p != *f)
      return false;
  return true;
}

Expected<fs::path> canonicalFolder(const std::string& name, bool create)
{
  if (name.empty())
    return Expected<fs::path>::failure("a data folder needs a name");
  std::error_code error;
  if (create)
    fs::create_directories(name, error);
  const fs::path canonical = fs::canonical(name, error);
  if (error || !fs::is_directory(canonical))
    return Expected<fs::path>::failure("the data folder " + name + " is not a folder that can be used" +
                                       (error ? ": " + error.message() : ""));
  return canonical;
}
}  // namespace

std::string defaultDataFolder()
{
  const char* ros_home = std::getenv("ROS_HOME");
  const char* home = std::getenv("HOME");
  const std::string base = ros_home && *ros_home ? ros_home : std::string(home && *home ? home : "/tmp") + "/.ros";
  return base + "/virtual_origami";
}

Expected<DataFolder> DataFolder::open(const std::string& root, const std::vector<std::string>& extra)
{
  DataFolder folder;
  const Expected<fs::path> canonical = canonicalFolder(root, true);
  if (!canonical)
    return Expected<DataFolder>::failure(canonical.message());
  folder.root_ = *canonical;
  folder.root_string_ = canonical->string();
  folder.allowed_.push_back(*canonical);
  for (const std::string& name : extra)
  {
    const Expected<fs::path> allowed = canonicalFolder(name, false);
    if (!allowed)
      return Expected<DataFolder>::failure(allowed.message());
    folder.allowed_.push_back(*allowed);
  }
  return folder;
}

Expected<std::string> DataFolder::resolve(const std::string& path) const
{
  if (path.empty())
    return Expected<std::string>::failure("no file named (an empty path)");
  const fs::path given(path);
  for (const fs::path& part : given)
    if (part == "..")
      return Expected<std::string>::failure(
          "\"" + path + "\" climbs out with \"..\": name a file inside the data folder " + root_string_);
  const fs::path absolute = given.is_absolute() ? given : root_ / given;
  // Follows every symlink that exists, the file's own included: a link planted inside the
  // folder that points out of it is refused like the path it points to.
  std::error_code error;
  const fs::path real = fs::weakly_canonical(absolute, error);
  if (error)
    return Expected<std::string>::failure("cannot resolve \"" + path + "\": " + error.message());
  // What weakly_canonical leaves unresolved does not exist, unless it is a dangling symlink,
  // through which a write would create a file wherever the link points.
  fs::path prefix;
  for (const fs::path& part : real)
  {
    prefix /= part;
    if (fs::is_symlink(fs::symlink_status(prefix, error)))
      return Expected<std::string>::failure("\"" + path + "\" is a symlink to a file that does not exist");
  }
  for (const fs::path& folder : allowed_)
    if (inside(real, folder))
      return real.string();
  return Expected<std::string>::failure("\"" + path + "\" is outside the data folder " + root_string_ +
                                        " (parameter data_dir; a launch may allow more folders with allowed_dirs)");
}

}  // namespace virtual_origami::core

#include "virtual_origami/core/data_folder.h"

#include "virtual_origami/core/atomic_write.h"

#include <fcntl.h>
#include <limits.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <deque>
#include <iterator>
#include <sstream>
#include <system_error>

namespace virtual_origami::core
{
namespace fs = std::filesystem;

/// An open file or folder, closed when the last owner lets go.
class DataFolder::Descriptor
{
public:
  explicit Descriptor(int fd) : fd_(fd)
  {}
  Descriptor(const Descriptor&) = delete;
  Descriptor& operator=(const Descriptor&) = delete;
  ~Descriptor()
  {
    if (fd_ >= 0)
      ::close(fd_);
  }
  int get() const
  {
    return fd_;
  }

private:
  int fd_ = -1;
};

namespace
{
using Descriptor = DataFolder::Descriptor;
using Shared = std::shared_ptr<const Descriptor>;

/// Symlinks followed in one walk at most (the kernel's own limit).
constexpr int kMaxLinks = 40;

std::string errnoText(int error = errno)
{
  return std::strerror(error);
}

bool inside(const fs::path& path, const fs::path& folder)
{
  auto p = path.begin();
  for (auto f = folder.begin(); f != folder.end(); ++f, ++p)
    if (p == path.end() || *p != *f)
      return false;
  return true;
}

/// The components of `path` after the first `skip`, in order.
std::deque<std::string> componentsAfter(const fs::path& path, size_t skip)
{
  std::deque<std::string> parts;
  size_t i = 0;
  for (const fs::path& part : path)
    if (i++ >= skip)
      parts.push_back(part.string());
  return parts;
}

size_t componentCount(const fs::path& path)
{
  return static_cast<size_t>(std::distance(path.begin(), path.end()));
}

Expected<fs::path> canonicalFolder(const std::string& name, bool create)
{
  if (name.empty())
    return Expected<fs::path>::failure("a data folder needs a name");
  const Status characters = checkPathCharacters(name);
  if (!characters)
    return Expected<fs::path>::failure(characters.message());
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

Status checkPathCharacters(const std::string& path)
{
  for (size_t i = 0; i < path.size(); ++i)
  {
    const unsigned char c = static_cast<unsigned char>(path[i]);
    if (c < 0x20 || c == 0x7f)
      return failure("the path has a control character (byte " + std::to_string(static_cast<int>(c)) + " at position " +
                     std::to_string(i) + "); name a file without one");
  }
  return success();
}

Expected<DataFolder> DataFolder::open(const std::string& root, const std::vector<std::string>& extra)
{
  DataFolder folder;
  std::vector<std::string> names{ root };
  names.insert(names.end(), extra.begin(), extra.end());
  for (size_t i = 0; i < names.size(); ++i)
  {
    const Expected<fs::path> canonical = canonicalFolder(names[i], i == 0);
    if (!canonical)
      return Expected<DataFolder>::failure(canonical.message());
    const int fd = ::open(canonical->c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (fd < 0)
      return Expected<DataFolder>::failure("cannot open the folder " + canonical->string() + ": " + errnoText());
    std::error_code error;
    const fs::path given = fs::absolute(names[i], error).lexically_normal();
    Allowed allowed{ *canonical, error ? *canonical : given, std::make_shared<const Descriptor>(fd) };
    if (!allowed.given.has_filename())  // "folder/" normalises to a trailing empty component
      allowed.given = allowed.given.parent_path();
    folder.allowed_.push_back(std::move(allowed));
  }
  folder.root_ = folder.allowed_.front().canonical;
  folder.root_string_ = folder.root_.string();
  return folder;
}

Expected<std::string> DataFolder::resolve(const std::string& path) const
{
  if (path.empty())
    return Expected<std::string>::failure("no file named (an empty path)");
  const Status characters = checkPathCharacters(path);
  if (!characters)
    return Expected<std::string>::failure(characters.message());
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
  for (const Allowed& folder : allowed_)
    if (inside(real, folder.canonical))
      return real.string();
  return Expected<std::string>::failure("\"" + path + "\" is outside the data folder " + root_string_ +
                                        " (parameter data_dir; a launch may allow more folders with allowed_dirs)");
}

Expected<DataFolder::Place> DataFolder::locate(const std::string& path, bool follow_last) const
{
  using Answer = Expected<Place>;
  if (path.empty())
    return Answer::failure("no file named (an empty path)");
  const Status characters = checkPathCharacters(path);
  if (!characters)
    return Answer::failure(characters.message());
  const fs::path given(path);
  for (const fs::path& part : given)
    if (part == "..")
      return Answer::failure("\"" + path + "\" climbs out with \"..\": name a file inside the data folder " +
                             root_string_);
  const std::string outside = "\"" + path + "\" is outside the data folder " + root_string_ +
                              " (parameter data_dir; a launch may allow more folders with allowed_dirs)";
  // An absolute path (or link target) starts from the allowed folder it names, by either name.
  const auto start = [&](const fs::path& absolute, std::vector<Shared>& stack, std::deque<std::string>& rest) {
    const fs::path normal = absolute.lexically_normal();
    for (const Allowed& folder : allowed_)
      for (const fs::path* name : { &folder.canonical, &folder.given })
        if (inside(normal, *name))
        {
          std::deque<std::string> after = componentsAfter(normal, componentCount(*name));
          rest.insert(rest.begin(), after.begin(), after.end());
          stack.assign(1, folder.descriptor);
          return true;
        }
    return false;
  };

  std::vector<Shared> stack{ allowed_.front().descriptor };  // the folders walked through, held open
  std::deque<std::string> rest;
  if (given.is_absolute())
  {
    if (!start(given, stack, rest))
      return Answer::failure(outside);
  }
  else
    rest = componentsAfter(given, 0);
  int links = 0;
  while (true)
  {
    while (!rest.empty() && (rest.front().empty() || rest.front() == "."))
      rest.pop_front();
    if (rest.empty())
      return Answer::failure("\"" + path + "\" names a folder, not a file");
    const std::string part = rest.front();
    rest.pop_front();
    if (part == "..")  // only from a link's target: allowed while it stays inside
    {
      if (stack.size() == 1)
        return Answer::failure(outside + ": a symlink on the way leads out of it");
      stack.pop_back();
      continue;
    }
    const bool last = rest.empty();
    const int folder = stack.back()->get();
    // The link is read in the folder held open, and whatever is opened next is opened without
    // following links: a link swapped in between the two is refused, never followed.
    char target[PATH_MAX];
    const ssize_t length = ::readlinkat(folder, part.c_str(), target, sizeof target);
    if (length >= 0)
    {
      if (last && !follow_last)
        return Answer::failure("cannot write \"" + path + "\": it is a symbolic link (not followed, not replaced)");
      if (++links > kMaxLinks || static_cast<size_t>(length) >= sizeof target)
        return Answer::failure("\"" + path + "\": too many symbolic links on the way");
      const fs::path link(std::string(target, static_cast<size_t>(length)));
      if (link.is_absolute())
      {
        if (!start(link, stack, rest))
          return Answer::failure(outside + ": a symlink on the way leads out of it");
      }
      else
      {
        std::deque<std::string> parts = componentsAfter(link, 0);
        rest.insert(rest.begin(), parts.begin(), parts.end());
      }
      continue;
    }
    if (last)
      return Place{ stack.back(), part };
    const int next = ::openat(folder, part.c_str(), O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
    if (next < 0)
    {
      if (errno == ELOOP && ++links <= kMaxLinks)  // became a link since it was read: read it again
      {
        rest.push_front(part);
        continue;
      }
      return Answer::failure("cannot open the folder \"" + part + "\" of \"" + path + "\": " + errnoText());
    }
    stack.push_back(std::make_shared<const Descriptor>(next));
  }
}

Status DataFolder::protect(const std::string& path)
{
  const Expected<std::string> real = resolve(path);
  if (!real)
    return failure(real.message());
  const fs::path file(*real);
  struct stat folder;
  if (::stat(file.parent_path().c_str(), &folder) != 0)
    return failure("cannot protect " + *real + ": " + errnoText());
  protected_.push_back({ static_cast<unsigned long>(folder.st_dev), static_cast<unsigned long>(folder.st_ino),
                         file.filename().string() });
  return success();
}

Status DataFolder::checkNotProtected(const Place& place, const std::string& path) const
{
  if (protected_.empty())
    return success();
  struct stat folder;
  if (::fstat(place.folder->get(), &folder) != 0)
    return failure("cannot check \"" + path + "\": " + errnoText());
  for (const Protected& p : protected_)
    if (p.device == folder.st_dev && p.inode == folder.st_ino && place.name.compare(0, p.name.size(), p.name) == 0)
      return failure("\"" + path + "\" is the session's journal (or a copy of it): never loaded or saved over");
  return success();
}

Expected<std::string> DataFolder::readFile(const std::string& path, size_t max_bytes) const
{
  using Answer = Expected<std::string>;
  const Expected<Place> place = locate(path, true);
  if (!place)
    return Answer::failure(place.message());
  const Status allowed = checkNotProtected(*place, path);
  if (!allowed)
    return Answer::failure(allowed.message());
  // O_NONBLOCK: opening a FIFO waits for a writer otherwise, holding the thread for good.
  const int fd =
      ::openat(place->folder->get(), place->name.c_str(), O_RDONLY | O_NOFOLLOW | O_NONBLOCK | O_NOCTTY | O_CLOEXEC);
  if (fd < 0)
    return Answer::failure(errno == ELOOP ? "cannot load \"" + path + "\": it became a symbolic link as it was opened" :
                                            "cannot open \"" + path + "\": " + errnoText());
  const Descriptor file(fd);
  struct stat status;
  if (::fstat(fd, &status) != 0)
    return Answer::failure("cannot read \"" + path + "\": " + errnoText());
  if (!S_ISREG(status.st_mode))
    return Answer::failure("cannot load \"" + path + "\": not a regular file (a FIFO, socket, device or folder)");
  if (static_cast<unsigned long long>(status.st_size) > max_bytes)
    return Answer::failure("cannot load \"" + path + "\": larger than " + std::to_string(max_bytes >> 20) + " MiB");
  std::string text;
  text.reserve(static_cast<size_t>(status.st_size));
  char buffer[1 << 16];
  while (true)
  {
    const ssize_t got = ::read(fd, buffer, sizeof buffer);
    if (got < 0 && errno == EINTR)
      continue;
    if (got < 0)
      return Answer::failure("cannot read \"" + path + "\": " + errnoText());
    if (got == 0)
      break;
    text.append(buffer, static_cast<size_t>(got));
    if (text.size() > max_bytes)  // it grew while it was read
      return Answer::failure("cannot load \"" + path + "\": larger than " + std::to_string(max_bytes >> 20) + " MiB");
  }
  return text;
}

Status DataFolder::writeFile(const std::string& path, const std::string& text) const
{
  const Expected<Place> place = locate(path, false);
  if (!place)
    return failure(place.message());
  const Status allowed = checkNotProtected(*place, path);
  if (!allowed)
    return allowed;
  return writeFileAt(place->folder->get(), place->name, text, "\"" + path + "\"");
}

}  // namespace virtual_origami::core

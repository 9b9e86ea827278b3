#include "virtual_origami/core/atomic_write.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <random>
#include <sstream>

namespace virtual_origami::core
{
namespace
{
std::string errnoText(int error = errno)
{
  return std::strerror(error);
}
}  // namespace

Status writeFileAt(int folder, const std::string& name, const std::string& text, const std::string& shown)
{
  if (name.empty() || name == "." || name == ".." || name.find('/') != std::string::npos)
    return failure("cannot write " + shown + ": not a file name");
  // Replace only a regular file the user may write: never a link (renameat would replace the
  // link, not what it points to), a device or folder, or a read-only file (renameat would
  // replace it anyway, as the folder is writable). As root access() calls every file
  // writable, so a file with no write permission at all counts as read-only too.
  struct stat target;
  const bool replacing = ::fstatat(folder, name.c_str(), &target, AT_SYMLINK_NOFOLLOW) == 0;
  if (!replacing && errno != ENOENT)
    return failure("cannot write " + shown + ": " + errnoText());
  if (replacing && S_ISLNK(target.st_mode))
    return failure("cannot write " + shown + ": it is a symbolic link (not followed, not replaced)");
  if (replacing && !S_ISREG(target.st_mode))
    return failure("cannot write " + shown + ": not a regular file");
  if (replacing &&
      ((target.st_mode & (S_IWUSR | S_IWGRP | S_IWOTH)) == 0 || ::faccessat(folder, name.c_str(), W_OK, 0) != 0))
    return failure("cannot write " + shown + ": the file is read-only");

  // A new name each time, created exclusively without following links, so nothing planted in
  // the folder (a link at the temporary name) is written through.
  thread_local std::mt19937_64 random{ std::random_device{}() };
  std::string temporary;
  int fd = -1;
  for (int attempt = 0; fd < 0; ++attempt)
  {
    std::ostringstream unique;
    unique << "." << name << "." << ::getpid() << "." << std::hex << random() << ".tmp";
    temporary = unique.str();
    fd = ::openat(folder, temporary.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0666);
    if (fd < 0 && (errno != EEXIST || attempt == 100))
      return failure("cannot write " + shown + ": " + errnoText());
  }
  const auto abandon = [&](const std::string& reason) {
    ::close(fd);
    ::unlinkat(folder, temporary.c_str(), 0);
    return failure("cannot write " + shown + ": " + reason);
  };
  if (replacing && ::fchmod(fd, target.st_mode & 07777) != 0)
    return abandon(errnoText());
  for (size_t done = 0; done < text.size();)
  {
    const ssize_t wrote = ::write(fd, text.data() + done, text.size() - done);
    if (wrote < 0 && errno == EINTR)
      continue;
    if (wrote <= 0)
      return abandon(errnoText());
    done += static_cast<size_t>(wrote);
  }
  // On disk before the rename makes it the file: a crash leaves the old file or the new one.
  if (::fsync(fd) != 0)
    return abandon(errnoText());
  if (::close(fd) != 0)
  {
    const std::string reason = errnoText();
    ::unlinkat(folder, temporary.c_str(), 0);
    return failure("cannot write " + shown + ": " + reason);
  }
  if (::renameat(folder, temporary.c_str(), folder, name.c_str()) != 0)
  {
    const std::string reason = errnoText();
    ::unlinkat(folder, temporary.c_str(), 0);
    return failure("cannot write " + shown + ": " + reason);
  }
  ::fsync(folder);  // the rename on disk too (best effort: some file systems refuse)
  return success();
}

}  // namespace virtual_origami::core

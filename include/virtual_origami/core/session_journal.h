// A session's history on disk, so that nothing a user did is lost when a node restarts or
// crashes: one JSON line per event, appended and flushed as it happens.
#pragma once

#include <fstream>
#include <string>

#include "virtual_origami/core/result.h"
#include "virtual_origami/core/session.h"

namespace virtual_origami::core
{
/// Bit-exact JSON of a paper (doubles printed to round-trip).
std::string formatPaperJson(const Paper& paper);
Expected<Paper> parsePaperJson(const std::string& text);

/// Appends a session's events to a file: a header line with the whole history so far, then
/// for each operation logged after it a commit (with the state it made) or an undo/redo.
class SessionJournal
{
public:
  /// Starts a new journal for `session` at `path` (replacing any file there), writing its
  /// whole history so far.
  Status start(const std::string& path, const Session& session);
  /// Appends the operations `session` logged since the last call. Call it after every
  /// operation: a commit's event carries the session's current state.
  Status record(const Session& session);
  const std::string& path() const { return path_; }

private:
  Status writeLine(const std::string& line);
  std::string path_;
  std::ofstream out_;
  size_t recorded_ = 0;  // operations of the log already written
};

/// The session a journal describes. A torn last line (a crash while writing) is ignored;
/// any other damage is an error naming the line.
Expected<History> readJournal(const std::string& path);

}  // namespace virtual_origami::core

// FOLD format (https://github.com/edemaine/fold) read and write.
#pragma once

#include <string>
#include <vector>

#include "virtual_origami/core/paper.h"
#include "virtual_origami/core/result.h"

namespace virtual_origami::core
{
/// Frames of a FOLD file, each resolved to a full paper (inheritance applied, crease
/// pattern recovered by unfolding where the frame holds only a folded form).
struct FoldDocument
{
  std::string title;
  std::string creator;
  std::vector<Paper> frames;  // frames[0] is the file's top-level frame
};

/// Parses FOLD text. Rejects malformed input with a message naming the field (or, for broken
/// JSON, the line and column), never quoting the text. A concave face is split into convex
/// pieces joined by flat edges marked Edge::split; a face that crosses or touches itself, or
/// winds around twice, is refused.
Expected<FoldDocument> parseFold(const std::string& text);
Expected<FoldDocument> readFoldFile(const std::string& path);

/// Writes one state: the crease pattern as the key frame, the folded form as frame 1. Faces
/// joined by split edges still flat (F) are written as the one face they were read as, and
/// those edges left out.
std::string formatFold(const Paper& paper, const std::string& title = "");
/// Writes a folding sequence, one frame per state.
std::string formatFoldSequence(const std::vector<Paper>& steps, const std::string& title = "");
/// Writes text to a file atomically: into a new temporary file beside it (created exclusively,
/// never through a link), synced to disk, then renamed over it, keeping its permissions.
/// Refuses, changing nothing, a target that is a symbolic link, not a regular file, or
/// read-only (no write permission, also when running as root).
Status writeTextFile(const std::string& path, const std::string& text);

/// The state a file describes: its last frame.
Expected<Paper> loadPaper(const std::string& path);

}  // namespace virtual_origami::core

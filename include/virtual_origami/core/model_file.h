// A model file as load takes it: the format its name says, a size check before the expensive
// work, then the parse. The file's text is read by the caller (DataFolder::readFile), so that
// no parser opens a path a client named.
#pragma once

#include <cstddef>
#include <optional>
#include <string>

#include "virtual_origami/core/paper.h"
#include "virtual_origami/core/result.h"

namespace virtual_origami::core
{
enum class ModelFormat
{
  Fold,
  OripaCp,
  OripaOpx,
};

/// By the name's extension (case-insensitive): `.cp`, `.opx`, else FOLD. None for names that are
/// never a model: a recording (`.bag`, `.bag.active`) or a journal (`.jsonl`).
std::optional<ModelFormat> modelFormat(const std::string& path);

/// The vertices the text declares, counted without building the model: FOLD, the longest
/// vertices_coords of any frame; ORIPA, two per line (every line may add two vertices, and
/// crossings more). Refused over `max_vertices` (0: no limit), before the parse whose cost
/// grows with them; text a parser would refuse anyway passes (the parser says why).
Status checkModelSize(const std::string& text, ModelFormat format, size_t max_vertices);

/// The paper the text describes (FOLD: its last frame; ORIPA: scaled to `size`).
Expected<Paper> parseModel(const std::string& text, ModelFormat format, double size);

}  // namespace virtual_origami::core

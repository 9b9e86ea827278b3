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
  Svg,  // Origami Simulator's convention (svg_pattern.h)
};

/// By the name's extension (case-insensitive): `.cp`, `.opx`, `.svg`, else FOLD. None for names that are
/// never a model: a recording (`.bag`, `.bag.active`) or a journal (`.jsonl`).
std::optional<ModelFormat> modelFormat(const std::string& path);

/// What load takes, so that every load is answered in seconds: the checks the parse and the
/// validity check make grow with the vertices, and with the square of a face's vertices (a
/// 200,000-vertex polygon got no answer in 780 s; an 8,000-gon takes 0.75 s, a 1,000-gon 0.01 s).
struct ModelLimits
{
  size_t max_vertices = 100000;     // 0: no limit
  size_t max_face_vertices = 1000;  // 0: no limit
};

/// The vertices and the largest face the text declares, counted without building the model:
/// FOLD, the longest vertices_coords and faces_vertices entry of any frame; ORIPA, two vertices
/// per line (every line may add two vertices, and crossings more); SVG, one per number pair
/// written (a curve adds more: its faces are checked after the parse). Refused over the limits,
/// before the parse; text a parser would refuse anyway passes (the parser says why).
Status checkModelSize(const std::string& text, ModelFormat format, const ModelLimits& limits);

/// After the parse, before the validity check: the faces the parse traced (from a FOLD file's
/// edges, an ORIPA file's lines) within max_face_vertices.
Status checkFaceSizes(const Paper& paper, const ModelLimits& limits);

/// The paper the text describes (FOLD: its last frame; ORIPA and SVG: scaled to `size`).
Expected<Paper> parseModel(const std::string& text, ModelFormat format, double size);

}  // namespace virtual_origami::core

#include "virtual_origami/core/model_file.h"

#include <algorithm>
#include <cctype>
#include <cstring>
#include <utility>

#include <nlohmann/json.hpp>

#include "virtual_origami/core/fold_io.h"
#include "virtual_origami/core/oripa_io.h"
#include "virtual_origami/core/svg_pattern.h"

namespace virtual_origami::core
{
namespace
{
bool endsWith(const std::string& s, const std::string& suffix)
{
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

/// The most vertices of any frame, and of any face.
std::pair<size_t, size_t> foldSizes(const std::string& text)
{
  const nlohmann::json root = nlohmann::json::parse(text, nullptr, false);
  if (root.is_discarded() || !root.is_object())
    return { 0, 0 };
  size_t vertices = 0, face = 0;
  const auto count = [&](const nlohmann::json& frame) {
    const auto coords = frame.find("vertices_coords");
    if (coords != frame.end() && coords->is_array())
      vertices = std::max(vertices, coords->size());
    const auto faces = frame.find("faces_vertices");
    if (faces != frame.end() && faces->is_array())
      for (const nlohmann::json& f : *faces)
        if (f.is_array())
          face = std::max(face, f.size());
  };
  count(root);
  const auto frames = root.find("file_frames");
  if (frames != root.end() && frames->is_array())
    for (const nlohmann::json& frame : *frames)
      if (frame.is_object())
        count(frame);
  return { vertices, face };
}

Status faceWithin(size_t face, const ModelLimits& limits)
{
  if (limits.max_face_vertices > 0 && face > limits.max_face_vertices)
    return failure("the model has a face of " + std::to_string(face) + " vertices, more than max_face_vertices (" +
                   std::to_string(limits.max_face_vertices) + "): refused before it is checked");
  return success();
}

size_t countOf(const std::string& text, const char* word)
{
  size_t count = 0;
  for (size_t at = text.find(word); at != std::string::npos; at = text.find(word, at + 1))
    ++count;
  return count;
}
/// Runs of digits: an upper bound on the numbers an SVG writes.
size_t numbersIn(const std::string& text)
{
  size_t count = 0;
  for (size_t i = 0; i < text.size(); ++i)
    count += std::isdigit(static_cast<unsigned char>(text[i])) &&
             (i == 0 || (!std::isdigit(static_cast<unsigned char>(text[i - 1])) && text[i - 1] != '.'));
  return count;
}
}  // namespace

std::optional<ModelFormat> modelFormat(const std::string& path)
{
  std::string lower = path;
  std::transform(lower.begin(), lower.end(), lower.begin(), [](unsigned char c) { return std::tolower(c); });
  if (endsWith(lower, ".bag") || endsWith(lower, ".bag.active") || endsWith(lower, ".jsonl"))
    return std::nullopt;
  if (endsWith(lower, ".cp"))
    return ModelFormat::OripaCp;
  if (endsWith(lower, ".opx"))
    return ModelFormat::OripaOpx;
  if (endsWith(lower, ".svg"))
    return ModelFormat::Svg;
  return ModelFormat::Fold;
}

Status checkModelSize(const std::string& text, ModelFormat format, const ModelLimits& limits)
{
  size_t vertices = 0;
  const char* what = "vertices";
  switch (format)
  {
    case ModelFormat::Fold: {
      const auto [most, face] = foldSizes(text);
      const Status faces = faceWithin(face, limits);
      if (!faces)
        return faces;
      vertices = most;
      break;
    }
    case ModelFormat::OripaCp:
      // Every non-blank line is a segment.
      for (size_t begin = 0; begin < text.size();)
      {
        size_t end = text.find('\n', begin);
        if (end == std::string::npos)
          end = text.size();
        if (std::any_of(text.begin() + static_cast<std::ptrdiff_t>(begin),
                        text.begin() + static_cast<std::ptrdiff_t>(end),
                        [](unsigned char c) { return !std::isspace(c); }))
          vertices += 2;
        begin = end + 1;
      }
      what = "vertices (two per line)";
      break;
    case ModelFormat::OripaOpx:
      vertices = 2 * countOf(text, "oripa.OriLineProxy");
      what = "vertices (two per line)";
      break;
    case ModelFormat::Svg:
      vertices = numbersIn(text) / 2;
      what = "vertices (one per pair of numbers)";
      break;
  }
  if (limits.max_vertices > 0 && vertices > limits.max_vertices)
    return failure("the model has " + std::to_string(vertices) + " " + what + ", more than max_load_vertices (" +
                   std::to_string(limits.max_vertices) + "): refused before it is read");
  return success();
}

Status checkFaceSizes(const Paper& paper, const ModelLimits& limits)
{
  size_t face = 0;
  for (const Face& f : paper.faces)
    face = std::max(face, f.vertices.size());
  return faceWithin(face, limits);
}

Expected<Paper> parseModel(const std::string& text, ModelFormat format, double size)
{
  switch (format)
  {
    case ModelFormat::OripaCp:
      return parseOripaCp(text, size);
    case ModelFormat::OripaOpx:
      return parseOripaOpx(text, size);
    case ModelFormat::Svg:
      return parseSvgPattern(text, size);
    case ModelFormat::Fold:
      break;
  }
  Expected<FoldDocument> document = parseFold(text);
  if (!document)
    return Expected<Paper>::failure(document.message());
  return std::move(document->frames.back());
}

}  // namespace virtual_origami::core

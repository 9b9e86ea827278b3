// A FOLD frame's fields, read from JSON and checked. Private to the FOLD reader.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "virtual_origami/core/paper.h"

namespace virtual_origami::core
{
using json = nlohmann::json;

/// One frame's fields, checked and converted (fold angles to radians).
struct FrameData
{
  std::vector<Vec3> coords;
  std::optional<std::vector<std::array<int, 2>>> edges;
  std::optional<std::vector<Assignment>> assignments;
  /// Per edge; an entry is empty where the file says null (FOLD: no value).
  std::optional<std::vector<std::optional<double>>> fold_angles;
  std::optional<std::vector<std::optional<double>>> target_angles;
  std::optional<std::vector<char>> facets;  // our own: which edges are facets (kFacetKey)
  std::optional<std::vector<std::vector<int>>> faces;
  std::vector<std::array<int, 3>> face_orders;  // [f, g, s] as in the file
  std::optional<std::vector<Vec2>> crease_pattern;
  std::vector<std::string> classes;
};

/// The frame's fields; refuses a malformed one (FormatError) naming the field.
FrameData readFrame(const json& frame);

/// "name[i]", for messages.
std::string indexed(const std::string& name, size_t i);
/// What a JSON value is, for a message: never the value itself, so that no message quotes
/// the file (loading any file, a private one too, must not echo what is in it).
std::string kindOf(const json& value);
/// The field, or nullptr when the object has none or it is null (FOLD: no value).
const json* findField(const json& object, const std::string& key);
/// Refuses (FormatError) a value that is not an array.
void requireArray(const json& value, const std::string& name);
/// A whole number from 0, written as an integer or a double.
int readIndex(const json& value, const std::string& name);
/// The string field, nothing when absent; refuses another kind of value.
std::optional<std::string> readOptionalString(const json& object, const std::string& key);

}  // namespace virtual_origami::core

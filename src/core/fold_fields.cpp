// A FOLD frame's fields read from JSON: each checked (a message names the field, never quoting
// the file) and converted (fold angles to radians).
#include "fold_fields.h"

#include <algorithm>
#include <array>
#include <climits>
#include <cmath>
#include <string>

#include "fold_format.h"
#include "format_error.h"

namespace virtual_origami::core
{
std::string indexed(const std::string& name, size_t i)
{
  return name + "[" + std::to_string(i) + "]";
}

std::string kindOf(const json& value)
{
  switch (value.type())
  {
    case json::value_t::null:
      return "null";
    case json::value_t::boolean:
      return "true or false";
    case json::value_t::number_integer:
    case json::value_t::number_unsigned:
    case json::value_t::number_float:
      return "a number";
    case json::value_t::string:
      return "a string";
    case json::value_t::array:
      return value.empty() ? "an empty array" : "an array of " + std::to_string(value.size());
    case json::value_t::object:
      return "an object";
    default:
      return "no JSON value";
  }
}

const json* findField(const json& object, const std::string& key)
{
  // FOLD's null is "no value": a field that holds it is absent.
  const auto it = object.find(key);
  return it == object.end() || it->is_null() ? nullptr : &*it;
}

void requireArray(const json& value, const std::string& name)
{
  if (!value.is_array())
    fail(name + " is " + kindOf(value) + ", not an array");
}

int readIndex(const json& value, const std::string& name)
{
  // Accept 3.0 as well as 3: some writers print every number as a double.
  const double x = value.is_number() ? value.get<double>() : -1.0;
  if (!(x >= 0 && x <= INT_MAX && x == std::floor(x)))
    fail(name + " is " + (value.is_number() ? std::string("a number but") : kindOf(value) + ",") +
         " not an index (a whole number from 0)");
  return static_cast<int>(x);
}

std::optional<std::string> readOptionalString(const json& object, const std::string& key)
{
  const json* field = findField(object, key);
  if (!field)
    return std::nullopt;
  if (!field->is_string())
    fail(key + " is " + kindOf(*field) + ", not a string");
  return field->get<std::string>();
}

namespace
{
double readNumber(const json& value, const std::string& name)
{
  if (!value.is_number())
    fail(name + " is " + kindOf(value) + ", not a number");
  const double x = value.get<double>();
  if (!std::isfinite(x))
    fail(name + " is not a finite number");
  return x;
}

int readVertexIndex(const json& value, const std::string& name, size_t vertex_count)
{
  const int v = readIndex(value, name);
  if (static_cast<size_t>(v) >= vertex_count)
    fail(name + " names vertex " + std::to_string(v) + " but there are " + std::to_string(vertex_count) + " vertices");
  return v;
}

std::vector<std::string> readStrings(const json& object, const std::string& key)
{
  std::vector<std::string> strings;
  const json* field = findField(object, key);
  if (!field)
    return strings;
  requireArray(*field, key);
  for (size_t i = 0; i < field->size(); ++i)
  {
    if (!(*field)[i].is_string())
      fail(indexed(key, i) + " is " + kindOf((*field)[i]) + ", not a string");
    strings.push_back((*field)[i].get<std::string>());
  }
  return strings;
}

/// Checks that an edge field has one entry per edge and returns it, or nullptr when absent.
const json* edgeField(const json& frame, const std::string& key, const std::optional<size_t>& edge_count)
{
  const json* field = findField(frame, key);
  if (!field)
    return nullptr;
  requireArray(*field, key);
  if (!edge_count)
    fail(key + " is given but edges_vertices is missing");
  if (field->size() != *edge_count)
    fail(key + " has " + std::to_string(field->size()) + " entries but edges_vertices has " +
         std::to_string(*edge_count));
  return field;
}

/// 2D coordinates get z = 0: whether a frame is flat is decided from the points, not their length.
std::vector<Vec3> readCoords(const json& frame)
{
  const json* field = findField(frame, "vertices_coords");
  if (!field)
    fail("vertices_coords is missing");
  requireArray(*field, "vertices_coords");
  if (field->empty())
    fail("vertices_coords is empty");
  std::vector<Vec3> coords;
  for (size_t i = 0; i < field->size(); ++i)
  {
    const json& entry = (*field)[i];
    const std::string name = indexed("vertices_coords", i);
    requireArray(entry, name);
    if (entry.size() != 2 && entry.size() != 3)
      fail(name + " has " + std::to_string(entry.size()) + " coordinates, not 2 or 3");
    Vec3 p = Vec3::Zero();
    for (size_t k = 0; k < entry.size(); ++k)
      p[k] = readNumber(entry[k], indexed(name, k));
    coords.push_back(p);
  }
  return coords;
}

std::optional<std::vector<std::array<int, 2>>> readEdges(const json& frame, size_t vertex_count)
{
  const json* field = findField(frame, "edges_vertices");
  if (!field)
    return std::nullopt;
  requireArray(*field, "edges_vertices");
  std::vector<std::array<int, 2>> edges;
  for (size_t e = 0; e < field->size(); ++e)
  {
    const json& entry = (*field)[e];
    const std::string name = indexed("edges_vertices", e);
    if (!entry.is_array() || entry.size() != 2)
      fail(name + " is " + kindOf(entry) + ", not a pair of vertices");
    const std::array<int, 2> ends{ readVertexIndex(entry[0], name, vertex_count),
                                   readVertexIndex(entry[1], name, vertex_count) };
    if (ends[0] == ends[1])
      fail(name + " joins vertex " + std::to_string(ends[0]) + " to itself");
    edges.push_back(ends);
  }
  return edges;
}

std::optional<std::vector<Assignment>> readAssignments(const json& frame, const std::optional<size_t>& edge_count)
{
  const json* field = edgeField(frame, "edges_assignment", edge_count);
  if (!field)
    return std::nullopt;
  std::vector<Assignment> assignments;
  for (size_t e = 0; e < field->size(); ++e)
  {
    const json& entry = (*field)[e];
    if (entry.is_null())  // no value: an edge nobody assigned
    {
      assignments.push_back(Assignment::Unassigned);
      continue;
    }
    const std::optional<Assignment> assignment =
        entry.is_string() ? assignmentFromLetter(entry.get<std::string>()) : std::nullopt;
    if (!assignment)
      fail(indexed("edges_assignment", e) + " is not one of the letters B M V F U C");
    assignments.push_back(*assignment);
  }
  return assignments;
}

std::optional<std::vector<std::optional<double>>> readFoldAngles(const json& frame,
                                                                 const std::optional<size_t>& edge_count)
{
  // FOLD 1.0 called the field edges_foldAngles.
  const std::string key = findField(frame, "edges_foldAngle") ? "edges_foldAngle" : "edges_foldAngles";
  const json* field = edgeField(frame, key, edge_count);
  if (!field)
    return std::nullopt;
  std::vector<std::optional<double>> angles;
  for (size_t e = 0; e < field->size(); ++e)
  {
    if ((*field)[e].is_null())  // FOLD's "no value" (Origami Simulator writes it for boundaries)
    {
      angles.emplace_back();
      continue;
    }
    const double degrees = readNumber((*field)[e], indexed(key, e));
    if (std::abs(degrees) > 180.0 + 1e-9)
      fail(indexed(key, e) + " is outside [-180, 180] degrees");
    angles.push_back(toRadians(std::max(-180.0, std::min(180.0, degrees))));
  }
  return angles;
}

std::optional<std::vector<std::optional<double>>> readTargetAngles(const json& frame,
                                                                   const std::optional<size_t>& edge_count)
{
  const json* field = edgeField(frame, kTargetAngleKey, edge_count);
  if (!field)
    return std::nullopt;
  std::vector<std::optional<double>> angles;
  for (size_t e = 0; e < field->size(); ++e)
  {
    if ((*field)[e].is_null())
    {
      angles.emplace_back();
      continue;
    }
    const double degrees = readNumber((*field)[e], indexed(kTargetAngleKey, e));
    if (std::abs(degrees) > 180.0 + 1e-9)
      fail(indexed(kTargetAngleKey, e) + " is outside [-180, 180] degrees");
    angles.emplace_back(toRadians(std::max(-180.0, std::min(180.0, degrees))));
  }
  return angles;
}

std::optional<std::vector<char>> readFacets(const json& frame, const std::optional<size_t>& edge_count)
{
  const json* field = edgeField(frame, kFacetKey, edge_count);
  if (!field)
    return std::nullopt;
  std::vector<char> facets;
  for (size_t e = 0; e < field->size(); ++e)
  {
    if (!(*field)[e].is_boolean())
      fail(indexed(kFacetKey, e) + " is " + kindOf((*field)[e]) + ", not true or false");
    facets.push_back((*field)[e].get<bool>() ? 1 : 0);
  }
  return facets;
}

std::optional<std::vector<std::vector<int>>> readFaces(const json& frame, size_t vertex_count)
{
  const json* field = findField(frame, "faces_vertices");
  if (!field)
    return std::nullopt;
  requireArray(*field, "faces_vertices");
  std::vector<std::vector<int>> faces;
  for (size_t f = 0; f < field->size(); ++f)
  {
    const json& entry = (*field)[f];
    const std::string name = indexed("faces_vertices", f);
    requireArray(entry, name);
    if (entry.size() < 3)
      fail(name + " has " + std::to_string(entry.size()) + " vertices; a face needs at least 3");
    std::vector<int> cycle;
    for (size_t i = 0; i < entry.size(); ++i)
    {
      const int v = readVertexIndex(entry[i], indexed(name, i), vertex_count);
      if (std::find(cycle.begin(), cycle.end(), v) != cycle.end())
        fail(name + " visits vertex " + std::to_string(v) + " twice");
      cycle.push_back(v);
    }
    faces.push_back(cycle);
  }
  return faces;
}

std::vector<std::array<int, 3>> readFaceOrders(const json& frame)
{
  std::vector<std::array<int, 3>> orders;
  const json* field = findField(frame, "faceOrders");
  if (!field)
    return orders;
  requireArray(*field, "faceOrders");
  for (size_t i = 0; i < field->size(); ++i)
  {
    const json& entry = (*field)[i];
    const std::string name = indexed("faceOrders", i);
    if (!entry.is_array() || entry.size() != 3)
      fail(name + " is " + kindOf(entry) + ", not a triple [f, g, s]");
    const int f = readIndex(entry[0], indexed(name, 0));
    const int g = readIndex(entry[1], indexed(name, 1));
    const double s = entry[2].is_number() ? entry[2].get<double>() : 2.0;
    if (s != -1.0 && s != 0.0 && s != 1.0)
      fail(name + " has an order other than -1, 0 or 1");
    orders.push_back({ f, g, static_cast<int>(s) });
  }
  return orders;
}

std::optional<std::vector<Vec2>> readCreasePatternField(const json& frame, size_t vertex_count)
{
  const json* field = findField(frame, kCreasePatternKey);
  if (!field)
    return std::nullopt;
  const std::string key = kCreasePatternKey;
  requireArray(*field, key);
  if (field->size() != vertex_count)
    fail(key + " has " + std::to_string(field->size()) + " entries but vertices_coords has " +
         std::to_string(vertex_count));
  std::vector<Vec2> points;
  for (size_t i = 0; i < field->size(); ++i)
  {
    const json& entry = (*field)[i];
    if (!entry.is_array() || entry.size() != 2)
      fail(indexed(key, i) + " is " + kindOf(entry) + ", not a 2D point");
    points.emplace_back(readNumber(entry[0], indexed(indexed(key, i), 0)),
                        readNumber(entry[1], indexed(indexed(key, i), 1)));
  }
  return points;
}

}  // namespace

FrameData readFrame(const json& frame)
{
  FrameData data;
  data.coords = readCoords(frame);
  const size_t vertex_count = data.coords.size();
  data.edges = readEdges(frame, vertex_count);
  const std::optional<size_t> edge_count = data.edges ? std::optional<size_t>(data.edges->size()) : std::nullopt;
  data.assignments = readAssignments(frame, edge_count);
  data.fold_angles = readFoldAngles(frame, edge_count);
  data.target_angles = readTargetAngles(frame, edge_count);
  data.facets = readFacets(frame, edge_count);
  data.faces = readFaces(frame, vertex_count);
  if (!data.edges && !data.faces)
    fail("edges_vertices and faces_vertices are both missing");
  data.face_orders = readFaceOrders(frame);
  data.crease_pattern = readCreasePatternField(frame, vertex_count);
  data.classes = readStrings(frame, "frame_classes");
  readOptionalString(frame, "frame_title");
  return data;
}

}  // namespace virtual_origami::core

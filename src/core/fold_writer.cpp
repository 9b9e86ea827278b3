// FOLD write: the crease pattern as the key frame and the folded form as a frame of its own, in
// JSON laid out to be read and diffed; and the atomic file write every saved file goes through.
#include "virtual_origami/core/fold_io.h"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <functional>
#include <map>
#include <set>
#include <sstream>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <nlohmann/json.hpp>

#include "fold_format.h"
#include "virtual_origami/core/atomic_write.h"
#include "virtual_origami/core/compliant_faces.h"

namespace virtual_origami::core
{
namespace
{
using ordered_json = nlohmann::ordered_json;

ordered_json creasePatternCoords(const Paper& paper)
{
  ordered_json coords = ordered_json::array();
  for (const Vertex& v : paper.vertices)
    coords.push_back({ v.crease_pattern.x(), v.crease_pattern.y() });
  return coords;
}

ordered_json foldedCoords(const Paper& paper)
{
  ordered_json coords = ordered_json::array();
  for (const Vertex& v : paper.vertices)
    coords.push_back({ v.folded.x(), v.folded.y(), v.folded.z() });
  return coords;
}

/// The faces and edges a file gets: faces joined by split edges that are still flat (F) are
/// merged back into the face they were split from, and those edges left out. A group whose
/// outline is not one simple cycle (creased since in a way that pinches it) stays in pieces,
/// with its split edges, which is still a valid FOLD.
struct FileTopology
{
  std::vector<std::vector<int>> faces;
  std::vector<int> edges;    // the paper's edges the file keeps, in order
  std::vector<int> face_of;  // for each paper face, the file face it is (part of)
};

/// The outline of a group of faces joined across `inside` edges, counter-clockwise from the
/// first face's first vertex; empty unless it is one cycle through every vertex of the group.
std::vector<int> outline(const Paper& paper, const std::vector<int>& group, const std::vector<char>& inside)
{
  std::map<int, int> next;
  std::vector<int> vertices;
  size_t sides = 0;
  for (int f : group)
  {
    const Face& face = paper.faces[f];
    for (size_t i = 0; i < face.vertices.size(); ++i)
    {
      vertices.push_back(face.vertices[i]);
      if (inside[face.edges[i]])
        continue;
      if (!next.emplace(face.vertices[i], face.vertices[(i + 1) % face.vertices.size()]).second)
        return {};  // the outline passes a vertex twice
      ++sides;
    }
  }
  const int start = paper.faces[group.front()].vertices.front();
  std::vector<int> cycle;
  for (int v = start; cycle.size() <= sides; v = next.at(v))
  {
    if (!next.count(v))
      return {};
    cycle.push_back(v);
    if (next.at(v) == start)
      break;
  }
  std::sort(vertices.begin(), vertices.end());
  vertices.erase(std::unique(vertices.begin(), vertices.end()), vertices.end());
  if (cycle.size() != sides || cycle.size() != vertices.size())
    return {};
  return cycle;
}

FileTopology fileTopology(const Paper& paper)
{
  const size_t face_count = paper.faces.size();
  // Union-find of the faces across flat split edges; each group's root is its first face.
  std::vector<int> root(face_count);
  for (size_t f = 0; f < face_count; ++f)
    root[f] = static_cast<int>(f);
  const std::function<int(int)> find = [&](int f) { return root[f] == f ? f : root[f] = find(root[f]); };
  std::vector<char> inside(paper.edges.size(), 0);
  for (size_t e = 0; e < paper.edges.size(); ++e)
  {
    const Edge& edge = paper.edges[e];
    // A facet that bends (a kept bend) stays in the file, with its mesh.
    const bool bends = isFacet(edge) && (edge.fold_angle != 0.0 || *edge.target_angle != 0.0);
    if (!edge.split || !edge.isCrease() || edge.assignment != Assignment::Flat || bends)
      continue;
    inside[e] = 1;
    const int a = find(edge.faces[0]), b = find(edge.faces[1]);
    root[std::max(a, b)] = std::min(a, b);
  }
  std::vector<std::vector<int>> groups(face_count);
  for (size_t f = 0; f < face_count; ++f)
    groups[find(static_cast<int>(f))].push_back(static_cast<int>(f));
  FileTopology file;
  file.face_of.assign(face_count, -1);
  std::vector<char> merged(face_count, 0);
  for (size_t f = 0; f < face_count; ++f)
  {
    const std::vector<int>& group = groups[f];
    if (group.empty())
      continue;  // f is in an earlier face's group
    std::vector<int> cycle = group.size() > 1 ? outline(paper, group, inside) : std::vector<int>{};
    if (cycle.empty())
    {
      for (int g : group)  // in pieces: each face its own, in order
        merged[g] = 0;
      continue;
    }
    for (int g : group)
      merged[g] = 1;
    file.face_of[f] = static_cast<int>(file.faces.size());
    file.faces.push_back(cycle);
  }
  for (size_t f = 0; f < face_count; ++f)
  {
    if (merged[f])
    {
      file.face_of[f] = file.face_of[find(static_cast<int>(f))];
      continue;
    }
    file.face_of[f] = static_cast<int>(file.faces.size());
    file.faces.push_back(paper.faces[f].vertices);
  }
  for (size_t e = 0; e < paper.edges.size(); ++e)
    if (!inside[e] || !merged[paper.edges[e].faces[0]])
      file.edges.push_back(static_cast<int>(e));
  return file;
}

/// Edges, faces and layer order: everything but the coordinates.
void addTopology(ordered_json& frame, const Paper& paper)
{
  const FileTopology file = fileTopology(paper);
  ordered_json edges = ordered_json::array(), assignments = ordered_json::array(), angles = ordered_json::array();
  for (int e : file.edges)
  {
    const Edge& edge = paper.edges[e];
    edges.push_back({ edge.vertices[0], edge.vertices[1] });
    assignments.push_back(std::string(1, assignmentLetter(edge.assignment)));
    angles.push_back(toDegrees(edge.fold_angle));
  }
  ordered_json faces = ordered_json::array();
  for (const std::vector<int>& face : file.faces)
    faces.push_back(face);
  frame["edges_vertices"] = edges;
  frame["edges_assignment"] = assignments;
  frame["edges_foldAngle"] = angles;
  if (std::any_of(file.edges.begin(), file.edges.end(), [&](int e) { return paper.edges[e].target_angle.has_value(); }))
  {
    ordered_json targets = ordered_json::array();
    for (int e : file.edges)
    {
      const std::optional<double>& target = paper.edges[e].target_angle;
      targets.push_back(target ? ordered_json(toDegrees(*target)) : ordered_json(nullptr));
    }
    frame[kTargetAngleKey] = targets;
  }
  if (std::any_of(file.edges.begin(), file.edges.end(), [&](int e) { return isFacet(paper.edges[e]); }))
  {
    ordered_json facets = ordered_json::array();
    for (int e : file.edges)
      facets.push_back(isFacet(paper.edges[e]));
    frame[kFacetKey] = facets;
  }
  frame["faces_vertices"] = faces;
  // Pieces of one face share its orders: each pair once, none of a face with itself.
  ordered_json orders = ordered_json::array();
  std::set<std::pair<int, int>> written;
  for (const FaceOrder& order : paper.face_orders)
  {
    const int face = file.face_of[order.face], other = file.face_of[order.other];
    if (face != other && written.emplace(face, other).second)
      orders.push_back({ other, face, order.above });  // see faceOrdersOf
  }
  if (!orders.empty())
    frame["faceOrders"] = orders;
}

ordered_json fileHeader(const std::string& title, const std::string& file_class)
{
  ordered_json file;
  file["file_spec"] = 1.1;
  file["file_creator"] = "virtual_origami";
  file["file_classes"] = { file_class };
  if (!title.empty())
    file["file_title"] = title;
  return file;
}

/// A standalone folded-form frame: 3D coordinates, with the crease pattern in our own field.
ordered_json foldedFormFrame(const Paper& paper)
{
  ordered_json frame;
  frame["frame_classes"] = { "foldedForm" };
  frame["frame_attributes"] = { "3D" };
  frame["vertices_coords"] = foldedCoords(paper);
  frame[kCreasePatternKey] = creasePatternCoords(paper);
  addTopology(frame, paper);
  return frame;
}

/// JSON with one object key or nested array entry per line and the innermost arrays on one
/// line: readable and diffable, and close to what other FOLD tools write. Numbers come out
/// in the shortest form that reads back to the same double.
void appendJson(const ordered_json& value, const std::string& indent, std::string& out)
{
  const std::string inner = indent + "  ";
  if (value.is_object() && !value.empty())
  {
    out += "{";
    bool first = true;
    for (const auto& [key, item] : value.items())
    {
      out += (first ? "\n" : ",\n") + inner + ordered_json(key).dump() + ": ";
      appendJson(item, inner, out);
      first = false;
    }
    out += "\n" + indent + "}";
  }
  else if (value.is_array() && !value.empty() && value.front().is_structured())
  {
    out += "[";
    for (size_t i = 0; i < value.size(); ++i)
    {
      out += (i == 0 ? "\n" : ",\n") + inner;
      appendJson(value[i], inner, out);
    }
    out += "\n" + indent + "]";
  }
  else
    out += value.dump();
}

std::string dumpFold(const ordered_json& file)
{
  std::string out;
  appendJson(file, "", out);
  return out + "\n";
}

}  // namespace

std::string formatFold(const Paper& paper, const std::string& title)
{
  ordered_json file = fileHeader(title, "singleModel");
  file["frame_classes"] = { "creasePattern" };
  file["frame_attributes"] = { "2D" };
  file["vertices_coords"] = creasePatternCoords(paper);
  addTopology(file, paper);
  ordered_json folded;
  folded["frame_classes"] = { "foldedForm" };
  folded["frame_attributes"] = { "3D" };
  folded["frame_inherit"] = true;
  folded["frame_parent"] = 0;
  folded["vertices_coords"] = foldedCoords(paper);
  file["file_frames"] = ordered_json::array({ folded });
  return dumpFold(file);
}

std::string formatFoldSequence(const std::vector<Paper>& steps, const std::string& title)
{
  // Steps may differ in topology (creases get added), so every frame stands alone.
  ordered_json file = fileHeader(title, "diagrams");
  if (steps.empty())
    return dumpFold(file);
  const ordered_json key_frame = foldedFormFrame(steps.front());
  for (const auto& [key, value] : key_frame.items())
    file[key] = value;
  ordered_json frames = ordered_json::array();
  for (size_t i = 1; i < steps.size(); ++i)
    frames.push_back(foldedFormFrame(steps[i]));
  if (!frames.empty())
    file["file_frames"] = frames;
  return dumpFold(file);
}

Status writeTextFile(const std::string& path, const std::string& text)
{
  const std::filesystem::path target(path);
  const std::string name = target.filename().string();
  const std::string folder_name = target.has_parent_path() ? target.parent_path().string() : ".";
  const int folder = ::open(folder_name.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (folder < 0)
    return failure("cannot write " + path + ": " + std::strerror(errno));
  const Status written = writeFileAt(folder, name, text, path);
  ::close(folder);
  return written;
}

}  // namespace virtual_origami::core

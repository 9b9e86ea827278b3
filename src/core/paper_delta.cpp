#include "virtual_origami/core/paper_delta.h"

#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

namespace virtual_origami::core
{
using nlohmann::json;

namespace
{
uint64_t bitsOf(double value)
{
  uint64_t bits = 0;
  std::memcpy(&bits, &value, sizeof(bits));
  return bits;
}

/// Equal by bits: a delta must carry a change from 0.0 to -0.0 too, or the restore differs.
bool same(double a, double b)
{
  return bitsOf(a) == bitsOf(b);
}
bool same(const Vec2& a, const Vec2& b)
{
  return same(a.x(), b.x()) && same(a.y(), b.y());
}
bool same(const Vec3& a, const Vec3& b)
{
  return same(a.x(), b.x()) && same(a.y(), b.y()) && same(a.z(), b.z());
}
bool same(const std::optional<double>& a, const std::optional<double>& b)
{
  return a.has_value() == b.has_value() && (!a || same(*a, *b));
}

/// Everything of an edge a delta carries but its fold angle (faces are derived).
bool sameButAngle(const Edge& a, const Edge& b)
{
  return a.vertices == b.vertices && a.assignment == b.assignment && a.split == b.split &&
         same(a.target_angle, b.target_angle);
}

/// splitmix64's finaliser over the running value: every bit of a word reaches every bit.
struct Fingerprint
{
  uint64_t value = 0x6a09e667f3bcc909ull;
  void add(uint64_t word)
  {
    uint64_t z = value ^ word;
    z += 0x9e3779b97f4a7c15ull;
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    value = z ^ (z >> 31);
  }
  void add(double d)
  {
    add(bitsOf(d));
  }
  void add(int i)
  {
    add(static_cast<uint64_t>(static_cast<int64_t>(i)));
  }
};

/// A number that must be an int in range: nlohmann's get<int>() of a huge float is undefined.
int integerOf(const json& value)
{
  if (value.is_number_integer())
  {
    const int64_t i = value.get<int64_t>();
    if (i >= std::numeric_limits<int>::min() && i <= std::numeric_limits<int>::max())
      return static_cast<int>(i);
  }
  throw std::runtime_error(value.dump() + " is not an integer in range");
}

/// An index into a list of `size` elements.
size_t indexOf(const json& value, size_t size, const char* what)
{
  const int i = integerOf(value);
  if (i < 0 || static_cast<size_t>(i) >= size)
    throw std::runtime_error(std::string(what) + " index " + value.dump() + " out of range");
  return static_cast<size_t>(i);
}

size_t countOf(const json& delta, const char* key)
{
  const int n = integerOf(delta.at(key));
  if (n < 0)
    throw std::runtime_error(std::string("negative count of ") + key);
  return static_cast<size_t>(n);
}

json edgeJson(size_t index, const Edge& e)
{
  json edge = { index, e.vertices[0], e.vertices[1], std::string(1, assignmentLetter(e.assignment)), e.fold_angle };
  // The same optional tail as a whole paper's edge: [..., split] when split or targeted.
  if (e.split || e.target_angle)
    edge.push_back(e.split);
  if (e.target_angle)
    edge.push_back(*e.target_angle);
  return edge;
}

/// A flat list [i, a, b, …, i, a, b, …] of `stride` numbers per element.
const json& flatList(const json& delta, const char* key, size_t stride)
{
  static const json empty = json::array();
  if (!delta.contains(key))
    return empty;
  const json& list = delta.at(key);
  if (!list.is_array() || list.size() % stride != 0)
    throw std::runtime_error(std::string(key) + " is not a list of " + std::to_string(stride) + "-number entries");
  return list;
}
}  // namespace

uint64_t paperFingerprint(const Paper& paper)
{
  Fingerprint f;
  f.add(static_cast<uint64_t>(paper.vertices.size()));
  for (const Vertex& v : paper.vertices)
  {
    f.add(v.crease_pattern.x());
    f.add(v.crease_pattern.y());
    f.add(v.folded.x());
    f.add(v.folded.y());
    f.add(v.folded.z());
  }
  f.add(static_cast<uint64_t>(paper.edges.size()));
  for (const Edge& e : paper.edges)
  {
    f.add(e.vertices[0]);
    f.add(e.vertices[1]);
    f.add(static_cast<uint64_t>(assignmentLetter(e.assignment)) | (e.split ? 0x100u : 0u) |
          (e.target_angle ? 0x200u : 0u));
    f.add(e.fold_angle);
    if (e.target_angle)
      f.add(*e.target_angle);
  }
  f.add(static_cast<uint64_t>(paper.faces.size()));
  for (const Face& face : paper.faces)
  {
    f.add(static_cast<uint64_t>(face.vertices.size()));
    for (int v : face.vertices)
      f.add(v);
  }
  f.add(static_cast<uint64_t>(paper.face_orders.size()));
  for (const FaceOrder& o : paper.face_orders)
  {
    f.add(o.face);
    f.add(o.other);
    f.add(o.above);
  }
  f.add(paper.sheet_area);
  return f.value;
}

json paperDeltaJson(const Paper& before, const Paper& after)
{
  json delta{ { "vertices", after.vertices.size() },
              { "edges", after.edges.size() },
              { "faces", after.faces.size() },
              { "face_orders", after.face_orders.size() } };
  json crease_pattern = json::array(), folded = json::array();
  for (size_t i = 0; i < after.vertices.size(); ++i)
  {
    const Vertex& v = after.vertices[i];
    const bool known = i < before.vertices.size();
    if (!known || !same(before.vertices[i].crease_pattern, v.crease_pattern))
    {
      crease_pattern.push_back(i);
      crease_pattern.push_back(v.crease_pattern.x());
      crease_pattern.push_back(v.crease_pattern.y());
    }
    if (!known || !same(before.vertices[i].folded, v.folded))
    {
      folded.push_back(i);
      folded.push_back(v.folded.x());
      folded.push_back(v.folded.y());
      folded.push_back(v.folded.z());
    }
  }
  json fold_angles = json::array(), edges = json::array();
  for (size_t i = 0; i < after.edges.size(); ++i)
  {
    const Edge& e = after.edges[i];
    if (i >= before.edges.size() || !sameButAngle(before.edges[i], e))
      edges.push_back(edgeJson(i, e));
    else if (!same(before.edges[i].fold_angle, e.fold_angle))
    {
      fold_angles.push_back(i);
      fold_angles.push_back(e.fold_angle);
    }
  }
  json faces = json::array();
  for (size_t i = 0; i < after.faces.size(); ++i)
    if (i >= before.faces.size() || before.faces[i].vertices != after.faces[i].vertices)
    {
      json face = json::array({ i });
      for (int v : after.faces[i].vertices)
        face.push_back(v);
      faces.push_back(std::move(face));
    }
  json orders = json::array();
  for (size_t i = 0; i < after.face_orders.size(); ++i)
    if (i >= before.face_orders.size() || !(before.face_orders[i] == after.face_orders[i]))
      for (const int value :
           { static_cast<int>(i), after.face_orders[i].face, after.face_orders[i].other, after.face_orders[i].above })
        orders.push_back(value);
  // Only what changed is written: most operations leave the crease pattern as it was.
  if (!crease_pattern.empty())
    delta["crease_pattern"] = std::move(crease_pattern);
  if (!folded.empty())
    delta["folded"] = std::move(folded);
  if (!fold_angles.empty())
    delta["fold_angles"] = std::move(fold_angles);
  if (!edges.empty())
    delta["edge_changes"] = std::move(edges);
  if (!faces.empty())
    delta["face_changes"] = std::move(faces);
  if (!orders.empty())
    delta["face_order_changes"] = std::move(orders);
  if (!same(before.sheet_area, after.sheet_area))
    delta["sheet_area"] = after.sheet_area;
  delta["fingerprint"] = paperFingerprint(after);
  return delta;
}

Expected<Paper> applyPaperDelta(const Paper& before, const json& delta)
{
  try
  {
    if (!delta.is_object())
      return Expected<Paper>::failure("a paper delta is not an object");
    Paper paper = before;
    const size_t nv = countOf(delta, "vertices"), ne = countOf(delta, "edges"), nf = countOf(delta, "faces"),
                 no = countOf(delta, "face_orders");
    // A changed edge or face, or a count, changes what linkTopology derives.
    bool relink = nv != paper.vertices.size() || ne != paper.edges.size() || nf != paper.faces.size();
    paper.vertices.resize(nv);
    paper.edges.resize(ne);
    paper.faces.resize(nf);
    paper.face_orders.resize(no);
    const json& cp = flatList(delta, "crease_pattern", 3);
    for (size_t k = 0; k < cp.size(); k += 3)
      paper.vertices[indexOf(cp[k], nv, "crease_pattern")].crease_pattern =
          Vec2(cp[k + 1].get<double>(), cp[k + 2].get<double>());
    const json& folded = flatList(delta, "folded", 4);
    for (size_t k = 0; k < folded.size(); k += 4)
      paper.vertices[indexOf(folded[k], nv, "folded")].folded =
          Vec3(folded[k + 1].get<double>(), folded[k + 2].get<double>(), folded[k + 3].get<double>());
    const json& angles = flatList(delta, "fold_angles", 2);
    for (size_t k = 0; k < angles.size(); k += 2)
      paper.edges[indexOf(angles[k], ne, "fold_angles")].fold_angle = angles[k + 1].get<double>();
    if (delta.contains("edge_changes"))
      for (const json& e : delta.at("edge_changes"))
      {
        Edge& edge = paper.edges[indexOf(e.at(0), ne, "edge_changes")];
        edge.vertices = { integerOf(e.at(1)), integerOf(e.at(2)) };
        const auto assignment = assignmentFromLetter(e.at(3).get<std::string>());
        if (!assignment)
          return Expected<Paper>::failure("unknown assignment " + e.at(3).dump());
        edge.assignment = *assignment;
        edge.fold_angle = e.at(4).get<double>();
        edge.split = e.size() > 5 && e.at(5).get<bool>();
        edge.target_angle = e.size() > 6 ? std::optional<double>(e.at(6).get<double>()) : std::nullopt;
        relink = true;
      }
    if (delta.contains("face_changes"))
      for (const json& f : delta.at("face_changes"))
      {
        Face& face = paper.faces[indexOf(f.at(0), nf, "face_changes")];
        face.vertices.clear();
        for (size_t k = 1; k < f.size(); ++k)
          face.vertices.push_back(integerOf(f[k]));
        relink = true;
      }
    const json& orders = flatList(delta, "face_order_changes", 4);
    for (size_t k = 0; k < orders.size(); k += 4)
      paper.face_orders[indexOf(orders[k], no, "face_order_changes")] = { integerOf(orders[k + 1]),
                                                                          integerOf(orders[k + 2]),
                                                                          integerOf(orders[k + 3]) };
    if (delta.contains("sheet_area"))
      paper.sheet_area = delta.at("sheet_area").get<double>();
    if (relink)
    {
      const Status linked = linkTopology(paper);
      if (!linked)
        return Expected<Paper>::failure(linked.message());
    }
    const json& fingerprint = delta.at("fingerprint");
    if (!fingerprint.is_number_integer() || fingerprint.get<uint64_t>() != paperFingerprint(paper))
      return Expected<Paper>::failure("a paper delta that does not give the state it was made for");
    return paper;
  }
  catch (const std::exception& e)  // json::exception and the range checks above
  {
    return Expected<Paper>::failure(std::string("malformed paper delta: ") + e.what());
  }
}

}  // namespace virtual_origami::core

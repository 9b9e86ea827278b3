#include "virtual_origami/core/paper_delta.h"

#include <algorithm>
#include <charconv>
#include <cmath>
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

/// xxHash64's rounds over four lanes (words go round-robin; the lanes multiply independently,
/// so a large paper is fingerprinted at memory speed), then its avalanche. Not for security:
/// it tells a delta applied to the wrong state, or damaged, from the state it was made for.
struct Fingerprint
{
  static constexpr uint64_t k1 = 0x9e3779b185ebca87ull, k2 = 0xc2b2ae3d27d4eb4full, k3 = 0x165667b19e3779f9ull;
  uint64_t lanes[4] = { k1 + k2, k2, 0, 0 - k1 };
  uint64_t count = 0;
  static uint64_t rotl(uint64_t x, int r)
  {
    return (x << r) | (x >> (64 - r));
  }
  void add(uint64_t word)
  {
    uint64_t& lane = lanes[count++ & 3];
    lane = rotl(lane + word * k2, 31) * k1;
  }
  void add(double d)
  {
    add(bitsOf(d));
  }
  void add(int i)
  {
    add(static_cast<uint64_t>(static_cast<int64_t>(i)));
  }
  uint64_t value() const
  {
    uint64_t h = rotl(lanes[0], 1) + rotl(lanes[1], 7) + rotl(lanes[2], 12) + rotl(lanes[3], 18);
    for (const uint64_t lane : lanes)
      h = (h ^ (rotl(lane * k2, 31) * k1)) * k1 + k3;
    h += count;
    h ^= h >> 33;
    h *= k2;
    h ^= h >> 29;
    h *= k3;
    return h ^ (h >> 32);
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

/// Appends JSON text fast: a large fold's delta holds a million numbers, and building a json
/// tree of them took several times as long as writing them (the node writes it under its lock).
class JsonText
{
public:
  explicit JsonText(std::string& out) : out_(out)
  {}
  /// The shortest text that reads back as the same double, always with a fraction or an
  /// exponent, so that a reader takes it as a float (-0.0 stays negative).
  void number(double value)
  {
    if (!std::isfinite(value))
    {
      out_ += "null";  // as nlohmann writes it: the reader refuses the line
      return;
    }
    char buffer[32];
    const auto [end, error] = std::to_chars(buffer, buffer + sizeof(buffer), value);
    out_.append(buffer, end);
    if (std::find_if(buffer, end, [](char c) { return c == '.' || c == 'e'; }) == end)
      out_ += ".0";
  }
  void number(int64_t value)
  {
    char buffer[24];
    out_.append(buffer, std::to_chars(buffer, buffer + sizeof(buffer), value).ptr);
  }
  void number(uint64_t value)
  {
    char buffer[24];
    out_.append(buffer, std::to_chars(buffer, buffer + sizeof(buffer), value).ptr);
  }
  void number(int value)
  {
    number(static_cast<int64_t>(value));
  }
  /// Opens `"key":[` (`,` before it unless first) the first time, `,` after.
  void item(bool& opened, const char* key)
  {
    if (!opened)
    {
      out_ += ",\"";
      out_ += key;
      out_ += "\":[";
      opened = true;
    }
    else
      out_ += ',';
  }
  void close(bool opened)
  {
    if (opened)
      out_ += ']';
  }
  std::string& out()
  {
    return out_;
  }

private:
  std::string& out_;
};

/// An edge's fields as a whole paper writes them: a, b, "M", angle, then the optional tail
/// [..., split] only for the edges that split a concave face, [..., split, target] for an edge
/// with a target angle (so that journals written before either field read as they were).
void writeEdgeFields(JsonText& text, const Edge& e)
{
  std::string& out = text.out();
  text.number(e.vertices[0]);
  out += ',';
  text.number(e.vertices[1]);
  out += ",\"";
  out += assignmentLetter(e.assignment);
  out += "\",";
  text.number(e.fold_angle);
  if (e.split || e.target_angle)
    out += e.split ? ",true" : ",false";
  if (e.target_angle)
  {
    out += ',';
    text.number(*e.target_angle);
  }
}

/// [index, a, b, "M", angle, …]: an edge of a delta.
void writeEdge(JsonText& text, size_t index, const Edge& e)
{
  std::string& out = text.out();
  out += '[';
  text.number(index);
  out += ',';
  writeEdgeFields(text, e);
  out += ']';
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
  return f.value();
}

std::string formatPaperText(const Paper& paper)
{
  std::string out;
  JsonText text(out);
  // Keys in the order nlohmann writes them (sorted), so that nothing but the numbers' spelling
  // differs from paperToJson(...).dump().
  out += "{\"edges\":[";
  for (size_t i = 0; i < paper.edges.size(); ++i)
  {
    out += i > 0 ? ",[" : "[";
    writeEdgeFields(text, paper.edges[i]);
    out += ']';
  }
  out += "],\"face_orders\":[";
  for (size_t i = 0; i < paper.face_orders.size(); ++i)
  {
    const FaceOrder& o = paper.face_orders[i];
    out += i > 0 ? ",[" : "[";
    text.number(o.face);
    out += ',';
    text.number(o.other);
    out += ',';
    text.number(o.above);
    out += ']';
  }
  out += "],\"faces\":[";
  for (size_t i = 0; i < paper.faces.size(); ++i)
  {
    out += i > 0 ? ",[" : "[";
    for (size_t k = 0; k < paper.faces[i].vertices.size(); ++k)
    {
      if (k > 0)
        out += ',';
      text.number(paper.faces[i].vertices[k]);
    }
    out += ']';
  }
  out += "],\"sheet_area\":";
  text.number(paper.sheet_area);
  out += ",\"vertices_crease_pattern\":[";
  for (size_t i = 0; i < paper.vertices.size(); ++i)
  {
    out += i > 0 ? ",[" : "[";
    text.number(paper.vertices[i].crease_pattern.x());
    out += ',';
    text.number(paper.vertices[i].crease_pattern.y());
    out += ']';
  }
  out += "],\"vertices_folded\":[";
  for (size_t i = 0; i < paper.vertices.size(); ++i)
  {
    const Vec3& p = paper.vertices[i].folded;
    out += i > 0 ? ",[" : "[";
    text.number(p.x());
    out += ',';
    text.number(p.y());
    out += ',';
    text.number(p.z());
    out += ']';
  }
  out += "]}";
  return out;
}

std::string formatPaperDelta(const Paper& before, const Paper& after, std::optional<uint64_t> after_fingerprint)
{
  std::string out;
  JsonText text(out);
  out += "{\"vertices\":";
  text.number(after.vertices.size());
  out += ",\"edges\":";
  text.number(after.edges.size());
  out += ",\"faces\":";
  text.number(after.faces.size());
  out += ",\"face_orders\":";
  text.number(after.face_orders.size());
  // Only what changed is written: most operations leave the crease pattern as it was.
  bool opened = false;
  for (size_t i = 0; i < after.vertices.size(); ++i)
  {
    const Vec2& p = after.vertices[i].crease_pattern;
    if (i < before.vertices.size() && same(before.vertices[i].crease_pattern, p))
      continue;
    text.item(opened, "crease_pattern");
    text.number(i);
    out += ',';
    text.number(p.x());
    out += ',';
    text.number(p.y());
  }
  text.close(opened);
  opened = false;
  for (size_t i = 0; i < after.vertices.size(); ++i)
  {
    const Vec3& p = after.vertices[i].folded;
    if (i < before.vertices.size() && same(before.vertices[i].folded, p))
      continue;
    text.item(opened, "folded");
    text.number(i);
    out += ',';
    text.number(p.x());
    out += ',';
    text.number(p.y());
    out += ',';
    text.number(p.z());
  }
  text.close(opened);
  opened = false;
  for (size_t i = 0; i < after.edges.size() && i < before.edges.size(); ++i)
    if (sameButAngle(before.edges[i], after.edges[i]) && !same(before.edges[i].fold_angle, after.edges[i].fold_angle))
    {
      text.item(opened, "fold_angles");
      text.number(i);
      out += ',';
      text.number(after.edges[i].fold_angle);
    }
  text.close(opened);
  opened = false;
  for (size_t i = 0; i < after.edges.size(); ++i)
    if (i >= before.edges.size() || !sameButAngle(before.edges[i], after.edges[i]))
    {
      text.item(opened, "edge_changes");
      writeEdge(text, i, after.edges[i]);
    }
  text.close(opened);
  opened = false;
  for (size_t i = 0; i < after.faces.size(); ++i)
    if (i >= before.faces.size() || before.faces[i].vertices != after.faces[i].vertices)
    {
      text.item(opened, "face_changes");
      out += '[';
      text.number(i);
      for (int v : after.faces[i].vertices)
      {
        out += ',';
        text.number(v);
      }
      out += ']';
    }
  text.close(opened);
  opened = false;
  for (size_t i = 0; i < after.face_orders.size(); ++i)
    if (i >= before.face_orders.size() || !(before.face_orders[i] == after.face_orders[i]))
    {
      const FaceOrder& o = after.face_orders[i];
      text.item(opened, "face_order_changes");
      text.number(i);
      for (const int value : { o.face, o.other, o.above })
      {
        out += ',';
        text.number(value);
      }
    }
  text.close(opened);
  if (!same(before.sheet_area, after.sheet_area))
  {
    out += ",\"sheet_area\":";
    text.number(after.sheet_area);
  }
  out += ",\"fingerprint\":";
  text.number(after_fingerprint ? *after_fingerprint : paperFingerprint(after));
  out += '}';
  return out;
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

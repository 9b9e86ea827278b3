// ORIPA .cp and .opx read. The parsers turn a file into segments, each remembering its line;
// paperFromSegments splits them into a planar graph and traces its faces. Malformed input is
// refused by line number, never by quoting the file.
#include "virtual_origami/core/oripa_io.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <fstream>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <string_view>
#include <utility>

#include "format_error.h"
#include "virtual_origami/core/planar_geometry.h"
#include "virtual_origami/core/planar_graph.h"
#include "virtual_origami/core/reference_patterns.h"
#include "virtual_origami/core/validity.h"

namespace virtual_origami::core
{
namespace
{
/// Larger files are refused unread, as FOLD files are.
constexpr size_t kMaxFileBytes = size_t{ 64 } << 20;
/// Points closer than this (relative to the sheet size) are one point. ORIPA itself works to
/// 1e-6 on a 400-unit sheet, so its files agree far better than this.
constexpr double kMergeTolerance = 1e-8;

[[noreturn]] void failAt(int line, const std::string& message)
{
  fail("line " + std::to_string(line) + ": " + message);
}

// ---------------------------------------------------------------------------------------------
// Values

std::string_view trim(std::string_view s)
{
  const auto space = [](char c) { return std::isspace(static_cast<unsigned char>(c)) != 0; };
  while (!s.empty() && space(s.front()))
    s.remove_prefix(1);
  while (!s.empty() && space(s.back()))
    s.remove_suffix(1);
  return s;
}

/// A finite number filling the whole token (a leading '+' allowed; locale-independent).
double readCoordinate(std::string_view token, int line, const std::string& name)
{
  if (!token.empty() && token.front() == '+')
    token.remove_prefix(1);
  double value = 0;
  const auto [end, error] = std::from_chars(token.data(), token.data() + token.size(), value);
  if (token.empty() || end != token.data() + token.size() ||
      (error != std::errc() && error != std::errc::result_out_of_range))
    failAt(line, name + " is not a number");
  if (error == std::errc::result_out_of_range || !std::isfinite(value))
    failAt(line, name + " is not finite");
  return value;
}

/// ORIPA's line type: the assignment, or nothing for an auxiliary line.
std::optional<Assignment> readType(std::string_view token, int line)
{
  if (!token.empty() && token.front() == '+')
    token.remove_prefix(1);
  int code = -1;
  const auto [end, error] = std::from_chars(token.data(), token.data() + token.size(), code);
  if (token.empty() || error != std::errc() || end != token.data() + token.size())
    failAt(line, "the line type is not an integer");
  switch (code)
  {
    case 0:  // auxiliary
    case 4:  // auxiliary in most editors; ORIPA's .cp reader also makes it auxiliary
      return std::nullopt;
    case 1:
      return Assignment::Boundary;
    case 2:
      return Assignment::Mountain;
    case 3:
      return Assignment::Valley;
    default:
      failAt(line, "unknown line type (ORIPA's are 0 auxiliary, 1 cut, 2 mountain, 3 valley, 4 auxiliary)");
  }
}

void checkSize(const std::string& text)
{
  if (text.size() > kMaxFileBytes)
    fail("the file is larger than " + std::to_string(kMaxFileBytes >> 20) + " MiB");
}

// ---------------------------------------------------------------------------------------------
// .cp

std::vector<CreaseSegment> readCp(const std::string& text)
{
  checkSize(text);
  std::vector<CreaseSegment> segments;
  size_t start = text.compare(0, 3, "\xEF\xBB\xBF") == 0 ? 3 : 0;  // a UTF-8 byte-order mark
  for (int line = 1; start <= text.size(); ++line)
  {
    size_t end = text.find('\n', start);
    if (end == std::string::npos)
      end = text.size();
    const std::string_view row(text.data() + start, end - start);
    start = end + 1;
    std::vector<std::string_view> fields;
    for (size_t i = 0; i < row.size();)
    {
      if (std::isspace(static_cast<unsigned char>(row[i])))
      {
        ++i;
        continue;
      }
      size_t j = i;
      while (j < row.size() && !std::isspace(static_cast<unsigned char>(row[j])))
        ++j;
      fields.push_back(row.substr(i, j - i));
      i = j;
    }
    if (fields.empty())
      continue;
    if (fields.size() != 5)
      failAt(line, "expected 5 numbers (type x1 y1 x2 y2), found " + std::to_string(fields.size()) + " fields");
    const std::optional<Assignment> type = readType(fields[0], line);
    static const char* const names[4] = { "x1", "y1", "x2", "y2" };
    double c[4];
    for (int k = 0; k < 4; ++k)
      c[k] = readCoordinate(fields[k + 1], line, names[k]);
    if (type)
      segments.push_back({ Vec2(c[0], c[1]), Vec2(c[2], c[3]), *type, line });
  }
  return segments;
}

// ---------------------------------------------------------------------------------------------
// .opx: a small tolerant XML walk that looks only at OriLineProxy objects.

struct XmlTag
{
  std::string name;
  std::map<std::string, std::string> attributes;
  bool closing = false;
  bool self_closing = false;
};

XmlTag parseTag(std::string_view body, int line)
{
  XmlTag tag;
  if (!body.empty() && body.front() == '/')
  {
    tag.closing = true;
    body.remove_prefix(1);
  }
  else if (!body.empty() && body.back() == '/')
  {
    tag.self_closing = true;
    body.remove_suffix(1);
  }
  size_t i = 0;
  const auto space = [](char c) { return std::isspace(static_cast<unsigned char>(c)) != 0; };
  size_t j = i;
  while (j < body.size() && !space(body[j]))
    ++j;
  tag.name = std::string(body.substr(i, j - i));
  if (tag.name.empty())
    failAt(line, "a tag without a name");
  for (i = j; i < body.size();)
  {
    if (space(body[i]))
    {
      ++i;
      continue;
    }
    j = i;
    while (j < body.size() && body[j] != '=' && !space(body[j]))
      ++j;
    const std::string key(body.substr(i, j - i));
    while (j < body.size() && space(body[j]))
      ++j;
    if (j >= body.size() || body[j] != '=')
      failAt(line, "an attribute without a value");
    ++j;
    while (j < body.size() && space(body[j]))
      ++j;
    if (j >= body.size() || (body[j] != '"' && body[j] != '\''))
      failAt(line, "an attribute value without quotes");
    const size_t close = body.find(body[j], j + 1);
    if (close == std::string_view::npos)
      failAt(line, "an attribute value without its closing quote");
    tag.attributes[key] = std::string(body.substr(j + 1, close - j - 1));
    i = close + 1;
  }
  return tag;
}

/// The OriLineProxy under construction: XMLEncoder writes only the properties that differ
/// from their defaults, so each starts at 0.
struct Proxy
{
  int line = 0;
  double value[4] = { 0, 0, 0, 0 };  // x0, y0, x1, y1
  std::string type = "0";
};

enum class Role
{
  Other,
  Proxy,
  Property,  // a <void property="…"> directly inside a proxy
  Value,     // the <int>/<double> inside such a property
};

struct Open
{
  std::string name;
  int line;
  Role role;
  int property;  // 0–3 coordinates, 4 type, −1 another property
};

std::vector<CreaseSegment> readOpx(const std::string& text)
{
  checkSize(text);
  static const char* const names[5] = { "x0", "y0", "x1", "y1", "type" };
  std::vector<CreaseSegment> segments;
  std::vector<Open> stack;
  std::optional<Proxy> proxy;
  std::string value_text;
  int line = 1;
  size_t pos = 0;
  const auto advance = [&](size_t to) {
    line += static_cast<int>(std::count(text.begin() + pos, text.begin() + to, '\n'));
    pos = to;
  };
  const auto collecting = [&] { return !stack.empty() && stack.back().role == Role::Value; };
  int proxies = 0;
  while (pos < text.size())
  {
    const size_t lt = text.find('<', pos);
    const size_t text_end = lt == std::string::npos ? text.size() : lt;
    if (collecting())
      value_text.append(text, pos, text_end - pos);
    advance(text_end);
    if (lt == std::string::npos)
      break;
    const int tag_line = line;
    const auto skipPast = [&](const char* terminator, const char* what) {
      const size_t end = text.find(terminator, lt);
      if (end == std::string::npos)
        failAt(tag_line, std::string(what) + " is never closed");
      advance(end + std::char_traits<char>::length(terminator));
    };
    if (text.compare(lt, 4, "<!--") == 0)
    {
      skipPast("-->", "a comment");
      continue;
    }
    if (text.compare(lt, 9, "<![CDATA[") == 0)
    {
      const size_t end = text.find("]]>", lt);
      if (end != std::string::npos && collecting())
        value_text.append(text, lt + 9, end - lt - 9);
      skipPast("]]>", "a CDATA section");
      continue;
    }
    if (text.compare(lt, 2, "<?") == 0)
    {
      skipPast("?>", "a processing instruction");
      continue;
    }
    if (text.compare(lt, 2, "<!") == 0)
    {
      skipPast(">", "a declaration");
      continue;
    }
    // A tag: find its '>' outside quoted attribute values.
    size_t gt = lt + 1;
    for (char quote = 0; gt < text.size(); ++gt)
    {
      const char c = text[gt];
      if (quote)
        quote = c == quote ? 0 : quote;
      else if (c == '"' || c == '\'')
        quote = c;
      else if (c == '>')
        break;
    }
    if (gt >= text.size())
      failAt(tag_line, "a tag is never closed");
    const XmlTag tag = parseTag(std::string_view(text).substr(lt + 1, gt - lt - 1), tag_line);
    advance(gt + 1);

    if (tag.closing)
    {
      if (stack.empty() || stack.back().name != tag.name)
        failAt(tag_line, stack.empty() ? "a closing tag with nothing open" :
                                         "a closing tag that does not match the element opened on line " +
                                             std::to_string(stack.back().line));
      const Open closed = stack.back();
      stack.pop_back();
      if (closed.role == Role::Value && closed.property >= 0)
      {
        const std::string_view v = trim(value_text);
        if (closed.property == 4)
        {
          proxy->type = std::string(v);
          readType(v, closed.line);  // refuse a bad type where it is written
        }
        else
          proxy->value[closed.property] = readCoordinate(v, closed.line, names[closed.property]);
      }
      else if (closed.role == Role::Proxy)
      {
        const std::optional<Assignment> type = readType(proxy->type, proxy->line);
        if (type)
          segments.push_back(
              { Vec2(proxy->value[0], proxy->value[1]), Vec2(proxy->value[2], proxy->value[3]), *type, proxy->line });
        proxy.reset();
      }
      continue;
    }

    Open open{ tag.name, tag_line, Role::Other, -1 };
    const Role parent = stack.empty() ? Role::Other : stack.back().role;
    const auto cls = tag.attributes.find("class");
    if (tag.name == "object" && cls != tag.attributes.end() && cls->second == "oripa.OriLineProxy" && !proxy)
    {
      open.role = Role::Proxy;
      proxy = Proxy{};
      proxy->line = tag_line;
      ++proxies;
    }
    else if (tag.name == "void" && parent == Role::Proxy)
    {
      open.role = Role::Property;
      const auto property = tag.attributes.find("property");
      if (property != tag.attributes.end())
        for (int k = 0; k < 5; ++k)
          if (property->second == names[k])
            open.property = k;
    }
    else if (parent == Role::Property && stack.back().property >= 0)
    {
      open.role = Role::Value;
      open.property = stack.back().property;
      value_text.clear();
    }
    if (tag.self_closing)
    {
      if (open.role == Role::Value)
        failAt(tag_line, std::string(names[open.property]) + " has no value");
      if (open.role == Role::Proxy)  // <object class="oripa.OriLineProxy"/>: type 0, auxiliary
        proxy.reset();
      continue;
    }
    stack.push_back(open);
  }
  if (!stack.empty())
    failAt(stack.back().line, "an element opened here is never closed");
  if (proxies == 0)
    fail("no ORIPA lines (oripa.OriLineProxy objects) found");
  return segments;
}

// ---------------------------------------------------------------------------------------------
// Planar graph

struct Piece
{
  Assignment assignment;
  int line;
};

using Pieces = std::map<std::pair<int, int>, Piece>;

void addPiece(Pieces& pieces, int a, int b, const Piece& piece)
{
  const auto key = std::minmax(a, b);
  auto [it, added] = pieces.emplace(std::make_pair(key.first, key.second), piece);
  if (added)
    return;
  Piece& old = it->second;
  if (old.assignment == piece.assignment)
    old.line = std::min(old.line, piece.line);
  else if (piece.assignment == Assignment::Boundary)  // a crease drawn over the outline is outline
    old = piece;
  else if (old.assignment != Assignment::Boundary)
    failAt(std::min(old.line, piece.line), "mountain and valley on the same stretch (with line " +
                                               std::to_string(std::max(old.line, piece.line)) + ")");
}

/// Splits every segment at the points of the others that lie on it and where it crosses them.
Pieces splitSegments(const std::vector<CreaseSegment>& segments, SnappedPoints& points, double tolerance)
{
  std::vector<SnappedSegment> snapped;
  for (const CreaseSegment& s : segments)
  {
    const int ia = points.snap(s.a), ib = points.snap(s.b);
    if (ia == ib)
      failAt(s.line, "zero-length segment");
    snapped.push_back({ s.a, s.b, ia, ib });
  }
  const std::vector<std::vector<int>> along = pointsAlongSegments(snapped, points, tolerance);
  Pieces pieces;
  for (size_t i = 0; i < segments.size(); ++i)
    for (size_t k = 0; k + 1 < along[i].size(); ++k)
      addPiece(pieces, along[i][k], along[i][k + 1], { segments[i].assignment, segments[i].line });
  return pieces;
}

/// Joins the two pieces at a vertex of degree 2 when they run straight on and are of one kind:
/// what is left where an auxiliary line (dropped) or a split in the file met a line.
void joinStraightRuns(Pieces& pieces, const std::vector<Vec2>& points, double tolerance)
{
  std::vector<std::set<int>> neighbours(points.size());
  for (const auto& [key, piece] : pieces)
  {
    neighbours[key.first].insert(key.second);
    neighbours[key.second].insert(key.first);
  }
  std::vector<int> work;
  for (size_t v = 0; v < points.size(); ++v)
    work.push_back(static_cast<int>(v));
  while (!work.empty())
  {
    const int v = work.back();
    work.pop_back();
    if (neighbours[v].size() != 2)
      continue;
    const int a = *neighbours[v].begin(), b = *neighbours[v].rbegin();
    const Piece pa = pieces.at(std::minmax(a, v)), pb = pieces.at(std::minmax(b, v));
    if (pa.assignment != pb.assignment || neighbours[a].count(b) ||
        (points[a] - points[v]).dot(points[b] - points[v]) >= 0 ||
        pointSegmentDistance(points[v], points[a], points[b]) > tolerance)
      continue;
    pieces.erase(std::minmax(a, v));
    pieces.erase(std::minmax(b, v));
    const auto key = std::minmax(a, b);
    pieces.emplace(std::make_pair(key.first, key.second), Piece{ pa.assignment, std::min(pa.line, pb.line) });
    neighbours[v].clear();
    neighbours[a].erase(v);
    neighbours[b].erase(v);
    neighbours[a].insert(b);
    neighbours[b].insert(a);
    work.push_back(a);
    work.push_back(b);
  }
}

/// The segments scaled into the paper's frame: the outline's box, its longer side `size` long,
/// with its corner at the origin. Refuses what cannot be part of a paper.
std::vector<CreaseSegment> scaledSegments(const std::vector<CreaseSegment>& input, double size, double tolerance)
{
  if (!(std::isfinite(size) && size > 0))
    fail("the paper size must be positive");
  constexpr double inf = std::numeric_limits<double>::infinity();
  Vec2 low(inf, inf), high(-inf, -inf);
  for (const CreaseSegment& s : input)
    if (s.assignment == Assignment::Boundary)
      for (const Vec2& p : { s.a, s.b })
      {
        low = low.cwiseMin(p);
        high = high.cwiseMax(p);
      }
  if (!std::isfinite(low.x()))
    fail("no boundary: the paper's outline needs cut (type 1) lines");
  const double extent = (high - low).maxCoeff();
  if (!(extent > 0 && std::isfinite(extent)))
    fail("the outline (type 1 lines) has no extent");
  const double scale = size / extent;
  const Vec2 box = (high - low) * scale;
  std::vector<CreaseSegment> segments;
  for (const CreaseSegment& s : input)
  {
    if (!(s.a.allFinite() && s.b.allFinite()))
      failAt(s.line, "a coordinate is not finite");
    CreaseSegment n{ (s.a - low) * scale, (s.b - low) * scale, s.assignment, s.line };
    if (s.assignment != Assignment::Boundary && s.assignment != Assignment::Mountain &&
        s.assignment != Assignment::Valley)
      failAt(s.line, "only cut (boundary), mountain and valley lines make a paper");
    if ((n.b - n.a).norm() <= tolerance)
      failAt(s.line, "zero-length segment");
    for (const Vec2& p : { n.a, n.b })
      if (p.x() < -tolerance || p.y() < -tolerance || p.x() > box.x() + tolerance || p.y() > box.y() + tolerance)
        failAt(s.line, "the segment lies outside the outline (type 1 lines)");
    segments.push_back(n);
  }
  return segments;
}

/// The graph the pieces draw: the points they use, renumbered, and one edge a piece.
struct CreaseGraph
{
  std::vector<Vec2> vertices;
  std::vector<std::array<int, 2>> edges;
  std::vector<Piece> edge_piece;
  std::vector<std::vector<int>> incident;  // the edges at each vertex
};

CreaseGraph creaseGraph(const Pieces& pieces, const std::vector<Vec2>& points)
{
  CreaseGraph graph;
  std::vector<int> number(points.size(), -1);
  for (const auto& [key, piece] : pieces)
  {
    for (int p : { key.first, key.second })
      if (number[p] < 0)
      {
        number[p] = static_cast<int>(graph.vertices.size());
        graph.vertices.push_back(points[p]);
      }
    graph.edges.push_back({ number[key.first], number[key.second] });
    graph.edge_piece.push_back(piece);
  }
  graph.incident.resize(graph.vertices.size());
  for (size_t e = 0; e < graph.edges.size(); ++e)
    for (int v : graph.edges[e])
      graph.incident[v].push_back(static_cast<int>(e));
  return graph;
}

/// No loose end, and one piece of paper: every edge reachable from the outline.
void checkConnected(const CreaseGraph& graph)
{
  const auto& [vertices, edges, edge_piece, incident] = graph;
  for (size_t v = 0; v < vertices.size(); ++v)
    if (incident[v].size() == 1)
      failAt(edge_piece[incident[v][0]].line, "the line ends without meeting another line (a loose end)");
  int start = 0;
  for (size_t e = 0; e < edges.size(); ++e)
    if (edge_piece[e].assignment == Assignment::Boundary)
    {
      start = edges[e][0];
      break;
    }
  std::vector<char> reached(vertices.size(), 0);
  std::vector<int> queue{ start };
  reached[start] = 1;
  while (!queue.empty())
  {
    const int v = queue.back();
    queue.pop_back();
    for (int e : incident[v])
    {
      const int w = edges[e][0] == v ? edges[e][1] : edges[e][0];
      if (!reached[w])
      {
        reached[w] = 1;
        queue.push_back(w);
      }
    }
  }
  int stray = -1;
  for (size_t e = 0; e < edges.size(); ++e)
    if (!reached[edges[e][0]] && (stray < 0 || edge_piece[e].line < stray))
      stray = edge_piece[e].line;
  if (stray >= 0)
    failAt(stray, "the line is not connected to the rest of the pattern");
}

/// The bounded faces, each a simple convex polygon; no cut line between two of them.
std::vector<std::vector<int>> convexFaces(const CreaseGraph& graph, double size)
{
  const auto& [vertices, edges, edge_piece, incident] = graph;
  std::vector<std::vector<int>> faces;
  std::vector<int> faces_of_edge(edges.size(), 0);
  for (TracedFace& traced : boundedFaces(vertices, edges, 1e-14 * size * size))
  {
    const std::vector<int>& face = traced.vertices;
    const std::vector<int>& cycle = traced.half_edges;
    const int line = edge_piece[cycle.front() / 2].line;
    std::vector<int> sorted = face;
    std::sort(sorted.begin(), sorted.end());
    if (std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end())
      failAt(line, "a face along this line passes one point twice (a line ending inside it, or paper meeting "
                   "paper at a point)");
    const size_t n = face.size();
    for (size_t k = 0; k < n; ++k)
    {
      const Vec2& a = vertices[face[k]];
      const Vec2& b = vertices[face[(k + 1) % n]];
      const Vec2& c = vertices[face[(k + 2) % n]];
      // The same slack as checkValidity's, so what loads is valid.
      if (cross2(b - a, c - b) < -1e-12 * size * size)
        failAt(edge_piece[cycle[(k + 1) % n] / 2].line, "a face bordered by this line is not convex");
    }
    for (int h : cycle)
      ++faces_of_edge[h / 2];
    faces.push_back(std::move(traced.vertices));
  }
  if (faces.empty())
    fail("the lines enclose no paper");
  for (size_t e = 0; e < edges.size(); ++e)
    if (faces_of_edge[e] == 2 && edge_piece[e].assignment == Assignment::Boundary)
      failAt(edge_piece[e].line, "a cut (type 1) line runs inside the paper: slits are not supported");
  return faces;
}

Paper buildPaper(const std::vector<CreaseSegment>& input, double size)
{
  const double tolerance = kMergeTolerance * size;
  const std::vector<CreaseSegment> segments = scaledSegments(input, size, tolerance);
  SnappedPoints points(tolerance);
  Pieces pieces = splitSegments(segments, points, tolerance);
  joinStraightRuns(pieces, points.points(), tolerance);
  const CreaseGraph graph = creaseGraph(pieces, points.points());
  checkConnected(graph);
  const std::vector<std::vector<int>> faces = convexFaces(graph, size);

  Expected<Paper> paper = patternPaper(graph.vertices, faces);
  if (!paper)
    fail(paper.message());
  std::map<std::pair<int, int>, Assignment> kind;
  for (size_t e = 0; e < graph.edges.size(); ++e)
    kind[std::minmax(graph.edges[e][0], graph.edges[e][1])] = graph.edge_piece[e].assignment;
  for (Edge& edge : paper->edges)
    if (edge.isCrease())
      edge.assignment = kind.at(std::minmax(edge.vertices[0], edge.vertices[1]));
  const ValidityReport report = checkValidity(*paper);
  if (!report.ok())
    fail("the crease pattern does not make a valid paper: " + report.problems.front());
  return std::move(*paper);
}

std::string lowerExtension(const std::string& path)
{
  const size_t dot = path.find_last_of('.');
  const size_t slash = path.find_last_of('/');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash))
    return "";
  std::string ext = path.substr(dot);
  for (char& c : ext)
    c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

}  // namespace

Expected<std::vector<CreaseSegment>> parseOripaCpSegments(const std::string& text)
{
  return guarded<std::vector<CreaseSegment>>([&] { return readCp(text); });
}

Expected<std::vector<CreaseSegment>> parseOripaOpxSegments(const std::string& text)
{
  return guarded<std::vector<CreaseSegment>>([&] { return readOpx(text); });
}

Expected<Paper> paperFromSegments(const std::vector<CreaseSegment>& segments, double size)
{
  return guarded<Paper>([&] { return buildPaper(segments, size); });
}

Expected<Paper> parseOripaCp(const std::string& text, double size)
{
  return guarded<Paper>([&] { return buildPaper(readCp(text), size); });
}

Expected<Paper> parseOripaOpx(const std::string& text, double size)
{
  return guarded<Paper>([&] { return buildPaper(readOpx(text), size); });
}

Expected<Paper> readCreasePatternFile(const std::string& path, double size)
{
  const std::string ext = lowerExtension(path);
  if (ext != ".cp" && ext != ".opx")
    return Expected<Paper>::failure(path + ": not an ORIPA file (expected the extension .cp or .opx)");
  std::ifstream in(path, std::ios::binary);
  if (!in)
    return Expected<Paper>::failure(path + ": cannot be read");
  in.seekg(0, std::ios::end);
  const std::streamoff length = in.tellg();
  if (length < 0)
    return Expected<Paper>::failure(path + ": cannot be read");
  if (static_cast<unsigned long long>(length) > kMaxFileBytes)
    return Expected<Paper>::failure(path + ": the file is larger than " + std::to_string(kMaxFileBytes >> 20) + " MiB");
  in.seekg(0);
  std::string text(static_cast<size_t>(length), '\0');
  if (!in.read(text.data(), length))
    return Expected<Paper>::failure(path + ": cannot be read");
  const Expected<Paper> paper = ext == ".cp" ? parseOripaCp(text, size) : parseOripaOpx(text, size);
  if (!paper)
    return Expected<Paper>::failure(path + ": " + paper.message());
  return paper;
}

}  // namespace virtual_origami::core

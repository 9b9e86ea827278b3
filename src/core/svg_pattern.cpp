// SVG crease patterns: the XML walked with the styles and transforms each element inherits, its
// geometry flattened to strokes, the strokes made a planar graph and read as a FOLD crease
// pattern without faces (so the FOLD reader traces, opens cuts and splits concave faces alike).
#include "virtual_origami/core/svg_pattern.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <string_view>
#include <utility>

#include <Eigen/Geometry>
#include <nlohmann/json.hpp>

#include "fold_format.h"
#include "format_error.h"
#include "virtual_origami/core/fold_io.h"
#include "virtual_origami/core/planar_graph.h"
#include "svg_geometry.h"
#include "xml_document.h"

namespace virtual_origami::core
{
namespace
{
/// Origami Simulator merges points this close, in the SVG's user units (its `vertTol`).
constexpr double kMergeUnits = 3.0;
/// ...unless that is more than this fraction of the drawing: small drawings keep their detail.
constexpr double kMergeFraction = 0.01;
/// Larger files are refused unread, as FOLD and ORIPA files are.
constexpr size_t kMaxFileBytes = size_t{ 64 } << 20;

std::string lower(std::string s)
{
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  return s;
}

std::string trim(std::string_view s)
{
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front())))
    s.remove_prefix(1);
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back())))
    s.remove_suffix(1);
  return std::string(s);
}

// ---------------------------------------------------------------------------------------------
// Styles

using Declarations = std::map<std::string, std::string>;

void readDeclarations(std::string_view text, Declarations& into)
{
  size_t pos = 0;
  while (pos < text.size())
  {
    size_t end = text.find(';', pos);
    if (end == std::string_view::npos)
      end = text.size();
    const std::string_view declaration = text.substr(pos, end - pos);
    const size_t colon = declaration.find(':');
    if (colon != std::string_view::npos)
    {
      std::string value = trim(declaration.substr(colon + 1));
      const size_t important = lower(value).find("!important");
      if (important != std::string::npos)
        value = trim(std::string_view(value).substr(0, important));
      into[lower(trim(declaration.substr(0, colon)))] = value;
    }
    pos = end + 1;
  }
}

/// A `<style>` sheet's rules for a tag, a class, or a tag and class (other selectors ignored).
struct StyleRule
{
  std::string tag;  // empty: any
  std::string cls;  // empty: any
  Declarations declarations;
};

void readStyleSheet(std::string text, std::vector<StyleRule>& rules)
{
  for (size_t open = text.find("/*"); open != std::string::npos; open = text.find("/*", open))
  {
    const size_t close = text.find("*/", open + 2);
    text.erase(open, close == std::string::npos ? std::string::npos : close + 2 - open);
  }
  size_t pos = 0;
  while (true)
  {
    const size_t open = text.find('{', pos);
    if (open == std::string::npos)
      break;
    const size_t close = text.find('}', open);
    if (close == std::string::npos)
      break;
    Declarations declarations;
    readDeclarations(std::string_view(text).substr(open + 1, close - open - 1), declarations);
    const std::string selectors = text.substr(pos, open - pos);
    size_t start = 0;
    while (start <= selectors.size())
    {
      size_t comma = selectors.find(',', start);
      if (comma == std::string::npos)
        comma = selectors.size();
      const std::string selector = trim(std::string_view(selectors).substr(start, comma - start));
      start = comma + 1;
      const bool simple = !selector.empty() && std::all_of(selector.begin(), selector.end(), [](char c) {
        return std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_' || c == '.';
      });
      if (!simple || std::count(selector.begin(), selector.end(), '.') > 1)
        continue;
      const size_t dot = selector.find('.');
      rules.push_back(
          { selector.substr(0, dot), dot == std::string::npos ? "" : selector.substr(dot + 1), declarations });
    }
    pos = close + 1;
  }
}

/// What an element inherits from its groups, and what it is given itself.
struct Inherited
{
  SvgTransform transform = SvgTransform::Identity();
  std::optional<std::string> stroke;
  double stroke_opacity = 1.0;
};

/// The element's own properties: presentation attributes, then sheet rules (tag, class, both),
/// then its style attribute, each over the last.
Declarations ownProperties(const XmlElement& element, const std::vector<StyleRule>& rules)
{
  Declarations properties;
  for (const char* key : { "stroke", "stroke-opacity", "opacity", "display" })
    if (const std::string* value = element.attribute(key))
      properties[key] = trim(*value);
  std::vector<std::string> classes;
  if (const std::string* cls = element.attribute("class"))
  {
    std::string word;
    for (char c : *cls + " ")
      if (std::isspace(static_cast<unsigned char>(c)))
      {
        if (!word.empty())
          classes.push_back(word);
        word.clear();
      }
      else
        word += c;
  }
  const std::string tag = element.localName();
  for (int specificity = 0; specificity < 3; ++specificity)
    for (const StyleRule& rule : rules)
    {
      const bool has_class = !rule.cls.empty() && std::find(classes.begin(), classes.end(), rule.cls) != classes.end();
      const bool matches = specificity == 0 ? rule.cls.empty() && rule.tag == tag :
                           specificity == 1 ? rule.tag.empty() && has_class :
                                              rule.tag == tag && has_class;
      if (matches)
        for (const auto& [key, value] : rule.declarations)
          properties[key] = value;
    }
  if (const std::string* style = element.attribute("style"))
    readDeclarations(*style, properties);
  return properties;
}

double opacityValue(const XmlElement& element, const std::string& key, const std::string& text)
{
  NumberReader reader(text);
  std::optional<double> x = reader.number();
  if (!x)
    failIn(element, key + " is not a number");
  if (reader.peek() == '%')
    *x /= 100;
  return std::clamp(*x, 0.0, 1.0);
}

/// Origami Simulator's six colours.
std::optional<Assignment> kindOfColour(const std::string& stroke)
{
  std::string colour;
  for (char c : lower(stroke))
    if (!std::isspace(static_cast<unsigned char>(c)))
      colour += c;
  static const std::map<std::string, Assignment> named = {
    { "black", Assignment::Boundary },     { "red", Assignment::Mountain }, { "blue", Assignment::Valley },
    { "green", Assignment::Cut },  // Origami Simulator's green is #0f0 (CSS's lime)
    { "lime", Assignment::Cut },           { "yellow", Assignment::Flat },  { "magenta", Assignment::Unassigned },
    { "fuchsia", Assignment::Unassigned },
  };
  const auto it = named.find(colour);
  if (it != named.end())
    return it->second;
  std::array<int, 3> rgb{ -1, -1, -1 };
  if (colour.size() == 4 && colour[0] == '#')  // #rgb is #rrggbb
    colour = { '#', colour[1], colour[1], colour[2], colour[2], colour[3], colour[3] };
  if (colour.size() == 7 && colour[0] == '#')
    for (int k = 0; k < 3; ++k)
    {
      const char* first = colour.data() + 1 + 2 * k;
      int value = -1;
      const auto [end, error] = std::from_chars(first, first + 2, value, 16);
      rgb[k] = error == std::errc() && end == first + 2 ? value : -1;
    }
  else if (colour.rfind("rgb(", 0) == 0 && colour.back() == ')')
  {
    NumberReader reader(std::string_view(colour).substr(4, colour.size() - 5));
    for (int k = 0; k < 3; ++k)
    {
      const std::optional<double> x = reader.number();
      if (!x)
        return std::nullopt;
      rgb[k] = static_cast<int>(std::lround(reader.peek() == '%' ? *x * 2.55 : *x));
      if (reader.peek() == '%')
        reader.skip();
    }
    if (!reader.atEnd())
      return std::nullopt;
  }
  static const std::pair<std::array<int, 3>, Assignment> colours[] = {
    { { 0, 0, 0 }, Assignment::Boundary }, { { 255, 0, 0 }, Assignment::Mountain },
    { { 0, 0, 255 }, Assignment::Valley }, { { 0, 255, 0 }, Assignment::Cut },
    { { 255, 255, 0 }, Assignment::Flat }, { { 255, 0, 255 }, Assignment::Unassigned },
  };
  for (const auto& [value, kind] : colours)
    if (rgb == value)
      return kind;
  return std::nullopt;
}

// ---------------------------------------------------------------------------------------------
// The walk

bool drawsNothing(const std::string& tag)
{
  static const char* const hidden[] = { "defs",     "symbol", "clipPath", "mask",   "marker", "pattern", "style",
                                        "metadata", "title",  "desc",     "script", "text",   "use",     "image" };
  return std::find_if(std::begin(hidden), std::end(hidden), [&](const char* h) { return tag == h; }) !=
         std::end(hidden);
}

void collectStyleSheets(const XmlElement& element, std::vector<StyleRule>& rules)
{
  if (element.localName() == "style")
    readStyleSheet(element.text, rules);
  for (const XmlElement& child : element.children)
    collectStyleSheets(child, rules);
}

void walk(const XmlElement& element, const Inherited& parent, const std::vector<StyleRule>& rules,
          std::vector<SvgStroke>& strokes)
{
  const std::string tag = element.localName();
  if (drawsNothing(tag))
    return;
  const Declarations properties = ownProperties(element, rules);
  const auto property = [&](const char* key) -> const std::string* {
    const auto it = properties.find(key);
    return it == properties.end() || lower(it->second) == "inherit" ? nullptr : &it->second;
  };
  if (const std::string* display = property("display"); display && lower(*display) == "none")
    return;
  Inherited here = parent;
  if (const std::string* transform = element.attribute("transform"))
    here.transform = parent.transform * parseTransform(element, *transform);
  if (const std::string* stroke = property("stroke"))
    here.stroke = *stroke;
  if (const std::string* stroke_opacity = property("stroke-opacity"))
    here.stroke_opacity = opacityValue(element, "stroke-opacity", *stroke_opacity);
  const std::vector<Polyline> lines = elementPolylines(element);
  const bool drawn = here.stroke && lower(trim(*here.stroke)) != "none" &&
                     std::any_of(lines.begin(), lines.end(), [](const Polyline& l) { return l.size() > 1; });
  if (drawn)
  {
    const std::optional<Assignment> kind = kindOfColour(*here.stroke);
    if (!kind)
      failIn(element, "its stroke colour is not one of the pattern's: black border, red mountain, blue valley, "
                      "green (#0f0) cut, yellow facet, magenta undriven hinge");
    const std::string* opacity_text = property("opacity");
    const double opacity = (opacity_text ? opacityValue(element, "opacity", *opacity_text) : 1.0) * here.stroke_opacity;
    std::optional<double> target;
    if (*kind == Assignment::Mountain)
      target = -opacity * M_PI;
    else if (*kind == Assignment::Valley)
      target = opacity * M_PI;
    for (const Polyline& line : lines)
      for (size_t i = 0; i + 1 < line.size(); ++i)
      {
        const Vec2 a = here.transform * line[i], b = here.transform * line[i + 1];
        if (!a.allFinite() || !b.allFinite())
          failIn(element, "a point is not finite after its transforms");
        if (a != b)
          strokes.push_back({ a, b, *kind, target, describeElement(element) });
      }
  }
  for (const XmlElement& child : element.children)
    walk(child, here, rules, strokes);
}

std::vector<SvgStroke> readStrokes(const std::string& text)
{
  if (text.size() > kMaxFileBytes)
    fail("the file is larger than " + std::to_string(kMaxFileBytes >> 20) + " MiB");
  const Expected<XmlElement> root = parseXml(text);
  if (!root)
    fail(root.message());
  if (root->localName() != "svg")
    fail("not an SVG drawing: its root element is <" + root->localName() + ">, not <svg>");
  std::vector<StyleRule> rules;
  collectStyleSheets(*root, rules);
  std::vector<SvgStroke> strokes;
  walk(*root, Inherited{}, rules, strokes);
  return strokes;
}

// ---------------------------------------------------------------------------------------------
// The paper

/// Which kind a stretch keeps when strokes of several kinds land on it (drawn over each other, or
/// brought together by the merge tolerance): Origami Simulator's, border first, then mountain,
/// valley, cut, facet, hinge.
int strength(Assignment kind)
{
  switch (kind)
  {
    case Assignment::Boundary:
      return 6;
    case Assignment::Mountain:
      return 5;
    case Assignment::Valley:
      return 4;
    case Assignment::Cut:
      return 3;
    case Assignment::Flat:
      return 2;
    case Assignment::Unassigned:
      return 1;
  }
  return 0;
}

/// Replaces "name[N]" in a FOLD reader's message by what `rename(N)` says.
std::string renameIndexed(std::string message, const std::string& name, const std::function<std::string(int)>& rename)
{
  const std::string open = name + "[";
  for (size_t at = message.find(open); at != std::string::npos; at = message.find(open, at))
  {
    const size_t close = message.find(']', at);
    int index = -1;
    const char* first = message.data() + at + open.size();
    const auto [end, error] = std::from_chars(first, message.data() + (close == std::string::npos ? 0 : close), index);
    if (close == std::string::npos || error != std::errc() || end != message.data() + close)
    {
      at += open.size();
      continue;
    }
    const std::string named = rename(index);
    message.replace(at, close + 1 - at, named);
    at += named.size();
  }
  return message;
}

Paper buildPaper(const std::vector<SvgStroke>& strokes, double size)
{
  if (!(std::isfinite(size) && size > 0))
    fail("the paper size must be positive");
  if (strokes.empty())
    fail("no strokes in the pattern's colours (black border, red mountain, blue valley, green cut, yellow facet, "
         "magenta hinge)");
  constexpr double inf = std::numeric_limits<double>::infinity();
  const bool bordered = std::any_of(strokes.begin(), strokes.end(),
                                    [](const SvgStroke& s) { return s.assignment == Assignment::Boundary; });
  Vec2 low(inf, inf), high(-inf, -inf);
  for (const SvgStroke& s : strokes)
    if (!bordered || s.assignment == Assignment::Boundary)
      for (const Vec2& p : { s.a, s.b })
      {
        low = low.cwiseMin(p);
        high = high.cwiseMax(p);
      }
  const double extent = (high - low).maxCoeff();
  if (!(extent > 0 && std::isfinite(extent)))
    fail("the drawing has no extent");
  const double scale = size / extent;
  const double tolerance = std::min(kMergeUnits, kMergeFraction * extent) * scale;
  // y turned up: the pattern seen from the paper's front looks as drawn.
  const auto place = [&](const Vec2& p) { return Vec2((p.x() - low.x()) * scale, (high.y() - p.y()) * scale); };

  SnappedPoints points(tolerance);
  std::vector<SnappedSegment> snapped;
  std::vector<int> stroke_of;
  for (size_t i = 0; i < strokes.size(); ++i)
  {
    const Vec2 a = place(strokes[i].a), b = place(strokes[i].b);
    const int ia = points.snap(a), ib = points.snap(b);
    if (ia == ib)
      continue;  // shorter than the merge tolerance
    snapped.push_back({ a, b, ia, ib });
    stroke_of.push_back(static_cast<int>(i));
  }
  const std::vector<std::vector<int>> along = pointsAlongSegments(snapped, points, tolerance);
  std::map<std::pair<int, int>, int> piece_stroke;  // each stretch between two points: its stroke
  for (size_t s = 0; s < snapped.size(); ++s)
    for (size_t k = 0; k + 1 < along[s].size(); ++k)
    {
      const auto key = std::minmax(along[s][k], along[s][k + 1]);
      const int stroke = stroke_of[s];
      const auto [it, added] = piece_stroke.emplace(std::make_pair(key.first, key.second), stroke);
      if (added)
        continue;
      if (strength(strokes[stroke].assignment) > strength(strokes[it->second].assignment))
        it->second = stroke;
    }

  nlohmann::json fold;
  fold["file_spec"] = 1.1;
  fold["frame_classes"] = { "creasePattern" };
  std::vector<int> number(points.points().size(), -1);
  nlohmann::json coords = nlohmann::json::array(), edges = nlohmann::json::array(),
                 assignments = nlohmann::json::array(), targets = nlohmann::json::array();
  std::vector<int> edge_stroke;
  for (const auto& [key, stroke] : piece_stroke)
  {
    for (int p : { key.first, key.second })
      if (number[p] < 0)
      {
        number[p] = static_cast<int>(coords.size());
        coords.push_back({ points.points()[p].x(), points.points()[p].y() });
      }
    edges.push_back({ number[key.first], number[key.second] });
    assignments.push_back(std::string(1, assignmentLetter(strokes[stroke].assignment)));
    const std::optional<double> target = strokes[stroke].target_angle;
    targets.push_back(target ? nlohmann::json(toDegrees(*target)) : nlohmann::json());
    edge_stroke.push_back(stroke);
  }
  fold["vertices_coords"] = coords;
  fold["edges_vertices"] = edges;
  fold["edges_assignment"] = assignments;
  fold[kTargetAngleKey] = targets;
  const Expected<FoldDocument> document = parseFold(fold.dump());
  if (!document)
  {
    // Said of the FOLD it became: name the SVG's elements and points instead.
    std::string message = renameIndexed(document.message(), "edges_vertices", [&](int e) {
      return e >= 0 && static_cast<size_t>(e) < edge_stroke.size() ?
                 "the line of the " + strokes[edge_stroke[e]].element :
                 "a line";
    });
    message = renameIndexed(message, "vertices_coords", [&](int v) {
      if (v < 0 || static_cast<size_t>(v) >= coords.size())
        return std::string("a point");
      const Vec2 p(coords[v][0].get<double>() / scale + low.x(), high.y() - coords[v][1].get<double>() / scale);
      return "the point (" + std::to_string(p.x()) + ", " + std::to_string(p.y()) + ")";
    });
    fail("the pattern drawn: " + message);
  }
  return document->frames.back();
}

}  // namespace

Expected<std::vector<SvgStroke>> parseSvgStrokes(const std::string& text)
{
  return guarded<std::vector<SvgStroke>>([&] { return readStrokes(text); });
}

Expected<Paper> parseSvgPattern(const std::string& text, double size)
{
  return guarded<Paper>([&] { return buildPaper(readStrokes(text), size); });
}

}  // namespace virtual_origami::core

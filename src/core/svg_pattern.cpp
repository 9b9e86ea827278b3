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
#include "xml_document.h"

namespace virtual_origami::core
{
namespace
{
using Transform = Eigen::Affine2d;

/// Origami Simulator merges points this close, in the SVG's user units (its `vertTol`).
constexpr double kMergeUnits = 3.0;
/// ...unless that is more than this fraction of the drawing: small drawings keep their detail.
constexpr double kMergeFraction = 0.01;
/// A curve becomes this many straight strokes; an arc one stroke per this much of its turn.
constexpr int kCurveSegments = 16;
constexpr double kArcStep = M_PI / 16;
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

std::string describe(const XmlElement& element)
{
  return "<" + element.localName() + "> on line " + std::to_string(element.line);
}

[[noreturn]] void failIn(const XmlElement& element, const std::string& message)
{
  fail(describe(element) + ": " + message);
}

// ---------------------------------------------------------------------------------------------
// Numbers

/// Reads numbers as SVG writes them: separated by spaces or commas, or by nothing where the next
/// starts with a sign or a second point ("1.5.5-2" is 1.5, .5, -2).
class NumberReader
{
public:
  explicit NumberReader(std::string_view text) : text_(text)
  {}

  void skipSeparators()
  {
    while (pos_ < text_.size() && (std::isspace(static_cast<unsigned char>(text_[pos_])) || text_[pos_] == ','))
      ++pos_;
  }
  bool atEnd()
  {
    skipSeparators();
    return pos_ >= text_.size();
  }
  char peek()
  {
    skipSeparators();
    return pos_ < text_.size() ? text_[pos_] : '\0';
  }
  void skip()
  {
    ++pos_;
  }
  bool atNumber()
  {
    const char c = peek();
    return std::isdigit(static_cast<unsigned char>(c)) || c == '-' || c == '+' || c == '.';
  }
  std::optional<double> number()
  {
    skipSeparators();
    size_t end = pos_;
    if (end < text_.size() && (text_[end] == '+' || text_[end] == '-'))
      ++end;
    bool digits = false, point = false;
    for (; end < text_.size(); ++end)
    {
      const char c = text_[end];
      if (std::isdigit(static_cast<unsigned char>(c)))
        digits = true;
      else if (c == '.' && !point)
        point = true;
      else
        break;
    }
    if (!digits)
      return std::nullopt;
    if (end < text_.size() && (text_[end] == 'e' || text_[end] == 'E'))
    {
      size_t exponent = end + 1;
      if (exponent < text_.size() && (text_[exponent] == '+' || text_[exponent] == '-'))
        ++exponent;
      if (exponent < text_.size() && std::isdigit(static_cast<unsigned char>(text_[exponent])))
      {
        end = exponent;
        while (end < text_.size() && std::isdigit(static_cast<unsigned char>(text_[end])))
          ++end;
      }
    }
    std::string_view token = text_.substr(pos_, end - pos_);
    if (token.front() == '+')
      token.remove_prefix(1);
    double value = 0;
    const auto [stop, error] = std::from_chars(token.data(), token.data() + token.size(), value);
    if (error != std::errc() || stop != token.data() + token.size() || !std::isfinite(value))
      return std::nullopt;
    pos_ = end;
    return value;
  }
  /// An arc's flag: one character, 0 or 1, which may run into what follows ("a1 1 0 01 5 5").
  std::optional<bool> flag()
  {
    const char c = peek();
    if (c != '0' && c != '1')
      return std::nullopt;
    ++pos_;
    return c == '1';
  }

private:
  std::string_view text_;
  size_t pos_ = 0;
};

/// A length attribute: its number (a unit after it is ignored: the pattern is scaled anyway).
double lengthAttribute(const XmlElement& element, const std::string& key, double fallback)
{
  const std::string* value = element.attribute(key);
  if (!value)
    return fallback;
  NumberReader reader(*value);
  const std::optional<double> x = reader.number();
  if (!x)
    failIn(element, key + " is not a number");
  return *x;
}

// ---------------------------------------------------------------------------------------------
// Transforms

Transform parseTransform(const XmlElement& element, const std::string& text)
{
  Transform result = Transform::Identity();
  size_t pos = 0;
  while (pos < text.size())
  {
    while (pos < text.size() && (std::isspace(static_cast<unsigned char>(text[pos])) || text[pos] == ','))
      ++pos;
    if (pos >= text.size())
      break;
    const size_t open = text.find('(', pos), close = text.find(')', pos);
    if (open == std::string::npos || close == std::string::npos || close < open)
      failIn(element, "transform is not a list of name(numbers)");
    const std::string name = trim(std::string_view(text).substr(pos, open - pos));
    std::vector<double> values;
    NumberReader reader(std::string_view(text).substr(open + 1, close - open - 1));
    while (!reader.atEnd())
    {
      const std::optional<double> x = reader.number();
      if (!x)
        failIn(element, "transform " + name + "() holds something that is not a number");
      values.push_back(*x);
    }
    const auto need = [&](std::initializer_list<size_t> counts) {
      if (std::find(counts.begin(), counts.end(), values.size()) == counts.end())
        failIn(element, "transform " + name + "() has " + std::to_string(values.size()) + " numbers");
    };
    Transform step = Transform::Identity();
    if (name == "matrix")
    {
      need({ 6 });
      step.matrix() << values[0], values[2], values[4], values[1], values[3], values[5], 0, 0, 1;
    }
    else if (name == "translate")
    {
      need({ 1, 2 });
      step.translate(Vec2(values[0], values.size() > 1 ? values[1] : 0.0));
    }
    else if (name == "scale")
    {
      need({ 1, 2 });
      step.scale(Vec2(values[0], values.size() > 1 ? values[1] : values[0]));
    }
    else if (name == "rotate")
    {
      need({ 1, 3 });
      const Vec2 centre = values.size() == 3 ? Vec2(values[1], values[2]) : Vec2::Zero();
      step.translate(centre).rotate(values[0] * M_PI / 180).translate(-centre);
    }
    else if (name == "skewX" || name == "skewY")
    {
      need({ 1 });
      step.matrix()(name == "skewX" ? 0 : 1, name == "skewX" ? 1 : 0) = std::tan(values[0] * M_PI / 180);
    }
    else
      failIn(element, "transform " + name + "() is not one SVG defines");
    result = result * step;
    pos = close + 1;
  }
  return result;
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
  Transform transform = Transform::Identity();
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
// Geometry: each element as polylines in its own coordinates

using Polyline = std::vector<Vec2>;

std::vector<Polyline> pointsPolyline(const XmlElement& element, bool closed)
{
  const std::string* points = element.attribute("points");
  Polyline line;
  const std::string empty;
  NumberReader reader(points ? *points : empty);  // a view: never of a temporary
  while (!reader.atEnd())
  {
    const std::optional<double> x = reader.number();
    const std::optional<double> y = x ? reader.number() : std::nullopt;
    if (!y)
      failIn(element, "points is not a list of x, y pairs");
    line.emplace_back(*x, *y);
  }
  if (closed && line.size() > 2)
    line.push_back(line.front());
  return { line };
}

Polyline ellipsePolyline(const Vec2& centre, double rx, double ry)
{
  Polyline line;
  for (int i = 0; i <= 4 * kCurveSegments; ++i)
  {
    const double angle = 2 * M_PI * (i % (4 * kCurveSegments)) / (4 * kCurveSegments);
    line.push_back(centre + Vec2(rx * std::cos(angle), ry * std::sin(angle)));
  }
  return line;
}

/// SVG's endpoint arc (implementation notes F.6.5): the points after `from`, to `to` included.
std::vector<Vec2> arcPoints(const Vec2& from, double rx, double ry, double rotation_degrees, bool large, bool sweep,
                            const Vec2& to)
{
  rx = std::abs(rx);
  ry = std::abs(ry);
  if (rx == 0 || ry == 0 || from == to)
    return { to };
  const double phi = rotation_degrees * M_PI / 180;
  const Eigen::Rotation2Dd rotate(phi);
  const Vec2 p = rotate.inverse() * (0.5 * (from - to));
  const double lambda = p.x() * p.x() / (rx * rx) + p.y() * p.y() / (ry * ry);
  if (lambda > 1)
  {
    rx *= std::sqrt(lambda);
    ry *= std::sqrt(lambda);
  }
  const double numerator = rx * rx * ry * ry - rx * rx * p.y() * p.y() - ry * ry * p.x() * p.x();
  const double denominator = rx * rx * p.y() * p.y() + ry * ry * p.x() * p.x();
  double factor = std::sqrt(std::max(0.0, numerator / denominator));
  if (large == sweep)
    factor = -factor;
  const Vec2 centre_rotated(factor * rx * p.y() / ry, -factor * ry * p.x() / rx);
  const Vec2 centre = rotate * centre_rotated + 0.5 * (from + to);
  const auto angle = [](const Vec2& u, const Vec2& v) { return std::atan2(u.x() * v.y() - u.y() * v.x(), u.dot(v)); };
  const Vec2 u((p.x() - centre_rotated.x()) / rx, (p.y() - centre_rotated.y()) / ry);
  const Vec2 v((-p.x() - centre_rotated.x()) / rx, (-p.y() - centre_rotated.y()) / ry);
  const double start = angle(Vec2(1, 0), u);
  double delta = angle(u, v);
  if (!sweep && delta > 0)
    delta -= 2 * M_PI;
  else if (sweep && delta < 0)
    delta += 2 * M_PI;
  const int steps = std::max(1, static_cast<int>(std::ceil(std::abs(delta) / kArcStep)));
  std::vector<Vec2> points;
  for (int i = 1; i < steps; ++i)
  {
    const double t = start + delta * i / steps;
    points.push_back(rotate * Vec2(rx * std::cos(t), ry * std::sin(t)) + centre);
  }
  points.push_back(to);
  return points;
}

std::vector<Polyline> pathPolylines(const XmlElement& element)
{
  const std::string* d = element.attribute("d");
  std::vector<Polyline> lines;
  if (!d)
    return lines;
  NumberReader reader(*d);
  Vec2 current = Vec2::Zero(), start = Vec2::Zero(), last_control = Vec2::Zero();
  char command = 0, previous = 0;
  const auto number = [&]() {
    const std::optional<double> x = reader.number();
    if (!x)
      failIn(element, std::string("path data: the ") + command + " command is missing a number");
    return *x;
  };
  const auto point = [&](bool relative) {
    const double x = number();
    const double y = number();
    return relative ? current + Vec2(x, y) : Vec2(x, y);
  };
  const auto lineTo = [&](const Vec2& p) {
    lines.back().push_back(p);
    current = p;
  };
  while (!reader.atEnd())
  {
    if (std::isalpha(static_cast<unsigned char>(reader.peek())))
    {
      command = reader.peek();
      reader.skip();
    }
    else if (command == 0)
      failIn(element, "path data does not start with a command");
    else if (command == 'M' || command == 'm')
      command = command == 'M' ? 'L' : 'l';  // pairs after a move are lines
    else if (command == 'Z' || command == 'z')
      failIn(element, "path data has numbers after a close (Z)");
    const bool relative = std::islower(static_cast<unsigned char>(command)) != 0;
    const char upper = static_cast<char>(std::toupper(static_cast<unsigned char>(command)));
    if (upper != 'Z' && lines.empty() && upper != 'M')
      failIn(element, "path data does not start with a move (M)");
    switch (upper)
    {
      case 'M':
        // A first relative move is absolute (SVG paths: the current point starts at the origin).
        current = point(relative);
        start = current;
        lines.push_back({ current });
        break;
      case 'L':
        lineTo(point(relative));
        break;
      case 'H':
        lineTo(Vec2(number() + (relative ? current.x() : 0.0), current.y()));
        break;
      case 'V':
        lineTo(Vec2(current.x(), number() + (relative ? current.y() : 0.0)));
        break;
      case 'Z':
        if (current != start)
          lineTo(start);
        lines.push_back({ start });  // what follows starts where the subpath did
        break;
      case 'C':
      case 'S': {
        const Vec2 p0 = current;
        const bool smooth_after = previous == 'C' || previous == 'S';
        const Vec2 p1 = upper == 'C' ? point(relative) : smooth_after ? 2 * p0 - last_control : p0;
        const Vec2 p2 = point(relative);
        const Vec2 p3 = point(relative);
        for (int i = 1; i <= kCurveSegments; ++i)
        {
          const double t = static_cast<double>(i) / kCurveSegments, s = 1 - t;
          lines.back().push_back(s * s * s * p0 + 3 * s * s * t * p1 + 3 * s * t * t * p2 + t * t * t * p3);
        }
        current = p3;
        last_control = p2;
        break;
      }
      case 'Q':
      case 'T': {
        const Vec2 p0 = current;
        const bool smooth_after = previous == 'Q' || previous == 'T';
        const Vec2 p1 = upper == 'Q' ? point(relative) : smooth_after ? 2 * p0 - last_control : p0;
        const Vec2 p2 = point(relative);
        for (int i = 1; i <= kCurveSegments; ++i)
        {
          const double t = static_cast<double>(i) / kCurveSegments, s = 1 - t;
          lines.back().push_back(s * s * p0 + 2 * s * t * p1 + t * t * p2);
        }
        current = p2;
        last_control = p1;
        break;
      }
      case 'A': {
        const double rx = number(), ry = number(), rotation = number();
        const std::optional<bool> large = reader.flag();
        const std::optional<bool> sweep = large ? reader.flag() : std::nullopt;
        if (!sweep)
          failIn(element, "path data: an arc's flags are not 0 or 1");
        const Vec2 to = point(relative);
        for (const Vec2& p : arcPoints(current, rx, ry, rotation, *large, *sweep, to))
          lines.back().push_back(p);
        current = to;
        break;
      }
      default:
        failIn(element, std::string("path data has an unknown command ") + command);
    }
    previous = upper;
  }
  return lines;
}

std::vector<Polyline> elementPolylines(const XmlElement& element)
{
  const std::string tag = element.localName();
  if (tag == "line")
    return { { Vec2(lengthAttribute(element, "x1", 0), lengthAttribute(element, "y1", 0)),
               Vec2(lengthAttribute(element, "x2", 0), lengthAttribute(element, "y2", 0)) } };
  if (tag == "polyline" || tag == "polygon")
    return pointsPolyline(element, tag == "polygon");
  if (tag == "rect")
  {
    const double x = lengthAttribute(element, "x", 0), y = lengthAttribute(element, "y", 0);
    const double w = lengthAttribute(element, "width", 0), h = lengthAttribute(element, "height", 0);
    if (!(w > 0 && h > 0))
      return {};
    return { { Vec2(x, y), Vec2(x + w, y), Vec2(x + w, y + h), Vec2(x, y + h), Vec2(x, y) } };
  }
  if (tag == "circle" || tag == "ellipse")
  {
    const Vec2 centre(lengthAttribute(element, "cx", 0), lengthAttribute(element, "cy", 0));
    const double rx = lengthAttribute(element, tag == "circle" ? "r" : "rx", 0);
    const double ry = tag == "circle" ? rx : lengthAttribute(element, "ry", 0);
    if (!(rx > 0 && ry > 0))
      return {};
    return { ellipsePolyline(centre, rx, ry) };
  }
  if (tag == "path")
    return pathPolylines(element);
  return {};
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
          strokes.push_back({ a, b, *kind, target, describe(element) });
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

#include "svg_geometry.h"

#include <algorithm>
#include <initializer_list>

#include "format_error.h"

namespace virtual_origami::core
{
std::string describeElement(const XmlElement& element)
{
  return "<" + element.localName() + "> on line " + std::to_string(element.line);
}

void failIn(const XmlElement& element, const std::string& message)
{
  fail(describeElement(element) + ": " + message);
}

namespace
{
/// A curve becomes this many straight strokes; an arc one stroke per this much of its turn.
constexpr int kCurveSegments = 16;
constexpr double kArcStep = M_PI / 16;

std::string trimmed(std::string_view s)
{
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front())))
    s.remove_prefix(1);
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back())))
    s.remove_suffix(1);
  return std::string(s);
}

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

}  // namespace

SvgTransform parseTransform(const XmlElement& element, const std::string& text)
{
  SvgTransform result = SvgTransform::Identity();
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
    const std::string name = trimmed(std::string_view(text).substr(pos, open - pos));
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
    SvgTransform step = SvgTransform::Identity();
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

}  // namespace virtual_origami::core

#include "virtual_origami/core/svg.h"

#include <algorithm>
#include <numeric>
#include <sstream>

namespace virtual_origami::core
{
namespace
{
struct Box
{
  double min_x = 1e300, min_y = 1e300, max_x = -1e300, max_y = -1e300;
  void add(double x, double y)
  {
    min_x = std::min(min_x, x);
    min_y = std::min(min_y, y);
    max_x = std::max(max_x, x);
    max_y = std::max(max_y, y);
  }
  double size() const
  {
    return std::max({ max_x - min_x, max_y - min_y, 1e-12 });
  }
};

const char* strokeOf(Assignment a)
{
  switch (a)
  {
    case Assignment::Mountain:
      return R"(stroke="#d62728" stroke-dasharray="6 2 1 2")";
    case Assignment::Valley:
      return R"(stroke="#1f77b4" stroke-dasharray="5 3")";
    case Assignment::Boundary:
      return R"(stroke="black")";
    default:
      return R"(stroke="#888888")";
  }
}

/// Text as SVG character data: a step's note may hold any character.
std::string xmlEscaped(const std::string& text)
{
  std::string out;
  for (char c : text)
    switch (c)
    {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      default:
        out += c;
    }
  return out;
}
}  // namespace

std::string paperSvg(const Paper& paper, const std::string& title)
{
  const double panel = 400, margin = 20;
  // The folded form seen obliquely from above the front, so that raised flaps show.
  const Eigen::Matrix3d view =
      (Eigen::AngleAxisd(-0.85, Vec3::UnitX()) * Eigen::AngleAxisd(-0.45, Vec3::UnitZ())).toRotationMatrix();
  const auto seen = [&](const Vec3& p) { return Vec3(view * p); };
  Box cp, folded;
  for (const Vertex& v : paper.vertices)
  {
    cp.add(v.crease_pattern.x(), v.crease_pattern.y());
    folded.add(seen(v.folded).x(), seen(v.folded).y());
  }
  // SVG's y runs down; the paper's y runs up.
  const auto cpX = [&](const Vec2& p) { return margin + (p.x() - cp.min_x) / cp.size() * panel; };
  const auto cpY = [&](const Vec2& p) { return margin + (cp.max_y - p.y()) / cp.size() * panel; };
  const auto fX = [&](const Vec3& p) {
    return 2 * margin + panel + margin + (seen(p).x() - folded.min_x) / folded.size() * panel;
  };
  const auto fY = [&](const Vec3& p) { return margin + (folded.max_y - seen(p).y()) / folded.size() * panel; };

  std::ostringstream svg;
  // The title gets a line of its own under both panels: a step's note is longer than one panel.
  const double height = panel + (title.empty() ? 3 : 4) * margin;
  svg << R"(<svg xmlns="http://www.w3.org/2000/svg" width=")" << 2 * panel + 4 * margin << R"(" height=")" << height
      << R"(" font-family="sans-serif" font-size="12">)" << '\n';
  svg << R"(<rect width="100%" height="100%" fill="white"/>)" << '\n';
  svg << "<text x=\"" << margin << "\" y=\"" << panel + 2.6 * margin << "\">crease pattern</text>\n";
  svg << "<text x=\"" << 3 * margin + panel << "\" y=\"" << panel + 2.6 * margin
      << "\">folded, seen from above the front</text>\n";
  if (!title.empty())
    svg << "<text x=\"" << margin << "\" y=\"" << panel + 3.6 * margin << "\">" << xmlEscaped(title) << "</text>\n";
  for (const Edge& e : paper.edges)
  {
    const Vec2& a = paper.vertices[e.vertices[0]].crease_pattern;
    const Vec2& b = paper.vertices[e.vertices[1]].crease_pattern;
    svg << "<line x1=\"" << cpX(a) << "\" y1=\"" << cpY(a) << "\" x2=\"" << cpX(b) << "\" y2=\"" << cpY(b) << "\" "
        << strokeOf(e.assignment) << " stroke-width=\"1.5\"/>\n";
  }
  // Folded faces far to near (painter's order), front side light, back side darker.
  std::vector<int> order(paper.faces.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(),
                   [&](int a, int b) { return seen(paper.faceCentroid(a)).z() < seen(paper.faceCentroid(b)).z(); });
  for (int f : order)
  {
    svg << "<polygon points=\"";
    for (int v : paper.faces[f].vertices)
      svg << fX(paper.vertices[v].folded) << ',' << fY(paper.vertices[v].folded) << ' ';
    const bool front = seen(paper.faceNormal(f)).z() >= 0;  // the side facing the viewer
    svg << "\" fill=\"" << (front ? "#f4e3c1" : "#c9a66b") << "\" fill-opacity=\"0.85\" stroke=\"#5a4630\" "
        << "stroke-width=\"1\"/>\n";
  }
  svg << "</svg>\n";
  return svg.str();
}

}  // namespace virtual_origami::core

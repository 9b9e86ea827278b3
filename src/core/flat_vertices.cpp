#include "virtual_origami/core/flat_vertices.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "virtual_origami/core/planar_geometry.h"

namespace virtual_origami::core
{
namespace
{
/// A crease about a vertex, in counter-clockwise order of its direction in the crease pattern.
struct Spoke
{
  int edge = -1;
  double direction = 0.0;  // radians, in the crease pattern
  int sign = 0;            // +1 valley, −1 mountain folded flat; 0 unfolded
};

/// The sector angles between consecutive folded spokes (sector i from spoke i to spoke i + 1).
std::vector<double> sectorsOf(const std::vector<Spoke>& folded)
{
  std::vector<double> sectors(folded.size());
  for (size_t i = 0; i < folded.size(); ++i)
  {
    double a = folded[(i + 1) % folded.size()].direction - folded[i].direction;
    if (a <= 0)
      a += 2 * M_PI;
    sectors[i] = a;
  }
  return sectors;
}

enum class Rule
{
  Holds,
  Maekawa,
  Kawasaki,
  BigLittleBig,
};

struct Verdict
{
  Rule rule = Rule::Holds;
  std::string detail;
  std::vector<int> suspects;  // spokes (indices into the folded ones) a change of which may help
};

std::string degrees(double radians)
{
  std::ostringstream out;
  out.precision(4);
  out << radians * 180.0 / M_PI << "°";
  return out.str();
}

/// Maekawa, Kawasaki, then crimps (big-little-big) until two creases are left: an assignment
/// folds flat at a single vertex exactly when this succeeds.
Verdict judge(const std::vector<Spoke>& folded)
{
  Verdict verdict;
  int valleys = 0, mountains = 0;
  for (const Spoke& s : folded)
    (s.sign > 0 ? valleys : mountains)++;
  if (std::abs(valleys - mountains) != 2)
  {
    verdict.rule = Rule::Maekawa;
    verdict.detail = std::to_string(valleys) + " valley and " + std::to_string(mountains) +
                     " mountain creases folded flat; a flat vertex has two more of one kind than of the other "
                     "(Maekawa)";
    for (size_t i = 0; i < folded.size(); ++i)
      verdict.suspects.push_back(static_cast<int>(i));
    return verdict;
  }
  std::vector<double> sectors = sectorsOf(folded);
  double alternate = 0.0;
  for (size_t i = 0; i < sectors.size(); i += 2)
    alternate += sectors[i];
  if (std::abs(alternate - M_PI) > 1e-6)
  {
    verdict.rule = Rule::Kawasaki;
    verdict.detail = "the angles between its creases folded flat sum to " + degrees(alternate) + " and " +
                     degrees(2 * M_PI - alternate) + " alternately, not 180° each (Kawasaki)";
    for (size_t i = 0; i < folded.size(); ++i)
      verdict.suspects.push_back(static_cast<int>(i));
    return verdict;
  }
  std::vector<int> signs, ids;
  for (size_t i = 0; i < folded.size(); ++i)
  {
    signs.push_back(folded[i].sign);
    ids.push_back(static_cast<int>(i));
  }
  // Crimp: a sector no larger than either neighbour whose two creases fold opposite ways folds
  // away, its neighbours merging; if every such sector has two creases folding the same way, the
  // flaps beside it would pass through each other.
  while (sectors.size() > 2)
  {
    const size_t n = sectors.size();
    std::optional<size_t> crimp;
    size_t smallest = 0;
    for (size_t i = 0; i < n; ++i)
    {
      if (sectors[i] < sectors[smallest])
        smallest = i;
      const bool local_minimum =
          sectors[i] <= sectors[(i + n - 1) % n] + 1e-9 && sectors[i] <= sectors[(i + 1) % n] + 1e-9;
      if (local_minimum && signs[i] != signs[(i + 1) % n] && !crimp)
        crimp = i;
    }
    if (!crimp)
    {
      verdict.rule = Rule::BigLittleBig;
      verdict.detail = "the two creases about its smallest angle (" + degrees(sectors[smallest]) +
                       ") fold the same way, so the larger flaps beside it would pass through each other "
                       "(big-little-big)";
      verdict.suspects = { ids[smallest], ids[(smallest + 1) % n] };
      return verdict;
    }
    const size_t i = *crimp, before = (i + n - 1) % n, after = (i + 1) % n;
    sectors[before] = sectors[before] - sectors[i] + sectors[after];
    // Drop sector i and the sector after it, and the creases i and i + 1 that bound sector i.
    std::vector<size_t> drop_sectors = { i, after }, drop_creases = { i, after };
    std::sort(drop_sectors.rbegin(), drop_sectors.rend());
    for (size_t d : drop_sectors)
      sectors.erase(sectors.begin() + static_cast<std::ptrdiff_t>(d));
    std::sort(drop_creases.rbegin(), drop_creases.rend());
    for (size_t d : drop_creases)
    {
      signs.erase(signs.begin() + static_cast<std::ptrdiff_t>(d));
      ids.erase(ids.begin() + static_cast<std::ptrdiff_t>(d));
    }
    // Erasing sector `after` == 0 (i = n − 1) shifts `before`; the merged value stays in place
    // because sectors are cyclic and `before` only moved down by one.
  }
  return verdict;
}

std::string pointText(const Vec2& p)
{
  std::ostringstream out;
  out.precision(4);
  out << "(" << p.x() << ", " << p.y() << ")";
  return out.str();
}

/// Whether flipping the spokes `chosen` (mountain ↔ valley) makes the vertex fold flat.
bool foldsFlipped(const std::vector<Spoke>& folded, const std::vector<int>& chosen)
{
  std::vector<Spoke> flipped = folded;
  for (int s : chosen)
    flipped[s].sign = -flipped[s].sign;
  return judge(flipped).rule == Rule::Holds;
}

/// The next `k`-subset of 0..n−1 in lexicographic order; false after the last.
bool nextSubset(std::vector<int>& subset, int n)
{
  const int k = static_cast<int>(subset.size());
  for (int i = k - 1; i >= 0; --i)
    if (subset[i] < n - k + i)
    {
      ++subset[i];
      for (int j = i + 1; j < k; ++j)
        subset[j] = subset[j - 1] + 1;
      return true;
    }
  return false;
}

/// The crease whose change (mountain ↔ valley, or unfolding it) makes the vertex fold flat; where
/// no single one does, the fewest creases (up to three) whose flips do, so that the user is told
/// which creases to change, not only that some must.
std::string remedy(const Paper& paper, const std::vector<Spoke>& folded, const Verdict& verdict)
{
  for (int s : verdict.suspects)
    if (foldsFlipped(folded, { s }))
      return ": fold " + creaseText(paper, folded[s].edge) + " " + (folded[s].sign > 0 ? "mountain" : "valley") +
             " instead";
  for (int s : verdict.suspects)
  {
    std::vector<Spoke> fewer = folded;
    fewer.erase(fewer.begin() + s);
    if (!fewer.empty() && judge(fewer).rule == Rule::Holds)
      return ": leave " + creaseText(paper, folded[s].edge) + " unfolded";
  }
  const int n = static_cast<int>(folded.size());
  constexpr int kMostSpokesSearched = 24;  // C(24, 3) = 2024 verdicts at most
  for (int k = 2; k <= 3 && k <= n && n <= kMostSpokesSearched && verdict.rule != Rule::Kawasaki; ++k)
  {
    std::vector<int> chosen(k);
    for (int i = 0; i < k; ++i)
      chosen[i] = i;
    do
    {
      if (!foldsFlipped(folded, chosen))
        continue;
      std::string text = ": fold";
      for (int i = 0; i < k; ++i)
      {
        const char* joint = i == 0 ? " " : i + 1 == k ? " and " : ", ";
        text += joint + creaseText(paper, folded[chosen[i]].edge) + " " +
                (folded[chosen[i]].sign > 0 ? "mountain" : "valley");
      }
      return text + " instead (no change of a single crease makes it fold flat)";
    } while (nextSubset(chosen, n));
  }
  return "; no change of a single crease makes it fold flat";
}
}  // namespace

std::string creaseText(const Paper& paper, int edge)
{
  if (edge < 0 || edge >= static_cast<int>(paper.edges.size()))
    return "crease " + std::to_string(edge);
  const Edge& e = paper.edges[edge];
  return "crease " + std::to_string(edge) + " " + pointText(paper.vertices[e.vertices[0]].crease_pattern) + "–" +
         pointText(paper.vertices[e.vertices[1]].crease_pattern);
}

std::string faceText(const Paper& paper, int face)
{
  if (face < 0 || face >= static_cast<int>(paper.faces.size()))
    return "face " + std::to_string(face);
  std::vector<Vec2> polygon;
  for (int v : paper.faces[face].vertices)
    polygon.push_back(paper.vertices[v].crease_pattern);
  Vec2 centroid = Vec2::Zero();
  for (size_t i = 0; i < polygon.size(); ++i)
  {
    const Vec2 &p = polygon[i], &q = polygon[(i + 1) % polygon.size()];
    centroid += (p + q) * cross2(p, q);
  }
  centroid /= 6.0 * signedArea(polygon);
  std::ostringstream out;
  out.precision(2);
  out << "face " << face << " (about (" << centroid.x() << ", " << centroid.y() << ") on the sheet)";
  return out.str();
}

Status checkFlatVertices(const Paper& paper, const std::vector<double>& angles, const std::vector<int>& around_edges)
{
  std::vector<char> wanted(paper.vertices.size(), around_edges.empty() ? 1 : 0);
  for (int e : around_edges)
    if (e >= 0 && e < static_cast<int>(paper.edges.size()))
      for (int v : paper.edges[e].vertices)
        wanted[v] = 1;
  std::vector<std::vector<int>> incident(paper.vertices.size());
  std::vector<char> on_boundary(paper.vertices.size(), 0);
  for (size_t e = 0; e < paper.edges.size(); ++e)
    for (int v : paper.edges[e].vertices)
    {
      incident[v].push_back(static_cast<int>(e));
      if (!paper.edges[e].isCrease())
        on_boundary[v] = 1;
    }
  for (size_t v = 0; v < paper.vertices.size(); ++v)
  {
    if (!wanted[v] || on_boundary[v] || incident[v].empty())
      continue;
    std::vector<Spoke> folded;
    bool flat = true;
    for (int e : incident[v])
    {
      const double angle = e < static_cast<int>(angles.size()) ? angles[e] : paper.edges[e].fold_angle;
      if (std::abs(angle) <= kFlatAngleTolerance)
        continue;
      if (std::abs(std::abs(angle) - M_PI) > kFlatAngleTolerance)
      {
        flat = false;
        break;
      }
      const Edge& edge = paper.edges[e];
      const int far = edge.vertices[0] == static_cast<int>(v) ? edge.vertices[1] : edge.vertices[0];
      const Vec2 d = paper.vertices[far].crease_pattern - paper.vertices[v].crease_pattern;
      folded.push_back({ e, std::atan2(d.y(), d.x()), angle > 0 ? 1 : -1 });
    }
    if (!flat || folded.empty())
      continue;
    std::sort(folded.begin(), folded.end(), [](const Spoke& a, const Spoke& b) { return a.direction < b.direction; });
    const Verdict verdict = judge(folded);
    if (verdict.rule == Rule::Holds)
      continue;
    return failure("vertex " + std::to_string(v) + " at " + pointText(paper.vertices[v].crease_pattern) +
                   " cannot fold flat: " + verdict.detail + remedy(paper, folded, verdict));
  }
  return success();
}

}  // namespace virtual_origami::core

// Tessellation generators. Each builds crease-pattern points and counter-clockwise faces, lets
// patternPaper() derive the edges and topology, then assigns the creases M/V by construction.
#include "virtual_origami/core/tessellations.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <sstream>
#include <utility>

#include "virtual_origami/core/planar_geometry.h"
#include "virtual_origami/core/reference_patterns.h"

namespace virtual_origami::core
{
namespace
{
constexpr double kPi = 3.14159265358979323846;
/// Larger patterns are refused before anything is allocated: the benchmarks need 10^4 vertices.
constexpr long kMaxVertices = 4'000'000;

bool positive(double x)
{
  return std::isfinite(x) && x > 0;
}

Status checkGrid(const std::string& name, int columns, int rows, TessellationKind kind)
{
  if (columns < 1 || rows < 1)
    return failure(name + ": columns and rows must be at least 1");
  if (tessellationVertexCount(kind, columns, rows) > kMaxVertices)
    return failure(name + ": more than " + std::to_string(kMaxVertices) + " vertices");
  return success();
}

/// Points and faces of a pattern under construction; faces are turned counter-clockwise as they
/// come, so generators can list corners in whichever order their geometry makes plain.
struct Builder
{
  std::vector<Vec2> points;
  std::vector<std::vector<int>> faces;
  /// Points addressed by integer lattice coordinates, for patterns drawn on a lattice.
  std::map<std::pair<long, long>, int> lattice;

  int add(const Vec2& p)
  {
    points.push_back(p);
    return static_cast<int>(points.size()) - 1;
  }
  int at(long x, long y, const Vec2& p)
  {
    auto [it, added] = lattice.emplace(std::make_pair(x, y), static_cast<int>(points.size()));
    if (added)
      points.push_back(p);
    return it->second;
  }
  void face(std::vector<int> cycle)
  {
    cycle.erase(std::unique(cycle.begin(), cycle.end()), cycle.end());  // clipped corners coincide
    if (cycle.size() > 1 && cycle.front() == cycle.back())
      cycle.pop_back();
    if (signedArea(points, cycle) < 0)
      std::reverse(cycle.begin(), cycle.end());
    faces.push_back(std::move(cycle));
  }
};

double targetOf(Assignment assignment)
{
  switch (assignment)
  {
    case Assignment::Valley:
      return kPi;
    case Assignment::Mountain:
      return -kPi;
    default:
      return 0.0;
  }
}

/// Assigns every crease of `paper` by `assign(paper, edge)` and records the targets.
template <class Assign>
Tessellation finish(Paper paper, const Assign& assign, int columns, int rows, bool flat_foldable)
{
  Tessellation t;
  t.target_fold_angle.assign(paper.edges.size(), 0.0);
  for (size_t e = 0; e < paper.edges.size(); ++e)
  {
    Edge& edge = paper.edges[e];
    edge.fold_angle = 0.0;
    if (!edge.isCrease())
      continue;
    edge.assignment = assign(paper, edge);
    t.target_fold_angle[e] = targetOf(edge.assignment);
  }
  t.paper = std::move(paper);
  t.flat_foldable = flat_foldable;
  t.columns = columns;
  t.rows = rows;
  return t;
}

Expected<Tessellation> build(const Builder& b, const std::map<std::pair<int, int>, Assignment>& creases, int columns,
                             int rows, bool flat_foldable)
{
  Expected<Paper> paper = patternPaper(b.points, b.faces);
  if (!paper)
    return Expected<Tessellation>::failure(paper.message());
  return finish(
      std::move(*paper),
      [&](const Paper&, const Edge& edge) {
        const auto it = creases.find(std::minmax(edge.vertices[0], edge.vertices[1]));
        return it == creases.end() ? Assignment::Unassigned : it->second;
      },
      columns, rows, flat_foldable);
}

Expected<Tessellation> build(const Builder& b, Assignment horizontal, Assignment other, int columns, int rows,
                             bool flat_foldable)
{
  Expected<Paper> paper = patternPaper(b.points, b.faces);
  if (!paper)
    return Expected<Tessellation>::failure(paper.message());
  return finish(
      std::move(*paper),
      [&](const Paper& p, const Edge& edge) {
        // Lattice coordinates are exact multiples, so equal y is exactly equal.
        const bool flat =
            p.vertices[edge.vertices[0]].crease_pattern.y() == p.vertices[edge.vertices[1]].crease_pattern.y();
        return flat ? horizontal : other;
      },
      columns, rows, flat_foldable);
}

Assignment opposite(Assignment a)
{
  return a == Assignment::Mountain ? Assignment::Valley : Assignment::Mountain;
}

}  // namespace

Expected<Tessellation> miuraTessellation(int columns, int rows, double a, double b, double gamma)
{
  if (const Status ok = checkGrid("miura", columns, rows, TessellationKind::Miura); !ok)
    return Expected<Tessellation>::failure(ok.message());
  if (!positive(a) || !positive(b))
    return Expected<Tessellation>::failure("miura: panel lengths must be positive");
  if (!(gamma > 0 && gamma < kPi / 2))
    return Expected<Tessellation>::failure("miura: gamma must lie in (0, pi/2)");
  Paper paper = miuraOri(columns, rows, a, b, gamma);
  const int stride = columns + 1;
  return finish(
      std::move(paper),
      [&](const Paper&, const Edge& edge) {
        const int lo = std::min(edge.vertices[0], edge.vertices[1]);
        const int hi = std::max(edge.vertices[0], edge.vertices[1]);
        const int i = lo % stride, j = lo / stride;
        double sign;
        if (hi == lo + 1)  // straight crease (i, j)→(i+1, j)
          sign = (i + j) % 2 ? -1.0 : 1.0;
        else  // zigzag crease (i, j)→(i, j+1)
          sign = i % 2 ? 1.0 : -1.0;
        return sign > 0 ? Assignment::Valley : Assignment::Mountain;
      },
      columns, rows, true);
}

Expected<Tessellation> miuraTessellationFolded(int columns, int rows, double a, double b, double gamma, double rho)
{
  if (!(std::abs(rho) < kPi))
    return Expected<Tessellation>::failure("miura: rho must lie in (-pi, pi)");
  Expected<Tessellation> t = miuraTessellation(columns, rows, a, b, gamma);
  if (!t)
    return t;
  const std::vector<double> angles = miuraFoldAngles(t->paper, columns, rows, gamma, rho);
  if (const Status folded = foldToAngles(t->paper, angles); !folded)
    return Expected<Tessellation>::failure("miura: " + folded.message());
  return t;
}

Expected<Tessellation> yoshimuraTessellation(int columns, int rows, double width, double height)
{
  if (const Status ok = checkGrid("yoshimura", columns, rows, TessellationKind::Yoshimura); !ok)
    return Expected<Tessellation>::failure(ok.message());
  if (!positive(width) || !positive(height))
    return Expected<Tessellation>::failure("yoshimura: width and height must be positive");
  // Lattice: x in half widths, y in lines. Even lines hold x = 0, 2, …, 2C; odd lines
  // x = 0, 1, 3, …, 2C − 1, 2C.
  Builder b;
  const long c2 = 2L * columns;
  const auto p = [&](long x, long y) { return b.at(x, y, Vec2(0.5 * width * x, height * y)); };
  for (long line = 0; line <= rows; ++line)
    for (long x = 0; x <= c2; ++x)
      if (line % 2 == 0 ? x % 2 == 0 : (x % 2 == 1 || x == 0 || x == c2))
        p(x, line);
  for (long row = 0; row < rows; ++row)
  {
    const long e = row % 2 == 0 ? row : row + 1;  // the even line of the two
    const long o = row % 2 == 0 ? row + 1 : row;
    for (long x = 0; x < c2; x += 2)
      b.face({ p(x, e), p(x + 2, e), p(x + 1, o) });
    for (long x = 1; x + 2 < c2; x += 2)
      b.face({ p(x, o), p(x + 2, o), p(x + 1, e) });
    b.face({ p(0, e), p(1, o), p(0, o) });
    b.face({ p(c2, e), p(c2, o), p(c2 - 1, o) });
  }
  const double phi = std::atan2(2 * height, width);
  return build(b, Assignment::Mountain, Assignment::Valley, columns, rows, phi <= kPi / 3 + 1e-12);
}

Expected<Tessellation> squareTwistTessellation(int columns, int rows, double pitch, double twist, double shrink)
{
  if (const Status ok = checkGrid("square twist", columns, rows, TessellationKind::SquareTwist); !ok)
    return Expected<Tessellation>::failure(ok.message());
  if (!positive(pitch))
    return Expected<Tessellation>::failure("square twist: pitch must be positive");
  if (!(twist > 0 && twist < kPi / 2))
    return Expected<Tessellation>::failure("square twist: twist must lie in (0, pi/2)");
  // A pleat a1 a2 b2 b1 has signed area ∝ shrink·(shrink − cos twist): zero at cos twist, and
  // past it the pleats fold over the tiles.
  if (!(shrink > 0 && shrink < std::cos(twist)))
    return Expected<Tessellation>::failure("square twist: shrink must lie in (0, cos(twist))");

  // Tile (i, j) corner k (0: −−, 1: +−, 2: ++, 3: −+) is vertex 4·(j·columns + i) + k.
  Builder b;
  const Eigen::Rotation2Dd turn(twist);
  static const int dx[4] = { 0, 1, 1, 0 }, dy[4] = { 0, 0, 1, 1 };
  for (int j = 0; j < rows; ++j)
    for (int i = 0; i < columns; ++i)
    {
      const Vec2 centre((i + 0.5) * pitch, (j + 0.5) * pitch);
      for (int k = 0; k < 4; ++k)
        b.add(centre + shrink * (turn * (pitch * Vec2(dx[k] - 0.5, dy[k] - 0.5))));
    }
  const auto corner = [&](int i, int j, int k) { return 4 * (j * columns + i) + k; };
  // Grid point of a tile corner, and its colour: the twist square there is all-valley on even
  // points and all-mountain on odd ones; a tile edge takes the colour opposite to that of the
  // twist square at its end where the pleat's angle is acute (the sector big-little-big singles out).
  const auto colour = [](int gi, int gj) { return (gi + gj) % 2 == 0 ? Assignment::Mountain : Assignment::Valley; };
  std::map<std::pair<int, int>, Assignment> creases;
  const auto pleat = [&](int p, int q, int p_partner, int q_partner, std::pair<int, int> p_grid,
                         std::pair<int, int> q_grid) {
    b.face({ p, q, q_partner, p_partner });
    const Vec2& P = b.points[p];
    const bool acute_at_p = angleBetween(b.points[q] - P, b.points[p_partner] - P) < kPi / 2;
    const std::pair<int, int> g = acute_at_p ? p_grid : q_grid;
    creases[std::minmax(p, q)] = colour(g.first, g.second);
    // The partner tile's edge is the same pleat seen from the other side (acute at the other end).
    const std::pair<int, int> h = acute_at_p ? q_grid : p_grid;
    creases[std::minmax(p_partner, q_partner)] = colour(h.first, h.second);
  };
  for (int j = 0; j < rows; ++j)
    for (int i = 0; i < columns; ++i)
    {
      b.face({ corner(i, j, 0), corner(i, j, 1), corner(i, j, 2), corner(i, j, 3) });
      if (i + 1 < columns)  // pleat across the tile's right side, grid points (i+1, j) and (i+1, j+1)
        pleat(corner(i, j, 1), corner(i, j, 2), corner(i + 1, j, 0), corner(i + 1, j, 3), { i + 1, j },
              { i + 1, j + 1 });
      if (j + 1 < rows)  // pleat across the top side, grid points (i, j+1) and (i+1, j+1)
        pleat(corner(i, j, 3), corner(i, j, 2), corner(i, j + 1, 0), corner(i, j + 1, 1), { i, j + 1 },
              { i + 1, j + 1 });
    }
  for (int j = 1; j < rows; ++j)
    for (int i = 1; i < columns; ++i)
    {
      const std::vector<int> square{ corner(i - 1, j - 1, 2), corner(i, j - 1, 3), corner(i, j, 0),
                                     corner(i - 1, j, 1) };
      for (size_t k = 0; k < 4; ++k)
        creases[std::minmax(square[k], square[(k + 1) % 4])] = opposite(colour(i, j));
      b.face(square);
    }
  return build(b, creases, columns, rows, true);
}

Expected<Tessellation> waterbombTessellation(int columns, int rows, double width, double height)
{
  if (const Status ok = checkGrid("waterbomb", columns, rows, TessellationKind::Waterbomb); !ok)
    return Expected<Tessellation>::failure(ok.message());
  if (!positive(width) || !positive(height))
    return Expected<Tessellation>::failure("waterbomb: width and height must be positive");
  // Lattice: x in half widths (0 … 2C), y in half heights (row r spans 2r … 2r + 2, its mid-line
  // at 2r + 1). Even rows have base centres at odd x, odd rows at even x (0 and 2C being the
  // centres of the clipped half bases).
  Builder b;
  const long c2 = 2L * columns, top = 2L * rows;
  const auto p = [&](long x, long y) { return b.at(x, y, Vec2(0.5 * width * x, 0.5 * height * y)); };
  const auto clip = [&](long x) { return std::clamp(x, 0L, c2); };
  for (long r = 0; r < rows; ++r)
  {
    const long lo = 2 * r, mid = lo + 1, hi = lo + 2;
    std::vector<long> centres;
    for (long x = r % 2 == 0 ? 1 : 0; x <= c2; x += 2)
      centres.push_back(x);
    for (const long c : centres)
    {
      // A base's top and bottom sides lie on row boundaries, where the next row's corners fall at
      // their mid-points: those stay on the side (collinear) so the faces meet edge to edge.
      std::vector<int> up{ p(c, mid), p(clip(c + 1), hi) };
      if (hi < top)
        up.push_back(p(c, hi));
      up.push_back(p(clip(c - 1), hi));
      b.face(up);
      std::vector<int> down{ p(c, mid), p(clip(c - 1), lo) };
      if (lo > 0)
        down.push_back(p(c, lo));
      down.push_back(p(clip(c + 1), lo));
      b.face(down);
    }
    for (size_t k = 0; k + 1 < centres.size(); ++k)
    {
      const long c = centres[k];
      b.face({ p(c, mid), p(c + 1, lo), p(c + 2, mid) });
      b.face({ p(c, mid), p(c + 2, mid), p(c + 1, hi) });
    }
    if (r % 2 == 0)  // the strips between the sheet's sides and the first and last centres
    {
      b.face({ p(0, lo), p(1, mid), p(0, mid) });
      b.face({ p(0, mid), p(1, mid), p(0, hi) });
      b.face({ p(c2, lo), p(c2, mid), p(c2 - 1, mid) });
      b.face({ p(c2, mid), p(c2, hi), p(c2 - 1, mid) });
    }
  }
  return build(b, Assignment::Mountain, Assignment::Valley, columns, rows, false);
}

std::string tessellationName(TessellationKind kind)
{
  switch (kind)
  {
    case TessellationKind::Miura:
      return "miura";
    case TessellationKind::Yoshimura:
      return "yoshimura";
    case TessellationKind::SquareTwist:
      return "square twist";
    case TessellationKind::Waterbomb:
      return "waterbomb";
  }
  return "unknown";
}

long tessellationVertexCount(TessellationKind kind, int columns, int rows)
{
  const long c = columns, r = rows;
  switch (kind)
  {
    case TessellationKind::Miura:
      return (c + 1) * (r + 1);
    case TessellationKind::Yoshimura:  // even lines C + 1 vertices, odd lines C + 2
      return (r / 2 + 1) * (c + 1) + ((r + 1) / 2) * (c + 2);
    case TessellationKind::SquareTwist:
      return 4 * c * r;
    case TessellationKind::Waterbomb: {
      // Bottom line C + 1; inner row boundaries 2C + 1; top line C + 1 (even last row) or C + 2;
      // mid-lines C + 2 on even rows, C + 1 on odd ones.
      const long top = (r - 1) % 2 == 0 ? c + 1 : c + 2;
      const long mids = ((r + 1) / 2) * (c + 2) + (r / 2) * (c + 1);
      return (c + 1) + (r - 1) * (2 * c + 1) + top + mids;
    }
  }
  return 0;
}

GridSize gridForVertexCount(TessellationKind kind, long vertex_count)
{
  // Sheet width and height per unit with the default parameters.
  double unit_w = 1.0, unit_h = 1.0;
  switch (kind)
  {
    case TessellationKind::Miura:
      unit_h = std::sin(kPi / 3);
      break;
    case TessellationKind::Yoshimura:
      unit_h = 0.5;
      break;
    default:
      break;
  }
  GridSize best{ 1, 1 };
  long best_error = std::numeric_limits<long>::max();
  const long target = std::max(vertex_count, 1L);
  for (int rows = 1; rows <= 4096; ++rows)
  {
    // The count grows linearly in columns for fixed rows: solve, then try the neighbours.
    const long base = tessellationVertexCount(kind, 1, rows);
    const long slope = tessellationVertexCount(kind, 2, rows) - base;
    const long guess = 1 + (target - base) / std::max(slope, 1L);
    for (long columns = std::max(1L, guess - 1); columns <= std::max(1L, guess + 1); ++columns)
    {
      if (columns > 4096)
        break;
      const double aspect = (columns * unit_w) / (rows * unit_h);
      if (aspect > 2.0 || aspect < 0.5)
        continue;
      const long error = std::abs(tessellationVertexCount(kind, static_cast<int>(columns), rows) - target);
      if (error < best_error)
      {
        best_error = error;
        best = { static_cast<int>(columns), rows };
      }
    }
  }
  return best;
}

Expected<Tessellation> tessellationWithVertices(TessellationKind kind, long vertex_count)
{
  if (vertex_count < 1 || vertex_count > kMaxVertices)
    return Expected<Tessellation>::failure(tessellationName(kind) + ": vertex count must lie in 1.." +
                                           std::to_string(kMaxVertices));
  const GridSize grid = gridForVertexCount(kind, vertex_count);
  switch (kind)
  {
    case TessellationKind::Miura:
      return miuraTessellation(grid.columns, grid.rows);
    case TessellationKind::Yoshimura:
      return yoshimuraTessellation(grid.columns, grid.rows);
    case TessellationKind::SquareTwist:
      return squareTwistTessellation(grid.columns, grid.rows);
    case TessellationKind::Waterbomb:
      return waterbombTessellation(grid.columns, grid.rows);
  }
  return Expected<Tessellation>::failure("unknown tessellation kind");
}

std::vector<std::string> flatFoldabilityProblems(const Paper& paper, double tolerance)
{
  const size_t n = paper.vertices.size();
  std::vector<std::vector<int>> incident(n);
  std::vector<char> on_boundary(n, 0);
  for (size_t e = 0; e < paper.edges.size(); ++e)
  {
    const Edge& edge = paper.edges[e];
    for (int v : edge.vertices)
    {
      incident[v].push_back(static_cast<int>(e));
      if (!edge.isCrease())
        on_boundary[v] = 1;
    }
  }
  std::vector<std::string> problems;
  for (size_t v = 0; v < n; ++v)
  {
    if (on_boundary[v] || incident[v].empty())
      continue;
    const Vec2& o = paper.vertices[v].crease_pattern;
    std::vector<std::pair<double, int>> around;
    int mountains = 0, valleys = 0, others = 0;
    for (int e : incident[v])
    {
      const Vec2 d = paper.vertices[paper.edges[e].otherVertex(static_cast<int>(v))].crease_pattern - o;
      around.emplace_back(std::atan2(d.y(), d.x()), e);
      const Assignment a = paper.edges[e].assignment;
      (a == Assignment::Mountain ? mountains : a == Assignment::Valley ? valleys : others) += 1;
    }
    std::ostringstream msg;
    if (others > 0)
      msg << "vertex " << v << ": " << others << " crease(s) neither mountain nor valley";
    else if (std::abs(mountains - valleys) != 2)
      msg << "vertex " << v << ": Maekawa fails (" << mountains << " M, " << valleys << " V)";
    else
    {
      std::sort(around.begin(), around.end());
      double alternate = 0;
      for (size_t k = 0; k < around.size(); k += 2)
      {
        const double next = k + 1 < around.size() ? around[k + 1].first : around[0].first + 2 * kPi;
        alternate += next - around[k].first;
      }
      const size_t m = around.size();
      const auto sector = [&](size_t k) {
        return k + 1 < m ? around[k + 1].first - around[k].first : around[0].first + 2 * kPi - around[k].first;
      };
      if (m % 2 != 0 || std::abs(alternate - kPi) > tolerance)
        msg << "vertex " << v << ": Kawasaki fails (alternate sectors sum to " << alternate << ")";
      else
        for (size_t k = 0; k < m; ++k)
        {
          // A sector smaller than both neighbours folds under them only between creases of opposite kinds.
          const double s = sector(k);
          const bool strict_minimum = s < sector((k + m - 1) % m) - tolerance && s < sector((k + 1) % m) - tolerance;
          if (strict_minimum &&
              paper.edges[around[k].second].assignment == paper.edges[around[(k + 1) % m].second].assignment)
          {
            msg << "vertex " << v << ": big-little-big fails (the smallest sector lies between creases of one kind)";
            break;
          }
        }
    }
    if (!msg.str().empty())
      problems.push_back(msg.str());
  }
  return problems;
}

}  // namespace virtual_origami::core

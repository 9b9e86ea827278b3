#include "virtual_origami/core/layer_order.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <numeric>
#include <optional>
#include <sstream>
#include <string>

#include <CGAL/Bbox_3.h>
#include <CGAL/box_intersection_d.h>

#include "virtual_origami/core/face_orders.h"
#include "virtual_origami/core/flat_vertices.h"
#include "virtual_origami/core/planar_geometry.h"

namespace virtual_origami::core
{
namespace
{
using Polygon = std::vector<Vec2>;

/// Counter-clockwise copy of a convex polygon.
Polygon counterClockwise(Polygon p)
{
  if (signedArea(p) < 0)
    std::reverse(p.begin(), p.end());
  return p;
}

/// Sutherland–Hodgman: the part of convex `subject` inside convex counter-clockwise `clip`.
Polygon clipConvex(const Polygon& subject, const Polygon& clip)
{
  Polygon out = subject;
  for (size_t i = 0; i < clip.size() && !out.empty(); ++i)
  {
    const Vec2 a = clip[i], b = clip[(i + 1) % clip.size()];
    const Polygon in = out;
    out.clear();
    for (size_t j = 0; j < in.size(); ++j)
    {
      const Vec2 p = in[j], q = in[(j + 1) % in.size()];
      const double sp = cross2(b - a, p - a), sq = cross2(b - a, q - a);
      if (sp >= 0)
        out.push_back(p);
      if ((sp >= 0) != (sq >= 0))
        out.push_back(p + (q - p) * (sp / (sp - sq)));
    }
  }
  return out;
}

double area(const Polygon& p)
{
  return std::abs(signedArea(p));
}

/// Smallest distance from `p` inside convex counter-clockwise `poly` to its sides (negative outside).
double depthInside(const Polygon& poly, const Vec2& p)
{
  double depth = std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < poly.size(); ++i)
  {
    const Vec2 a = poly[i], b = poly[(i + 1) % poly.size()];
    const double length = (b - a).norm();
    if (length > 0)
      depth = std::min(depth, cross2(b - a, p - a) / length);
  }
  return depth;
}

/// A crease folded flat, as a segment of the stack's plane with the side its two faces lie on.
struct FlatCrease
{
  int edge = -1, face = -1, other = -1;
  Vec2 a, b;
  int side = 0;  // +1: the faces lie left of a→b
};

/// The faces of one plane, in 2D coordinates of it, with the literals of the pairs that overlap.
class StackProblem
{
public:
  StackProblem(const Paper& paper, const std::vector<int>& faces, double tolerance)
    : paper_(paper), faces_(faces), tolerance_(tolerance)
  {
    up_ = paper.faceNormal(faces.front());
    const Vec3 e1 = up_.unitOrthogonal(), e2 = up_.cross(e1);
    for (int f : faces)
    {
      Polygon p;
      for (int v : paper.faces[f].vertices)
        p.emplace_back(e1.dot(paper.vertices[v].folded), e2.dot(paper.vertices[v].folded));
      polygons_[f] = counterClockwise(p);
      facing_[f] = paper.faceNormal(f).dot(up_) > 0 ? 1 : -1;
      for (int v : paper.faces[f].vertices)
        plane_points_[v] = Vec2(e1.dot(paper.vertices[v].folded), e2.dot(paper.vertices[v].folded));
    }
    for (size_t i = 0; i < faces.size(); ++i)
      for (size_t j = i + 1; j < faces.size(); ++j)
        if (facesStacked(paper, faces[i], faces[j], tolerance))
        {
          const int f = std::min(faces[i], faces[j]), g = std::max(faces[i], faces[j]);
          variables_[{ f, g }] = static_cast<int>(pairs_.size());
          pairs_.push_back({ f, g });
        }
  }

  int variableCount() const
  {
    return static_cast<int>(pairs_.size());
  }
  const std::vector<std::pair<int, int>>& pairs() const
  {
    return pairs_;
  }
  int facing(int f) const
  {
    return facing_.at(f);
  }

  /// The literal "b lies higher than a" (along the stack's up), 0 when the two do not overlap.
  int higher(int a, int b) const
  {
    const auto it = variables_.find({ std::min(a, b), std::max(a, b) });
    if (it == variables_.end())
      return 0;
    return a < b ? it->second + 1 : -(it->second + 1);
  }

  const Polygon& polygon(int f) const
  {
    return polygons_.at(f);
  }
  Vec2 planePoint(int v) const
  {
    return plane_points_.at(v);
  }
  const Paper& paper() const
  {
    return paper_;
  }
  double tolerance() const
  {
    return tolerance_;
  }

private:
  const Paper& paper_;
  std::vector<int> faces_;
  double tolerance_;
  Vec3 up_;
  std::map<int, Polygon> polygons_;
  std::map<int, int> facing_;
  std::map<int, Vec2> plane_points_;
  std::map<std::pair<int, int>, int> variables_;
  std::vector<std::pair<int, int>> pairs_;
};

/// Why a clause holds, in words: written only when the clause is the one that fails (writing it
/// for every clause, with the creases' coordinates, took a third of a flap drag's time).
using Why = std::function<std::string()>;

struct Clause
{
  std::vector<int> literals;
  Why why;
};

using Clauses = std::vector<Clause>;

/// +1 when convex `poly` lies left of the line a→b, −1 right (by its centroid).
int sideOf(const Vec2& a, const Vec2& b, const Polygon& poly)
{
  Vec2 centroid = Vec2::Zero();
  for (const Vec2& p : poly)
    centroid += p;
  centroid /= static_cast<double>(poly.size());
  return cross2(b - a, centroid - a) > 0 ? 1 : -1;
}

/// A face folded flat over a crease lies on the side its fold angle says; returns those creases.
std::vector<FlatCrease> creaseRules(const Paper& paper, const StackProblem& stack, const std::vector<char>& member,
                                    Clauses& clauses)
{
  std::vector<FlatCrease> creases;
  for (size_t e = 0; e < paper.edges.size(); ++e)
  {
    const Edge& edge = paper.edges[e];
    if (!edge.isCrease() || std::abs(std::abs(edge.fold_angle) - M_PI) > kFlatAngleTolerance)
      continue;
    const int f = edge.faces[0], g = edge.faces[1];
    if (!member[f] || !member[g])
      continue;
    const int literal = stack.higher(f, g);
    if (literal == 0)
      continue;
    const bool g_higher = (edge.fold_angle > 0) == (stack.facing(f) > 0);
    clauses.push_back({ { g_higher ? literal : -literal }, [e, f, g, g_higher] {
                         return "crease " + std::to_string(e) + " puts face " + std::to_string(g) +
                                (g_higher ? " above" : " below") + " face " + std::to_string(f);
                       } });
    FlatCrease crease{ static_cast<int>(e), f, g, stack.planePoint(edge.vertices[0]),
                       stack.planePoint(edge.vertices[1]) };
    crease.side = sideOf(crease.a, crease.b, stack.polygon(f));
    creases.push_back(crease);
  }
  return creases;
}

/// Orders known beforehand hold.
void keptRules(const StackProblem& stack, const std::vector<char>& member, const std::vector<FaceOrder>& kept,
               Clauses& clauses)
{
  const auto inStack = [&](int f) { return f >= 0 && f < static_cast<int>(member.size()) && member[f]; };
  for (const FaceOrder& o : kept)
  {
    if (!inStack(o.face) || !inStack(o.other) || o.above == 0)
      continue;
    const int literal = stack.higher(o.face, o.other);
    if (literal != 0)
      clauses.push_back({ { o.above * stack.facing(o.face) > 0 ? literal : -literal }, [o] {
                           return "faces " + std::to_string(o.face) + " and " + std::to_string(o.other) +
                                  " keep their order";
                         } });
  }
}

/// Three layers over one place stack one way.
void transitivityRules(const StackProblem& stack, const std::vector<int>& faces, Clauses& clauses)
{
  const double tolerance = stack.tolerance();
  // Each face's later partners (the faces after it in `faces` that it overlaps), with the literal
  // "the partner lies higher", and its outline's box: the triples are those of overlapping pairs,
  // found by merging two partner lists instead of asking every third face, and their clauses
  // made from the kept literals instead of looking each pair up again (a flat Miura-ori's stack
  // of 156 faces: its layer order 0.8 -> 0.47 s).
  const size_t n = faces.size();
  std::vector<std::vector<std::pair<size_t, int>>> later(n);
  std::vector<Eigen::AlignedBox2d> boxes(n);
  for (size_t i = 0; i < n; ++i)
  {
    for (const Vec2& p : stack.polygon(faces[i]))
      boxes[i].extend(p);
    for (size_t j = i + 1; j < n; ++j)
      if (const int higher = stack.higher(faces[i], faces[j]))
        later[i].emplace_back(j, higher);
  }
  for (size_t i = 0; i < n; ++i)
    for (size_t a = 0; a < later[i].size(); ++a)
    {
      const auto [j, f_below_g] = later[i][a];
      const int f = faces[i], g = faces[j];
      const Polygon fg = clipConvex(stack.polygon(f), stack.polygon(g));
      if (fg.empty())
        continue;
      Eigen::AlignedBox2d fg_box;
      for (const Vec2& p : fg)
        fg_box.extend(p);
      // Merge the partners of f after g with those of g: each h both overlap.
      for (size_t b = a + 1, c = 0; b < later[i].size() && c < later[j].size();)
      {
        const auto [k, f_below_h] = later[i][b];
        const auto [k_of_g, g_below_h] = later[j][c];
        if (k != k_of_g)
        {
          (k < k_of_g ? b : c) += 1;
          continue;
        }
        ++b;
        ++c;
        const int h = faces[k];
        if (fg_box.exteriorDistance(boxes[k]) > tolerance ||
            area(clipConvex(fg, stack.polygon(h))) <= tolerance * tolerance)
          continue;
        const Why why = [f, g, h] {
          return "faces " + std::to_string(f) + ", " + std::to_string(g) + " and " + std::to_string(h) +
                 " overlap in one place";
        };
        // Not g over f, h over g and f over h; nor the other way round.
        clauses.push_back({ { -f_below_g, -g_below_h, f_below_h }, why });
        clauses.push_back({ { f_below_g, g_below_h, -f_below_h }, why });
      }
    }
}

/// Whether the segment from `from` to `to` runs through the inside of `poly` (off its sides), for a length.
bool crossesInside(const Vec2& from, const Vec2& to, const Polygon& poly, double tolerance)
{
  double t0 = 0.0, t1 = 1.0;  // the part of the segment inside poly
  for (size_t s = 0; s < poly.size() && t0 <= t1; ++s)
  {
    const Vec2 a = poly[s], b = poly[(s + 1) % poly.size()];
    const double da = cross2(b - a, from - a), db = cross2(b - a, to - a);
    if (da < 0 && db < 0)
      t1 = -1.0;
    else if (da < 0)
      t0 = std::max(t0, da / (da - db));
    else if (db < 0)
      t1 = std::min(t1, da / (da - db));
  }
  if (t1 - t0 <= 0 || (t1 - t0) * (to - from).norm() <= tolerance)
    return false;
  return depthInside(poly, from + 0.5 * (t0 + t1) * (to - from)) > tolerance;
}

/// No layer lies between the two faces of a fold where the fold's line crosses it (taco–tortilla).
void tacoTortillaRules(const StackProblem& stack, const std::vector<int>& faces, const std::vector<FlatCrease>& creases,
                       Clauses& clauses)
{
  for (const FlatCrease& c : creases)
    for (int h : faces)
    {
      if (h == c.face || h == c.other || stack.higher(c.face, h) == 0 || stack.higher(c.other, h) == 0 ||
          !crossesInside(c.a, c.b, stack.polygon(h), stack.tolerance()))
        continue;
      const Why why = [&paper = stack.paper(), h, edge = c.edge] {
        return "face " + std::to_string(h) + " would pass through the fold at " + creaseText(paper, edge);
      };
      clauses.push_back({ { -stack.higher(c.face, h), -stack.higher(h, c.other) }, why });
      clauses.push_back({ { -stack.higher(c.other, h), -stack.higher(h, c.face) }, why });
    }
}

/// Whether segments p and q lie on one line and overlap by more than `tolerance`.
bool onOneLine(const Vec2& pa, const Vec2& pb, const Vec2& qa, const Vec2& qb, double tolerance)
{
  const Vec2 d = (pb - pa).normalized();
  if (std::abs(cross2(d, qa - pa)) > tolerance || std::abs(cross2(d, qb - pa)) > tolerance)
    return false;
  const double p_end = (pb - pa).norm(), q_start = d.dot(qa - pa), q_end = d.dot(qb - pa);
  return std::min(p_end, std::max(q_start, q_end)) - std::max(0.0, std::min(q_start, q_end)) > tolerance;
}

/// Whether two folds lie on one line, overlapping, with their faces on the same side of it.
bool foldsOnOneSide(const FlatCrease& p, const FlatCrease& q, double tolerance)
{
  if (!onOneLine(p.a, p.b, q.a, q.b, tolerance))
    return false;
  const int q_side = (p.b - p.a).dot(q.b - q.a) > 0 ? q.side : -q.side;  // q.side measured along p's direction
  return q_side == p.side;
}

/// The clauses forbidding every order of the four faces of two folds on one line that
/// interleaves them, over the six pairs' literals (pair (x, y) of faces4, x < y, in the order
/// (0,1), (0,2), (0,3), (1,2), (1,3), (2,3)).
void forbidInterleaving(const std::vector<int>& literals, const Why& why, Clauses& clauses)
{
  for (int mask = 0; mask < 64; ++mask)
  {
    const auto bit = [](int x, int y) { return x == 0 ? y - 1 : x == 1 ? y + 1 : 5; };
    const auto above = [&](int x, int y) {  // faces4[y] higher than faces4[x]
      return x < y ? ((mask >> bit(x, y)) & 1) != 0 : ((mask >> bit(y, x)) & 1) == 0;
    };
    const auto between = [&](int x, int lo, int hi) {
      return (above(lo, x) && above(x, hi)) || (above(hi, x) && above(x, lo));
    };
    if (between(2, 0, 1) == between(3, 0, 1) && between(0, 2, 3) == between(1, 2, 3))
      continue;
    Clause clause{ {}, why };
    for (int b = 0; b < 6; ++b)
      clause.literals.push_back(((mask >> b) & 1) ? -literals[b] : literals[b]);
    clauses.push_back(std::move(clause));
  }
}

/// Two folds on one line with their faces on one side nest or lie apart, never interleave (taco–taco).
void tacoTacoRules(const StackProblem& stack, const std::vector<FlatCrease>& creases, Clauses& clauses)
{
  for (size_t i = 0; i < creases.size(); ++i)
    for (size_t j = i + 1; j < creases.size(); ++j)
    {
      const FlatCrease &p = creases[i], &q = creases[j];
      if (p.face == q.face || p.face == q.other || p.other == q.face || p.other == q.other ||
          !foldsOnOneSide(p, q, stack.tolerance()))
        continue;
      const int faces4[4] = { p.face, p.other, q.face, q.other };
      std::vector<int> literals;
      for (int x = 0; x < 4; ++x)
        for (int y = x + 1; y < 4; ++y)
          literals.push_back(stack.higher(faces4[x], faces4[y]));
      if (std::find(literals.begin(), literals.end(), 0) != literals.end())
        continue;  // two of the faces do not overlap
      forbidInterleaving(
          literals,
          [&paper = stack.paper(), p = p.edge, q = q.edge] {
            return creaseText(paper, p) + " and " + creaseText(paper, q) +
                   " fold on one line: their layers cannot interleave";
          },
          clauses);
    }
}

/// A crease left unfolded (0°) within the stack: its two faces are one flat sheet across it.
struct UnfoldedCrease
{
  int edge = -1;
  int left = -1, right = -1;  // the faces left and right of a→b
  Vec2 a, b;
};

std::vector<UnfoldedCrease> unfoldedCreases(const Paper& paper, const StackProblem& stack,
                                            const std::vector<char>& member)
{
  std::vector<UnfoldedCrease> creases;
  for (size_t e = 0; e < paper.edges.size(); ++e)
  {
    const Edge& edge = paper.edges[e];
    if (!edge.isCrease() || std::abs(edge.fold_angle) > kFlatAngleTolerance || !member[edge.faces[0]] ||
        !member[edge.faces[1]])
      continue;
    UnfoldedCrease crease{ static_cast<int>(e), edge.faces[0], edge.faces[1], stack.planePoint(edge.vertices[0]),
                           stack.planePoint(edge.vertices[1]) };
    if (sideOf(crease.a, crease.b, stack.polygon(crease.left)) < 0)
      std::swap(crease.left, crease.right);
    creases.push_back(crease);
  }
  return creases;
}

/// The face of `u` on the side `side` (+1: left) of the line p→q that `u` lies on.
int faceOnSide(const UnfoldedCrease& u, const Vec2& p, const Vec2& q, int side)
{
  const bool same_way = (q - p).dot(u.b - u.a) > 0;
  return (side > 0) == same_way ? u.left : u.right;
}

/// `b` lies higher than `a` exactly when `b2` lies higher than `a2`.
void sameOrder(const StackProblem& stack, int a, int b, int a2, int b2, const Why& why, Clauses& clauses)
{
  const int first = stack.higher(a, b), second = stack.higher(a2, b2);
  if (first == 0 || second == 0)
    return;
  clauses.push_back({ { -first, second }, why });
  clauses.push_back({ { first, -second }, why });
}

/// A sheet flat across an unfolded crease lies on one side of every layer it meets there
/// (tortilla–tortilla): a layer the crease runs through lies above or below both its faces, and
/// two sheets flat across one line keep one order on both sides of it.
void tortillaTortillaRules(const StackProblem& stack, const std::vector<int>& faces,
                           const std::vector<UnfoldedCrease>& unfolded, Clauses& clauses)
{
  const Paper& paper = stack.paper();
  const auto sheet = [](const Paper& paper, const UnfoldedCrease& u) {
    return faceText(paper, u.left) + " and " + faceText(paper, u.right) + ", one flat sheet across " +
           creaseText(paper, u.edge);
  };
  for (const UnfoldedCrease& u : unfolded)
    for (int h : faces)
      if (h != u.left && h != u.right && crossesInside(u.a, u.b, stack.polygon(h), stack.tolerance()))
        sameOrder(
            stack, u.left, h, u.right, h,
            [&paper, sheet, u, h] {
              return faceText(paper, h) + " would pass through " + sheet(paper, u) +
                     ": it lies above one and below the other";
            },
            clauses);
  for (size_t i = 0; i < unfolded.size(); ++i)
    for (size_t j = i + 1; j < unfolded.size(); ++j)
    {
      const UnfoldedCrease &u = unfolded[i], &w = unfolded[j];
      if (!onOneLine(u.a, u.b, w.a, w.b, stack.tolerance()))
        continue;
      sameOrder(
          stack, u.left, faceOnSide(w, u.a, u.b, 1), u.right, faceOnSide(w, u.a, u.b, -1),
          [&paper, sheet, u, w] {
            return sheet(paper, u) + ", and " + sheet(paper, w) +
                   ", would pass through each other: one lies above the other on one side of the crease and "
                   "below it on the other";
          },
          clauses);
    }
}

/// A sheet flat across an unfolded crease cannot lie between the two faces of a fold on the same
/// line (taco–tortilla where the tortilla's crease meets the fold).
void tacoUnfoldedRules(const StackProblem& stack, const std::vector<FlatCrease>& creases,
                       const std::vector<UnfoldedCrease>& unfolded, Clauses& clauses)
{
  for (const FlatCrease& c : creases)
    for (const UnfoldedCrease& u : unfolded)
    {
      if (!onOneLine(c.a, c.b, u.a, u.b, stack.tolerance()))
        continue;
      const int h = faceOnSide(u, c.a, c.b, c.side);
      if (h == c.face || h == c.other || stack.higher(c.face, h) == 0 || stack.higher(c.other, h) == 0)
        continue;
      const Why why = [&paper = stack.paper(), h, sheet = u.edge, fold = c.edge] {
        return faceText(paper, h) + ", flat across " + creaseText(paper, sheet) + ", would pass through the fold at " +
               creaseText(paper, fold);
      };
      clauses.push_back({ { -stack.higher(c.face, h), -stack.higher(h, c.other) }, why });
      clauses.push_back({ { -stack.higher(c.other, h), -stack.higher(h, c.face) }, why });
    }
}

/// Every rule of the stack as clauses.
Clauses rulesOf(const Paper& paper, const StackProblem& stack, const std::vector<int>& faces,
                const std::vector<FaceOrder>& kept, bool unfolded_sheets)
{
  std::vector<char> member(paper.faces.size(), 0);
  for (int f : faces)
    member[f] = 1;
  Clauses clauses;
  const std::vector<FlatCrease> creases = creaseRules(paper, stack, member, clauses);
  keptRules(stack, member, kept, clauses);
  transitivityRules(stack, faces, clauses);
  tacoTortillaRules(stack, faces, creases, clauses);
  tacoTacoRules(stack, creases, clauses);
  if (unfolded_sheets)
  {
    const std::vector<UnfoldedCrease> unfolded = unfoldedCreases(paper, stack, member);
    tortillaTortillaRules(stack, faces, unfolded, clauses);
    tacoUnfoldedRules(stack, creases, unfolded, clauses);
  }
  return clauses;
}

/// Unit propagation and chronological backtracking over clauses of ±(variable + 1).
class Search
{
public:
  Search(int variables, const std::vector<Clause>& clauses)
    : clauses_(clauses), value_(variables, 0), watch_(2 * variables)
  {
    for (size_t c = 0; c < clauses.size(); ++c)
      for (int literal : clauses[c].literals)
        watch_[slot(-literal)].push_back(static_cast<int>(c));  // revisit c when `literal` turns false
  }

  /// Empty when an assignment satisfies every clause; else why none does (a clause that fails).
  std::optional<std::string> solve(long max_guesses, bool& gave_up)
  {
    struct Guess
    {
      size_t trail_length;
      int literal;
      bool flipped;
    };
    std::vector<int> trail;
    std::vector<Guess> guesses;
    for (const Clause& clause : clauses_)
      if (clause.literals.size() == 1 && !assign(clause.literals[0], trail))
        return clause.why();
    std::optional<int> conflict = propagate(trail, 0);
    if (conflict)
      return clauses_[*conflict].why();
    long count = 0;
    for (;;)
    {
      const auto free = std::find(value_.begin(), value_.end(), 0);
      if (free == value_.end())
        return std::nullopt;
      if (++count > max_guesses)
      {
        gave_up = true;
        return "the search for an order of the layers gave up after " + std::to_string(max_guesses) + " guesses";
      }
      guesses.push_back({ trail.size(), static_cast<int>(free - value_.begin()) + 1, false });
      assign(guesses.back().literal, trail);
      conflict = propagate(trail, trail.size() - 1);
      while (conflict)
      {
        // Back to the newest guess not yet tried the other way, and the other way.
        while (!guesses.empty() && guesses.back().flipped)
        {
          undo(trail, guesses.back().trail_length);
          guesses.pop_back();
        }
        if (guesses.empty())
          return clauses_[*conflict].why();
        Guess& guess = guesses.back();
        undo(trail, guess.trail_length);
        guess.literal = -guess.literal;
        guess.flipped = true;
        assign(guess.literal, trail);
        conflict = propagate(trail, trail.size() - 1);
      }
    }
  }

  /// +1 / −1 per variable.
  const std::vector<int>& values() const
  {
    return value_;
  }

private:
  size_t slot(int literal) const
  {
    return 2 * (std::abs(literal) - 1) + (literal < 0 ? 1 : 0);
  }
  int truth(int literal) const
  {
    return literal > 0 ? value_[literal - 1] : -value_[-literal - 1];
  }

  bool assign(int literal, std::vector<int>& trail)
  {
    const int t = truth(literal);
    if (t != 0)
      return t > 0;
    value_[std::abs(literal) - 1] = literal > 0 ? 1 : -1;
    trail.push_back(literal);
    return true;
  }

  void undo(std::vector<int>& trail, size_t length)
  {
    while (trail.size() > length)
    {
      value_[std::abs(trail.back()) - 1] = 0;
      trail.pop_back();
    }
  }

  std::optional<int> propagate(std::vector<int>& trail, size_t from)
  {
    for (size_t i = from; i < trail.size(); ++i)
      for (int c : watch_[slot(trail[i])])
      {
        int unset = 0, unset_count = 0;
        bool satisfied = false;
        for (int literal : clauses_[c].literals)
        {
          const int t = truth(literal);
          if (t > 0)
          {
            satisfied = true;
            break;
          }
          if (t == 0)
          {
            unset = literal;
            ++unset_count;
          }
        }
        if (satisfied)
          continue;
        if (unset_count == 0)
          return c;
        if (unset_count == 1)
          assign(unset, trail);
      }
    return std::nullopt;
  }

  const std::vector<Clause>& clauses_;
  std::vector<int> value_;
  std::vector<std::vector<int>> watch_;
};

/// Where stacksOf stopped: a stack of more overlapping pairs than it was asked to look for.
struct StackTooLarge
{
};

/// The faces of `paper` in groups that lie flat on one another (connected by stacking, and with
/// `unfolded_sheets` by unfolded creases). Candidate pairs are those whose boxes meet (CGAL's box
/// intersection: a 10,000-face sheet part folded is a few thousand pairs, where every pair was
/// 50 million). With `max_pairs` > 0, throws StackTooLarge once one group has more stacked pairs
/// (a flat-folded Miura-ori of 10,000 faces lies in one stack of 48 million).
std::vector<std::vector<int>> stacksOf(const Paper& paper, double tolerance, bool unfolded_sheets, long max_pairs = 0)
{
  using Box = CGAL::Box_intersection_d::Box_with_handle_d<double, 3, const int*,
                                                          CGAL::Box_intersection_d::ID_FROM_HANDLE>;
  const int n = static_cast<int>(paper.faces.size());
  std::vector<int> parent(n);
  std::iota(parent.begin(), parent.end(), 0);
  const std::function<int(int)> root = [&](int f) { return parent[f] == f ? f : parent[f] = root(parent[f]); };
  std::vector<long> pairs_in(n, 0);  // stacked pairs found in each group, at its root
  std::vector<int> ids(n);
  std::iota(ids.begin(), ids.end(), 0);
  std::vector<Box> boxes;
  boxes.reserve(n);
  const double half = 0.5 * tolerance;  // boxes within the tolerance of each other meet
  for (int f = 0; f < n; ++f)
  {
    CGAL::Bbox_3 bounds;
    for (int v : paper.faces[f].vertices)
    {
      const Vec3& p = paper.vertices[v].folded;
      bounds += CGAL::Bbox_3(p.x() - half, p.y() - half, p.z() - half, p.x() + half, p.y() + half, p.z() + half);
    }
    boxes.emplace_back(bounds, &ids[f]);
  }
  // The stacked pairs, each group's count kept as they are found (a union-find of its own).
  std::vector<std::pair<int, int>> stacked_pairs;
  std::vector<int> group(n);
  std::iota(group.begin(), group.end(), 0);
  const std::function<int(int)> group_of_face = [&](int f) {
    return group[f] == f ? f : group[f] = group_of_face(group[f]);
  };
  CGAL::box_self_intersection_d(
      boxes.begin(), boxes.end(),
      [&](const Box& x, const Box& y) {
        const int f = std::min(*x.handle(), *y.handle()), g = std::max(*x.handle(), *y.handle());
        if (!facesStacked(paper, f, g, tolerance))
          return;
        stacked_pairs.emplace_back(f, g);
        const int a = group_of_face(f), b = group_of_face(g);
        if (a != b)
        {
          group[a] = b;
          pairs_in[b] += pairs_in[a];
        }
        if (max_pairs > 0 && ++pairs_in[b] > max_pairs)
          throw StackTooLarge{};
      },
      std::ptrdiff_t(10), CGAL::Box_intersection_d::CLOSED);
  // Joined in the order of the pairs (f, g), as every pair was once tried: the groups' roots,
  // and so the order their faces are searched in below, are the same whatever order the boxes
  // met in.
  std::sort(stacked_pairs.begin(), stacked_pairs.end());
  std::vector<char> stacked(n, 0);
  for (const auto& [f, g] : stacked_pairs)
  {
    parent[root(f)] = root(g);
    stacked[f] = stacked[g] = 1;
  }
  std::map<int, std::vector<int>> groups;
  for (int f = 0; f < n; ++f)
    if (stacked[f])
      groups[root(f)].push_back(f);
  // Faces flat across an unfolded crease are one sheet: the stacks on either side are ordered
  // together, each stack's faces kept together (its pairs searched in the order they were alone).
  std::map<int, int> group_of;  // a stacked face's group, by the group's place in `groups`
  std::vector<int> group_parent;
  for (auto& [r, faces] : groups)
  {
    for (int f : faces)
      group_of[f] = static_cast<int>(group_parent.size());
    group_parent.push_back(static_cast<int>(group_parent.size()));
  }
  const std::function<int(int)> group_root = [&](int g) {
    return group_parent[g] == g ? g : group_parent[g] = group_root(group_parent[g]);
  };
  for (const Edge& edge : paper.edges)
    if (unfolded_sheets && edge.isCrease() && std::abs(edge.fold_angle) <= kFlatAngleTolerance &&
        stacked[edge.faces[0]] && stacked[edge.faces[1]])
    {
      const int a = group_root(group_of[edge.faces[0]]), b = group_root(group_of[edge.faces[1]]);
      group_parent[std::max(a, b)] = std::min(a, b);
    }
  std::vector<std::vector<int>> stacks;
  std::map<int, size_t> stack_of_root;
  int g = 0;
  for (auto& [r, faces] : groups)
  {
    const int joined = group_root(g++);
    if (!stack_of_root.count(joined))
    {
      stack_of_root[joined] = stacks.size();
      stacks.emplace_back();
    }
    std::vector<int>& stack = stacks[stack_of_root[joined]];
    stack.insert(stack.end(), faces.begin(), faces.end());
  }
  return stacks;
}
}  // namespace

Expected<LayerOrder> solveLayerOrder(const Paper& paper, const LayerOrderOptions& options)
{
  LayerOrder result;
  std::vector<std::vector<int>> stacks;
  try
  {
    stacks = stacksOf(paper, options.tolerance, options.unfolded_sheets, options.max_pairs);
  }
  catch (const StackTooLarge&)
  {
    result.complete = false;
    result.incomplete = "a stack of more than the " + std::to_string(options.max_pairs) +
                        " overlapping pairs of faces whose layer order is worked out";
    return result;
  }
  for (const std::vector<int>& faces : stacks)
  {
    if (static_cast<int>(faces.size()) > options.max_faces)
    {
      result.complete = false;
      result.incomplete = "a stack of " + std::to_string(faces.size()) + " faces is more than the " +
                          std::to_string(options.max_faces) + " whose layer order is worked out";
      continue;
    }
    const StackProblem stack(paper, faces, options.tolerance);
    if (options.max_pairs > 0 && stack.variableCount() > options.max_pairs)
    {
      result.complete = false;
      result.incomplete = "a stack of " + std::to_string(stack.variableCount()) +
                          " overlapping pairs of faces is more than the " + std::to_string(options.max_pairs) +
                          " whose layer order is worked out";
      continue;
    }
    const std::vector<Clause> clauses = rulesOf(paper, stack, faces, options.kept, options.unfolded_sheets);
    Search search(stack.variableCount(), clauses);
    bool gave_up = false;
    if (const std::optional<std::string> conflict = search.solve(options.max_guesses, gave_up))
    {
      if (!gave_up)
        return Expected<LayerOrder>::failure("no order of the layers folds flat: " + *conflict);
      result.complete = false;
      result.incomplete = *conflict;
      continue;
    }
    for (size_t k = 0; k < stack.pairs().size(); ++k)
    {
      const auto [f, g] = stack.pairs()[k];
      const int g_higher = search.values()[k];  // +1: g above f along the stack's up
      result.orders.push_back({ f, g, g_higher * stack.facing(f) });
    }
    result.stacked_pairs += stack.variableCount();
  }
  return result;
}

std::string layerOrderViolation(const Paper& paper, const std::vector<FaceOrder>& orders, double tolerance,
                                bool unfolded_sheets)
{
  Paper ordered = paper;
  ordered.face_orders = orders;
  for (const std::vector<int>& faces : stacksOf(paper, tolerance, unfolded_sheets))
  {
    const StackProblem stack(paper, faces, tolerance);
    std::vector<int> value(stack.variableCount(), 0);
    for (size_t k = 0; k < stack.pairs().size(); ++k)
    {
      const auto [f, g] = stack.pairs()[k];
      const int above = faceOrder(ordered, f, g);
      if (above == 0)
        return "faces " + std::to_string(f) + " and " + std::to_string(g) + " lie on each other with no order recorded";
      value[k] = above * stack.facing(f);
    }
    for (const Clause& clause : rulesOf(paper, stack, faces, {}, unfolded_sheets))
    {
      const bool holds = std::any_of(clause.literals.begin(), clause.literals.end(), [&](int literal) {
        return (literal > 0 ? value[literal - 1] : -value[-literal - 1]) > 0;
      });
      if (!holds)
        return clause.why();
    }
  }
  return {};
}

}  // namespace virtual_origami::core

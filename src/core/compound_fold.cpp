#include "virtual_origami/core/compound_fold.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <set>

#include <Eigen/Geometry>

#include "virtual_origami/core/chosen_creases.h"
#include "virtual_origami/core/flat_vertices.h"
#include "virtual_origami/core/kinematics.h"
#include "virtual_origami/core/layer_pick.h"
#include "virtual_origami/core/layers.h"

namespace virtual_origami::core
{
namespace
{
/// How many ways of folding the creases of one vertex set are tried, at most: a press must
/// answer at once.
constexpr size_t kMaxAssignments = 20000;
/// Vertex sets with more creases than this are left out (2^n assignments).
constexpr size_t kMaxPool = 22;
/// Fold directions tried per outcome, at most (each a flat fold).
constexpr int kMaxDirections = 64;
/// Ways of the pressed point that pass the pointer within this of each other (of the paper's
/// scale) are alike: a hand does not draw straighter.
constexpr double kAlikeWays = 0.02;

bool isFolded(double angle)
{
  return std::abs(angle) > M_PI / 2;
}

/// The creases at each vertex, and whether it is inner (no sheet edge meets it).
struct Incidence
{
  std::vector<std::vector<int>> creases;
  std::vector<char> inner;
  explicit Incidence(const Paper& paper) : creases(paper.vertices.size()), inner(paper.vertices.size(), 1)
  {
    for (size_t e = 0; e < paper.edges.size(); ++e)
      for (int v : paper.edges[e].vertices)
      {
        if (paper.edges[e].isCrease())
          creases[v].push_back(static_cast<int>(e));
        else
          inner[v] = 0;
      }
  }
};

/// Kawasaki at an inner vertex for the creases folded (`folded(e)`): the angles between them,
/// taken alternately, sum to 180°.
bool foldsFlatAt(const Paper& paper, int v, const std::vector<int>& creases, const std::function<bool(int)>& folded)
{
  std::vector<double> directions;
  for (int e : creases)
    if (folded(e))
    {
      const Vec2 d = paper.vertices[paper.edges[e].otherVertex(v)].crease_pattern - paper.vertices[v].crease_pattern;
      directions.push_back(std::atan2(d.y(), d.x()));
    }
  if (directions.empty())
    return true;
  if (directions.size() % 2)
    return false;
  std::sort(directions.begin(), directions.end());
  double alternating = 0.0;
  for (size_t i = 0; i < directions.size(); ++i)
  {
    const double next = i + 1 < directions.size() ? directions[i + 1] : directions[0] + 2 * M_PI;
    alternating += (i % 2 ? -1.0 : 1.0) * (next - directions[i]);
  }
  return std::abs(alternating) < 1e-9;
}

Eigen::Isometry3d motionOf(const Paper& paper, const std::vector<Vec3>& after, int face)
{
  const std::vector<int>& vs = paper.faces[face].vertices;
  Eigen::Matrix3Xd from(3, vs.size()), to(3, vs.size());
  for (size_t i = 0; i < vs.size(); ++i)
  {
    from.col(static_cast<Eigen::Index>(i)) = paper.vertices[vs[i]].folded;
    to.col(static_cast<Eigen::Index>(i)) = after[vs[i]];
  }
  Eigen::Isometry3d motion;
  motion.matrix() = Eigen::umeyama(from, to, false);
  return motion;
}

/// How many of the faces a fold moved lie between faces it left in place (faces both above and
/// below them, as the layer order of `folded` stacks them): a reverse fold's tip turned in
/// between the layers has them, one wrapped round them has none.
int tuckedFaces(const Paper& folded, const FlatFoldResult& result)
{
  std::vector<char> moved(folded.faces.size(), 0), above(folded.faces.size(), 0), below(folded.faces.size(), 0);
  for (int f : result.moved_faces)
    moved[f] = 1;
  for (const FaceOrder& o : folded.face_orders)
  {
    if (o.face < 0 || o.other < 0 || o.above == 0 || moved[o.face] == moved[o.other])
      continue;
    // Whether `other` lies above `face` along +z.
    const bool other_above = (o.above > 0) == (folded.faceNormal(o.face).z() > 0);
    if (moved[o.face])
      (other_above ? above : below)[o.face] = 1;
    else
      (other_above ? below : above)[o.other] = 1;
  }
  int tucked = 0;
  for (int f : result.moved_faces)
    tucked += above[f] && below[f];
  return tucked;
}

/// Whether `other` lies above `face` along +z, by a face order of `paper`.
bool aboveAlongZ(const Paper& paper, const FaceOrder& o)
{
  return (o.above > 0) == (paper.faceNormal(o.face).z() > 0);
}

/// How many faces a fold moved lie under a face it left in place, seen from `side`: a flap
/// folded on the side it was pressed from stays on that side (seed 000: the pressed face leads).
int coveredFaces(const Paper& folded, const FlatFoldResult& result, const Vec3& side)
{
  std::vector<char> moved(folded.faces.size(), 0), covered(folded.faces.size(), 0);
  for (int f : result.moved_faces)
    moved[f] = 1;
  const bool up = side.z() > 0;
  for (const FaceOrder& o : folded.face_orders)
  {
    if (o.face < 0 || o.other < 0 || o.above == 0 || moved[o.face] == moved[o.other])
      continue;
    const bool other_above = aboveAlongZ(folded, o);
    if (moved[o.face] && other_above == up)
      covered[o.face] = 1;
    if (moved[o.other] && other_above != up)
      covered[o.other] = 1;
  }
  return static_cast<int>(std::count(covered.begin(), covered.end(), 1));
}

/// Whether `p` lies on the line through `a` and `b`.
bool onLine(const Vec3& a, const Vec3& b, const Vec3& p, double tolerance)
{
  const Vec3 d = (b - a).normalized();
  return ((p - a) - (p - a).dot(d) * d).norm() < tolerance;
}
}  // namespace

const char* compoundKindName(CompoundKind kind)
{
  switch (kind)
  {
    case CompoundKind::Squash:
      return "squash fold";
    case CompoundKind::Petal:
      return "petal fold";
    case CompoundKind::InsideReverse:
      return "inside reverse fold";
    case CompoundKind::OutsideReverse:
      return "outside reverse fold";
    case CompoundKind::Reverse:
      return "reverse fold";
    case CompoundKind::Fold:
      break;
  }
  return "fold";
}

Expected<CompoundFolds> CompoundFolds::at(const Paper& paper, int face, const Vec3& press, const Vec3& eye_side)
{
  using Failure = Expected<CompoundFolds>;
  if (face < 0 || face >= static_cast<int>(paper.faces.size()))
    return Failure::failure("press on the paper: on a flap to fold");
  if (!press.allFinite() || !eye_side.allFinite() || eye_side.norm() == 0.0)
    return Failure::failure("the press and the side it is seen from must be finite, the side not zero");
  for (const Edge& edge : paper.edges)
    if (edge.isCrease() && std::abs(edge.fold_angle) > kFlatAngleTolerance &&
        std::abs(std::abs(edge.fold_angle) - M_PI) > kFlatAngleTolerance)
      return Failure::failure("the paper does not lie flat: a flap is folded by dragging only on flat paper");
  CompoundFolds folds;
  folds.paper_ = paper;
  folds.face_ = face;
  folds.press_ = press;
  // The side the face was pressed from: the eye's, unless it is the bottom layer there.
  const Vec3 towards_eye = eye_side.normalized();
  const std::vector<int> under = facesUnder(paper, press, -towards_eye);
  folds.side_ = under.size() > 1 && under.back() == face ? -towards_eye : towards_eye;
  const double tolerance = 1e-7 * paper.scale();
  // The face that stays: the one farthest from the pressed face on the sheet (the bulk of the
  // model, away from the flap).
  const Vec2 pressed = creasePatternPoint(paper, face);
  double farthest = -1.0;
  for (size_t f = 0; f < paper.faces.size(); ++f)
  {
    const double d = (creasePatternPoint(paper, static_cast<int>(f)) - pressed).norm();
    if (d > farthest)
    {
      farthest = d;
      folds.fixed_face_ = static_cast<int>(f);
    }
  }
  const Incidence incidence(paper);
  std::vector<char> folded_now(paper.edges.size(), 0);
  for (size_t e = 0; e < paper.edges.size(); ++e)
    folded_now[e] = isFolded(paper.edges[e].fold_angle);
  const Eigen::Isometry3d root_pose = facePose(paper, folds.fixed_face_);
  std::set<std::vector<std::pair<int, char>>> seen;

  // Every way of folding or unfolding the creases at `vertices` (and `line_creases`) that folds
  // flat at each inner vertex and closes over the whole paper, and that moves the pressed face.
  const auto tryVertexSet = [&](const std::vector<int>& vertices, const std::vector<int>& line_creases, bool from_line,
                                bool patch) {
    std::vector<int> pool = line_creases;
    for (int v : vertices)
      for (int e : incidence.creases[v])
        if (std::find(pool.begin(), pool.end(), e) == pool.end())
          pool.push_back(e);
    if (pool.empty() || pool.size() > kMaxPool)
      return;
    std::sort(pool.begin(), pool.end());
    std::vector<int> position(paper.edges.size(), -1);
    for (size_t i = 0; i < pool.size(); ++i)
      position[pool[i]] = static_cast<int>(i);
    // Each inner vertex a pool crease meets is checked once its last pool crease is decided.
    std::vector<std::vector<int>> check_at(pool.size());
    std::set<int> touched;
    for (int e : pool)
      for (int v : paper.edges[e].vertices)
        if (incidence.inner[v])
          touched.insert(v);
    for (int v : touched)
    {
      int last = -1;
      for (int e : incidence.creases[v])
        last = std::max(last, position[e]);
      check_at[last].push_back(v);
    }
    std::vector<char> state(pool.size(), 0);
    const auto folded = [&](int e) { return position[e] >= 0 ? state[position[e]] != 0 : folded_now[e] != 0; };
    size_t assignments = 0;
    std::function<void(size_t)> assign = [&](size_t i) {
      if (assignments >= kMaxAssignments)
        return;
      if (i == pool.size())
      {
        ++assignments;
        std::vector<std::pair<int, char>> changes;
        bool on_line = line_creases.empty();
        for (size_t k = 0; k < pool.size(); ++k)
          if (state[k] != folded_now[pool[k]])
          {
            changes.emplace_back(pool[k], state[k]);
            on_line = on_line || std::find(line_creases.begin(), line_creases.end(), pool[k]) != line_creases.end();
          }
        if (changes.empty() || !on_line || !seen.insert(changes).second)
          return;
        std::vector<double> angles(paper.edges.size());
        for (size_t e = 0; e < paper.edges.size(); ++e)
          angles[e] = paper.edges[e].fold_angle;
        for (const auto& [e, f] : changes)
          angles[e] = f ? M_PI : 0.0;
        const Expected<std::vector<Vec3>> placed =
            foldedPositionsFromAngles(paper, angles, folds.fixed_face_, root_pose, tolerance);
        if (!placed)
          return;
        const Vec3 landing = motionOf(paper, *placed, face) * press;
        if ((landing - press).norm() < 1e-6 * paper.scale())
          return;
        CompoundOutcome outcome;
        for (const auto& [e, f] : changes)
        {
          outcome.edges.push_back(e);
          outcome.folded.push_back(f);
        }
        outcome.landing = landing;
        for (size_t v = 0; v < paper.vertices.size(); ++v)
          outcome.disturbance += ((*placed)[v] - paper.vertices[v].folded).norm();
        outcome.line_creases = line_creases;
        outcome.from_line = from_line;
        outcome.patch = patch;
        folds.outcomes_.push_back(std::move(outcome));
        return;
      }
      for (char s : { folded_now[pool[i]], static_cast<char>(!folded_now[pool[i]]) })
      {
        state[i] = s;
        bool flat = true;
        for (int v : check_at[i])
          flat = flat && foldsFlatAt(paper, v, incidence.creases[v], folded);
        if (flat)
          assign(i + 1);
      }
    };
    assign(0);
  };

  const std::vector<int>& corners = paper.faces[face].vertices;
  // A squash: the creases at one corner of the pressed face.
  for (int v : corners)
    if (incidence.inner[v])
      tryVertexSet({ v }, {}, false, false);
  // Along a line through an edge of the pressed face: the creases on it, and those meeting it,
  // in the part of the paper the line cuts off with the face (a reverse fold) or in the face's
  // layer (a petal fold).
  for (int edge : paper.faces[face].edges)
  {
    if (!paper.edges[edge].isCrease())
      continue;
    const Vec3 a = paper.vertices[paper.edges[edge].vertices[0]].folded;
    const Vec3 b = paper.vertices[paper.edges[edge].vertices[1]].folded;
    const auto lies = [&](int e) {
      return onLine(a, b, paper.vertices[paper.edges[e].vertices[0]].folded, tolerance) &&
             onLine(a, b, paper.vertices[paper.edges[e].vertices[1]].folded, tolerance);
    };
    for (const bool patch : { false, true })
    {
      const std::vector<char> reached =
          walkFaces(paper, face, {}, [&](int e) { return !lies(e) && (!patch || !folded_now[e]); });
      std::set<int> vertices;
      std::vector<int> line_creases;
      for (size_t f = 0; f < paper.faces.size(); ++f)
        if (reached[f])
          for (size_t i = 0; i < paper.faces[f].edges.size(); ++i)
          {
            const int e = paper.faces[f].edges[i];
            if (!paper.edges[e].isCrease() || !lies(e))
              continue;
            if (std::find(line_creases.begin(), line_creases.end(), e) == line_creases.end())
              line_creases.push_back(e);
            for (int v : paper.edges[e].vertices)
              if (incidence.inner[v])
                vertices.insert(v);
          }
      if (reached[folds.fixed_face_] && !patch)
        continue;  // the line cuts nothing off
      tryVertexSet(std::vector<int>(vertices.begin(), vertices.end()), line_creases, true, patch);
    }
  }
  folds.resolved_.resize(folds.outcomes_.size());
  return folds;
}

std::optional<CompoundFolds::Choice> CompoundFolds::nearest(const Vec3& pointer) const
{
  // The fold whose way (the pressed point's, from the press to its landing) the pointer is on:
  // a drag shows one fold all the way, not each fold landing near the pointer on the way.
  // Of folds whose ways pass alike, the one landing nearest the pointer; of those landing at
  // the same place, the one that moves the rest of the paper least.
  const double alike = kAlikeWays * paper_.scale(), same = 1e-9 * paper_.scale();
  std::optional<Choice> best;
  double best_off = 0.0;
  for (size_t i = 0; i < outcomes_.size(); ++i)
  {
    const CompoundOutcome& o = outcomes_[i];
    if (resolved_[i] && !resolved_[i]->ok())
      continue;  // no fold directions make it
    const Vec3 way = o.landing - press_;
    const double fraction = std::clamp((pointer - press_).dot(way) / way.squaredNorm(), 0.0, 1.0);
    const double off = (press_ + fraction * way - pointer).norm();
    const double miss = (o.landing - pointer).norm();
    if (best)
    {
      const CompoundOutcome& b = outcomes_[best->outcome];
      const bool better =
          off < best_off - alike ||
          (off <= best_off + alike &&
           (miss < best->miss - same || (miss <= best->miss + same && o.disturbance < b.disturbance - same)));
      if (!better)
        continue;
    }
    best = Choice{ i, fraction, miss };
    best_off = off;
  }
  return best;
}

Expected<CompoundFolds::Resolved> CompoundFolds::resolve(size_t index)
{
  using Failure = Expected<Resolved>;
  if (index >= outcomes_.size())
    return Failure::failure("no such fold");
  if (resolved_[index])
    return *resolved_[index];
  const CompoundOutcome& outcome = outcomes_[index];
  const Incidence incidence(paper_);
  // The directions of the creases it folds: every inner vertex with mountains and valleys
  // differing by two (Maekawa), then the fold itself decides (big-little-big, the layers).
  std::vector<double> angles(paper_.edges.size());
  for (size_t e = 0; e < paper_.edges.size(); ++e)
    angles[e] = paper_.edges[e].fold_angle;
  std::vector<int> choose;
  for (size_t k = 0; k < outcome.edges.size(); ++k)
  {
    angles[outcome.edges[k]] = outcome.folded[k] ? M_PI : 0.0;
    if (outcome.folded[k])
      choose.push_back(outcome.edges[k]);
  }
  const auto maekawa = [&](int v) {
    if (!incidence.inner[v])
      return true;
    int valleys = 0, mountains = 0;
    for (int e : incidence.creases[v])
      if (isFolded(angles[e]))
        (angles[e] > 0 ? valleys : mountains)++;
    return valleys + mountains == 0 || std::abs(valleys - mountains) == 2;
  };
  std::vector<std::vector<int>> check_at(choose.size());
  for (size_t i = 0; i < choose.size(); ++i)
    for (int v : paper_.edges[choose[i]].vertices)
    {
      size_t last = i;
      for (int e : incidence.creases[v])
      {
        const auto it = std::find(choose.begin(), choose.end(), e);
        if (it != choose.end())
          last = std::max(last, static_cast<size_t>(it - choose.begin()));
      }
      if (last == i)
        check_at[i].push_back(v);
    }
  struct Valid
  {
    FlatFoldRequest request;
    int tucked = 0;
    int covered = 0;
  };
  std::vector<Valid> valid;
  int tried = 0;
  std::string last_refusal = "no fold directions fold flat";
  const Vec2 fixed_point = creasePatternPoint(paper_, fixed_face_);
  std::function<void(size_t)> direct = [&](size_t i) {
    if (tried >= kMaxDirections)
      return;
    if (i == choose.size())
    {
      ++tried;
      FlatFoldRequest request;
      request.fixed_point = fixed_point;
      for (int e : outcome.edges)
      {
        const Edge& edge = paper_.edges[e];
        request.creases.push_back(CreaseLineAngle{ paper_.vertices[edge.vertices[0]].crease_pattern,
                                                   paper_.vertices[edge.vertices[1]].crease_pattern, angles[e] });
      }
      Paper folded = paper_;
      const Expected<FlatFoldResult> result = flatFold(folded, request);
      if (!result)
      {
        last_refusal = result.message();
        return;
      }
      valid.push_back(Valid{ std::move(request), tuckedFaces(folded, *result), coveredFaces(folded, *result, side_) });
      return;
    }
    for (const double sign : { 1.0, -1.0 })
    {
      angles[choose[i]] = sign * M_PI;
      bool ok = true;
      for (int v : check_at[i])
        ok = ok && maekawa(v);
      if (ok)
        direct(i + 1);
    }
  };
  direct(0);
  if (valid.empty())
  {
    resolved_[index] = Failure::failure(last_refusal);
    return *resolved_[index];
  }
  // Along a line cutting a flap off: a reverse fold, its tip turned in between the layers
  // (the most faces tucked) unless the user asks otherwise.
  // Otherwise the flap stays on the side it was pressed from; a squash folds its new creases
  // one way (the flap's sides both under it).
  const auto oneWay = [](const FlatFoldRequest& request) {
    int valleys = 0, mountains = 0;
    for (const CreaseLineAngle& line : request.creases)
    {
      valleys += line.angle > M_PI / 2;
      mountains += line.angle < -M_PI / 2;
    }
    return valleys == 0 || mountains == 0;
  };
  const auto better = [&](const Valid& a, const Valid& b) {
    if (outcome.from_line && !outcome.patch && a.tucked != b.tucked)
      return a.tucked > b.tucked;
    if (!outcome.from_line && oneWay(a.request) != oneWay(b.request))
      return oneWay(a.request);
    return a.covered < b.covered;
  };
  const Valid* chosen = &valid.front();
  for (const Valid& v : valid)
    if (better(v, *chosen))
      chosen = &v;
  CompoundKind kind = CompoundKind::Squash;
  if (outcome.from_line)
    kind = outcome.patch      ? CompoundKind::Petal :
           chosen->tucked > 0 ? CompoundKind::InsideReverse :
                                CompoundKind::Reverse;
  Resolved resolved{ chosen->request, kind, std::nullopt };
  if (kind == CompoundKind::InsideReverse)
  {
    // The other way round: the tip wrapped round the layers, none of it between them.
    for (const Valid& v : valid)
      if (v.tucked == 0 && (!resolved.outside || v.covered < chosen->covered))
        resolved.outside = v.request;
  }
  resolved_[index] = resolved;
  return resolved;
}

std::optional<std::pair<CompoundFolds::Choice, CompoundFolds::Resolved>>
CompoundFolds::nearestResolved(const Vec3& pointer)
{
  for (std::optional<Choice> choice = nearest(pointer); choice; choice = nearest(pointer))
  {
    const Expected<Resolved> resolved = resolve(choice->outcome);
    if (resolved)
      return std::make_pair(*choice, *resolved);
  }
  return std::nullopt;
}

}  // namespace virtual_origami::core

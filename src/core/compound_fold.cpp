#include "virtual_origami/core/compound_fold.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <functional>
#include <map>
#include <numeric>
#include <optional>
#include <set>
#include <thread>

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
/// How many ways of folding the creases of one vertex set are tried, at most (each checked whole,
/// or dropped with the ways it begins at a vertex that cannot fold flat): a press must answer at
/// once.
constexpr size_t kMaxAssignments = 20000;
/// Faces moved, summed over the folds tried, at most per press (each fold tried moves the parts
/// of the paper its creases part, counted as every face): a press on a large crease pattern
/// answers within a second or so.
constexpr size_t kMaxFacesPlaced = 2000000;
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

/// Whether `other` lies above `face` along +z, by a face order of `paper`.
bool aboveAlongZ(const Paper& paper, const FaceOrder& o)
{
  return (o.above > 0) == (paper.faceNormal(o.face).z() > 0);
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
    const bool other_above = aboveAlongZ(folded, o);
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

/// The face farthest from `face` on the sheet: the one that stays (the bulk of the model, away
/// from the flap).
int farthestFace(const Paper& paper, int face)
{
  const Vec2 pressed = creasePatternPoint(paper, face);
  int farthest = face;
  double distance = -1.0;
  for (size_t f = 0; f < paper.faces.size(); ++f)
  {
    const double d = (creasePatternPoint(paper, static_cast<int>(f)) - pressed).norm();
    if (d > distance)
    {
      distance = d;
      farthest = static_cast<int>(f);
    }
  }
  return farthest;
}

/// The search for the flat folds of a pressed face: every way of folding or unfolding a set of
/// creases that folds flat at each inner vertex it changes (Kawasaki), closes over the whole paper
/// and moves the pressed face.
class OutcomeSearch
{
public:
  OutcomeSearch(const Paper& paper, int face, const Vec3& press, int fixed_face)
    : paper_(paper)
    , face_(face)
    , fixed_face_(fixed_face)
    , press_(press)
    , incidence_(paper)
    , folded_now_(paper.edges.size(), 0)
    , directions_(paper.vertices.size())
    , vertex_face_(paper.vertices.size(), 0)
    , turns_(paper.edges.size())
    , part_(paper.faces.size(), 0)
    , tolerance_(1e-7 * paper.scale())
  {
    for (size_t e = 0; e < paper.edges.size(); ++e)
      folded_now_[e] = isFolded(paper.edges[e].fold_angle);
    for (size_t v = 0; v < paper.vertices.size(); ++v)
      if (incidence_.inner[v])
      {
        for (int e : incidence_.creases[v])
        {
          const Vec2 d = paper.vertices[paper.edges[e].otherVertex(static_cast<int>(v))].crease_pattern -
                         paper.vertices[v].crease_pattern;
          directions_[v].emplace_back(std::atan2(d.y(), d.x()), e);
        }
        std::sort(directions_[v].begin(), directions_[v].end());
      }
    for (size_t f = 0; f < paper.faces.size(); ++f)
    {
      poses_.push_back(facePose(paper, static_cast<int>(f)));
      for (int v : paper.faces[f].vertices)
        vertex_face_[v] = static_cast<int>(f);
    }
    // The turn of a crease's second face relative to its first, in the paper's frame, when the
    // crease is unfolded (0) or folded flat (1) from its angle now.
    for (size_t e = 0; e < paper.edges.size(); ++e)
      if (paper.edges[e].isCrease())
      {
        const int f = paper.edges[e].faces[0], i = static_cast<int>(e);
        const Eigen::Isometry3d now = hingeTransform(paper, i, f, paper.edges[e].fold_angle).inverse();
        for (const int folded : { 0, 1 })
          turns_[e][folded] = poses_[f] * hingeTransform(paper, i, f, folded ? M_PI : 0.0) * now * poses_[f].inverse();
      }
  }

  bool inner(int v) const
  {
    return incidence_.inner[v] != 0;
  }

  /// The creases on the line through `edge` (as folded) and those meeting them at inner
  /// vertices, in the part of the paper the line cuts off with the pressed face or (`patch`) in
  /// the pressed face's layer: the faces reached from it without crossing the line or a folded
  /// crease.
  void foldAlong(int edge, bool patch)
  {
    const Vec3 a = paper_.vertices[paper_.edges[edge].vertices[0]].folded;
    const Vec3 b = paper_.vertices[paper_.edges[edge].vertices[1]].folded;
    const auto lies = [&](int e) {
      return onLine(a, b, paper_.vertices[paper_.edges[e].vertices[0]].folded, tolerance_) &&
             onLine(a, b, paper_.vertices[paper_.edges[e].vertices[1]].folded, tolerance_);
    };
    const std::vector<char> reached =
        walkFaces(paper_, face_, {}, [&](int e) { return !lies(e) && (!patch || !folded_now_[e]); });
    if (reached[fixed_face_] && !patch)
      return;  // the line cuts nothing off
    std::set<int> vertices;
    std::vector<int> line_creases;
    for (size_t f = 0; f < paper_.faces.size(); ++f)
      if (reached[f])
        for (int e : paper_.faces[f].edges)
        {
          if (!paper_.edges[e].isCrease() || !lies(e))
            continue;
          if (std::find(line_creases.begin(), line_creases.end(), e) == line_creases.end())
            line_creases.push_back(e);
          for (int v : paper_.edges[e].vertices)
            if (inner(v))
              vertices.insert(v);
        }
    foldCreasesAt(std::vector<int>(vertices.begin(), vertices.end()), line_creases, true, patch);
  }

  /// Every way of folding the creases at `vertices` and `line_creases` (at least one of those
  /// changing, when given) into `outcomes`: the ways changing one crease first, then two, and so
  /// on, so that the folds a hand makes (a few creases at a corner) are found before the cap on
  /// the ways tried, also at a vertex where many creases meet (a frog base's centre has 16).
  void foldCreasesAt(const std::vector<int>& vertices, const std::vector<int>& line_creases, bool from_line, bool patch)
  {
    pool_ = line_creases;
    for (int v : vertices)
      for (int e : incidence_.creases[v])
        if (std::find(pool_.begin(), pool_.end(), e) == pool_.end())
          pool_.push_back(e);
    if (pool_.empty() || pool_.size() > kMaxPool)
      return;
    std::sort(pool_.begin(), pool_.end());
    position_.assign(paper_.edges.size(), -1);
    for (size_t i = 0; i < pool_.size(); ++i)
      position_[pool_[i]] = static_cast<int>(i);
    line_creases_ = line_creases;
    from_line_ = from_line;
    patch_ = patch;
    state_.resize(pool_.size());
    for (size_t i = 0; i < pool_.size(); ++i)
      state_[i] = folded_now_[pool_[i]];
    // Each inner vertex is checked once its last crease in the pool is decided: a way failing
    // Kawasaki there is dropped with every way it begins (a petal fold changes 8 of 18 creases).
    check_at_.assign(pool_.size(), {});
    for (size_t i = 0; i < pool_.size(); ++i)
      for (int v : paper_.edges[pool_[i]].vertices)
        if (inner(v) && lastInPool(v) == static_cast<int>(i))
          check_at_[i].push_back(v);
    assignments_ = 0;
    for (size_t changes = 1; changes <= pool_.size(); ++changes)
      change(0, changes);
  }

  std::vector<CompoundOutcome> outcomes;

private:
  bool folded(int e) const
  {
    return position_[e] >= 0 ? state_[position_[e]] != 0 : folded_now_[e] != 0;
  }

  bool capped() const
  {
    return assignments_ >= kMaxAssignments || faces_placed_ >= kMaxFacesPlaced;
  }

  /// The last position in the pool of a crease at `v`.
  int lastInPool(int v) const
  {
    int last = -1;
    for (int e : incidence_.creases[v])
      last = std::max(last, position_[e]);
    return last;
  }

  /// Whether the vertices whose creases are all decided once the `i`-th is fold flat (Kawasaki)
  /// where a crease of theirs changes.
  bool decidedFoldFlat(size_t i) const
  {
    for (int v : check_at_[i])
      for (int e : incidence_.creases[v])
        if (folded(e) != (folded_now_[e] != 0))
        {
          if (!kawasaki(v))
            return false;
          break;
        }
    return true;
  }

  /// Every way of changing `left` more pool creases from the `i`-th on (in the order of the
  /// changed creases' positions: the first changing first).
  void change(size_t i, size_t left)
  {
    if (capped())
      return;
    if (left == 0)
    {
      ++assignments_;
      if (foldsFlat())
        record();
      return;
    }
    if (i + left > pool_.size())
      return;
    state_[i] = !folded_now_[pool_[i]];
    if (decidedFoldFlat(i))
      change(i + 1, left - 1);
    else
      ++assignments_;
    state_[i] = folded_now_[pool_[i]];
    if (i + left < pool_.size())
    {
      if (decidedFoldFlat(i))
        change(i + 1, left);
      else
        ++assignments_;
    }
  }

  /// Kawasaki at every inner vertex a changed crease meets (the others lie flat as before).
  bool foldsFlat()
  {
    checked_.clear();
    for (size_t k = 0; k < pool_.size(); ++k)
      if (state_[k] != folded_now_[pool_[k]])
        for (int v : paper_.edges[pool_[k]].vertices)
          if (inner(v) && std::find(checked_.begin(), checked_.end(), v) == checked_.end())
          {
            if (!kawasaki(v))
              return false;
            checked_.push_back(v);
          }
    return true;
  }

  /// Kawasaki at `v` for the creases as decided: the angles between the folded creases, taken
  /// alternately, sum to 180° (their directions sorted once, at the start).
  bool kawasaki(int v) const
  {
    double alternating = 0.0, first = 0.0, last = 0.0;
    int count = 0;
    for (const auto& [direction, e] : directions_[v])
      if (folded(e))
      {
        if (count == 0)
          first = direction;
        else
          alternating += (count % 2 ? 1.0 : -1.0) * (direction - last);
        last = direction;
        ++count;
      }
    if (count == 0)
      return true;
    if (count % 2)
      return false;
    alternating -= first + 2 * M_PI - last;  // the angle closing the turn, taken with the even ones
    return std::abs(alternating) < 1e-9;
  }

  /// How the changes move the paper: the parts the changed creases divide it into (`part_`, by
  /// the faces joined across unchanged creases) each move rigidly, the fixed face's part stays,
  /// and across a changed crease the next part turns about it by the change of its angle (its
  /// faces as they lie now). Per part its motion, or none when the parts' motions disagree (the
  /// changed angles do not close) or a part is not reached. Faster than placing every face
  /// anew from the crease pattern, which a press would do for each of thousands of ways.
  std::optional<std::vector<Eigen::Isometry3d>> partMotions(const std::vector<std::pair<int, char>>& changes)
  {
    std::iota(part_.begin(), part_.end(), 0);
    const std::function<int(int)> root = [&](int f) { return part_[f] == f ? f : part_[f] = root(part_[f]); };
    for (size_t e = 0; e < paper_.edges.size(); ++e)
      if (paper_.edges[e].isCrease() && (position_[e] < 0 || state_[position_[e]] == folded_now_[e]))
        part_[root(paper_.edges[e].faces[0])] = root(paper_.edges[e].faces[1]);
    for (size_t f = 0; f < part_.size(); ++f)
      part_[f] = root(static_cast<int>(f));
    std::vector<Eigen::Isometry3d> motion(paper_.faces.size());
    std::vector<char> known(paper_.faces.size(), 0);
    motion[part_[fixed_face_]] = Eigen::Isometry3d::Identity();
    known[part_[fixed_face_]] = 1;
    for (bool progress = true; progress;)
    {
      progress = false;
      for (const auto& [e, folded] : changes)
      {
        const int f = paper_.edges[e].faces[0], g = paper_.edges[e].faces[1];
        const int a = part_[f], b = part_[g];
        if (known[a] == known[b] && !known[a])
          continue;
        const Eigen::Isometry3d& turn = turns_[e][folded ? 1 : 0];
        if (!known[b])
        {
          motion[b] = motion[a] * turn;
          known[b] = 1;
          progress = true;
        }
        else if (!known[a])
        {
          motion[a] = motion[b] * turn.inverse();
          known[a] = 1;
          progress = true;
        }
        else
          for (int v : paper_.faces[g].vertices)
            if ((motion[b] * paper_.vertices[v].folded - motion[a] * turn * paper_.vertices[v].folded).norm() >
                tolerance_)
              return std::nullopt;
      }
    }
    for (size_t f = 0; f < part_.size(); ++f)
      if (!known[part_[f]])
        return std::nullopt;
    return motion;
  }

  /// The outcome of the creases as decided, when it changes something new, closes and moves
  /// the pressed face.
  void record()
  {
    std::vector<std::pair<int, char>> changes;
    bool on_line = line_creases_.empty();
    for (size_t k = 0; k < pool_.size(); ++k)
      if (state_[k] != folded_now_[pool_[k]])
      {
        changes.emplace_back(pool_[k], state_[k]);
        on_line = on_line || std::count(line_creases_.begin(), line_creases_.end(), pool_[k]) > 0;
      }
    if (changes.empty() || !on_line || !seen_.insert(changes).second)
      return;
    faces_placed_ += paper_.faces.size();
    const std::optional<std::vector<Eigen::Isometry3d>> motions = partMotions(changes);
    if (!motions)
      return;
    const Vec3 landing = (*motions)[part_[face_]] * press_;
    if ((landing - press_).norm() < 1e-6 * paper_.scale())
      return;
    CompoundOutcome outcome;
    for (const auto& [e, f] : changes)
    {
      outcome.edges.push_back(e);
      outcome.folded.push_back(f);
    }
    outcome.landing = landing;
    for (size_t v = 0; v < paper_.vertices.size(); ++v)
    {
      const Vec3& at = paper_.vertices[v].folded;
      outcome.disturbance += ((*motions)[part_[vertex_face_[v]]] * at - at).norm();
    }
    outcome.line_creases = line_creases_;
    outcome.from_line = from_line_;
    outcome.patch = patch_;
    outcomes.push_back(std::move(outcome));
  }

  const Paper& paper_;
  const int face_, fixed_face_;
  const Vec3 press_;
  const Incidence incidence_;
  std::vector<char> folded_now_;
  std::vector<std::vector<std::pair<double, int>>> directions_;  // per inner vertex, its creases by direction
  std::vector<int> checked_;                                     // the vertices foldsFlat checked
  std::vector<std::vector<int>> check_at_;                       // per pool position, the vertices decided with it
  std::vector<Eigen::Isometry3d> poses_;                         // each face's pose as it lies now
  std::vector<int> vertex_face_;                                 // a face of each vertex
  std::vector<std::array<Eigen::Isometry3d, 2>> turns_;          // per crease, unfolded and folded
  std::vector<int> part_;                                        // per face, the part it moves with (partMotions)
  const double tolerance_;
  std::set<std::vector<std::pair<int, char>>> seen_;  // the change sets recorded
  // The crease set being decided.
  std::vector<int> pool_, position_, line_creases_;
  std::vector<char> state_;
  bool from_line_ = false, patch_ = false;
  size_t assignments_ = 0;
  size_t faces_placed_ = 0;  // over the whole press
};

/// A choice of fold directions for an outcome that folds flat, and how its layers stack.
struct Directed
{
  FlatFoldRequest request;
  int tucked = 0;   // tuckedFaces
  int covered = 0;  // coveredFaces
};

/// Every choice of directions for the creases `outcome` folds (up to kMaxDirections) with which
/// every inner vertex has mountains and valleys differing by two (Maekawa) and the fold itself
/// succeeds (big-little-big, the layers); `refusal`: why the last one tried did not.
std::vector<Directed> foldDirections(const Paper& paper, const CompoundOutcome& outcome, const Vec2& fixed_point,
                                     const Vec3& side, std::string& refusal)
{
  const Incidence incidence(paper);
  std::vector<double> angles(paper.edges.size());
  for (size_t e = 0; e < paper.edges.size(); ++e)
    angles[e] = paper.edges[e].fold_angle;
  std::vector<int> choose;  // the creases it folds, whose direction is chosen
  std::vector<char> changing(paper.edges.size(), 0);
  for (size_t k = 0; k < outcome.edges.size(); ++k)
  {
    angles[outcome.edges[k]] = outcome.folded[k] ? M_PI : 0.0;
    changing[outcome.edges[k]] = 1;
    if (outcome.folded[k])
      choose.push_back(outcome.edges[k]);
  }
  // A reverse fold that turns the tip in between the layers turns its spine inside out: the
  // folded creases of the part that turns, at the line's inner vertices, may fold either way.
  std::vector<int> reversible;
  if (outcome.from_line && !outcome.patch)
  {
    const std::vector<char> stays =
        walkFaces(paper, faceContaining(paper, fixed_point), {}, [&](int e) { return !changing[e]; });
    for (int e : outcome.edges)
      for (int v : paper.edges[e].vertices)
        if (incidence.inner[v])
          for (int c : incidence.creases[v])
            if (!changing[c] && isFolded(paper.edges[c].fold_angle) && !stays[paper.edges[c].faces[0]] &&
                !stays[paper.edges[c].faces[1]] &&
                std::find(reversible.begin(), reversible.end(), c) == reversible.end())
              reversible.push_back(c);
    choose.insert(choose.end(), reversible.begin(), reversible.end());
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
  // Each vertex is checked once the last of its creases to choose is chosen.
  std::vector<std::vector<int>> check_at(choose.size());
  for (size_t i = 0; i < choose.size(); ++i)
    for (int v : paper.edges[choose[i]].vertices)
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
  std::vector<FlatFoldRequest> requests;  // the ways every vertex's Maekawa count allows
  int tried = 0;
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
        const Edge& edge = paper.edges[e];
        request.creases.push_back(CreaseLineAngle{ paper.vertices[edge.vertices[0]].crease_pattern,
                                                   paper.vertices[edge.vertices[1]].crease_pattern, angles[e] });
      }
      for (int e : reversible)
        if (angles[e] != paper.edges[e].fold_angle)
        {
          const Edge& edge = paper.edges[e];
          request.creases.push_back(CreaseLineAngle{ paper.vertices[edge.vertices[0]].crease_pattern,
                                                     paper.vertices[edge.vertices[1]].crease_pattern, angles[e] });
        }
      requests.push_back(std::move(request));
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
  // Each way folded in full (its layers ordered), on two threads: the ways are independent and
  // flatFold only reads `paper`; a press resolving a reverse fold's ways took 24 ms on one.
  std::vector<std::optional<Directed>> folded_ways(requests.size());
  std::vector<std::string> refusals(requests.size());
  std::atomic<size_t> next{ 0 };
  const auto fold = [&] {
    for (size_t k = next++; k < requests.size(); k = next++)
    {
      Paper folded = paper;
      const Expected<FlatFoldResult> result = flatFold(folded, requests[k]);
      if (result)
        folded_ways[k] = Directed{ requests[k], tuckedFaces(folded, *result), coveredFaces(folded, *result, side) };
      else
        refusals[k] = result.message();
    }
  };
  if (requests.size() > 1)
  {
    std::thread other(fold);
    fold();
    other.join();
  }
  else
    fold();
  std::vector<Directed> valid;
  refusal = "no fold directions fold flat";
  for (size_t k = 0; k < requests.size(); ++k)
    if (folded_ways[k])
      valid.push_back(std::move(*folded_ways[k]));
    else
      refusal = refusals[k];  // the last way's refusal, as when they were folded in turn
  return valid;
}

/// Whether the creases a fold folds all fold the same way.
bool oneWay(const FlatFoldRequest& request)
{
  int valleys = 0, mountains = 0;
  for (const CreaseLineAngle& line : request.creases)
  {
    valleys += line.angle > M_PI / 2;
    mountains += line.angle < -M_PI / 2;
  }
  return valleys == 0 || mountains == 0;
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
  folds.fixed_face_ = farthestFace(paper, face);

  OutcomeSearch search(paper, face, press, folds.fixed_face_);
  // A squash: the creases at one corner of the pressed face.
  for (int v : paper.faces[face].vertices)
    if (search.inner(v))
      search.foldCreasesAt({ v }, {}, false, false);
  // Along a line through an edge of the pressed face: the creases on it, and those meeting it,
  // in the part of the paper the line cuts off with the face (a reverse fold) or in the face's
  // layer (a petal fold).
  for (int edge : paper.faces[face].edges)
    if (paper.edges[edge].isCrease())
      for (const bool patch : { false, true })
        search.foldAlong(edge, patch);
  folds.outcomes_ = std::move(search.outcomes);
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
  std::string refusal;
  const std::vector<Directed> valid =
      foldDirections(paper_, outcome, creasePatternPoint(paper_, fixed_face_), side_, refusal);
  if (valid.empty())
  {
    resolved_[index] = Failure::failure(refusal);
    return *resolved_[index];
  }
  const bool reverse = outcome.from_line && !outcome.patch;
  // A reverse fold turns the tip in between the layers (the most faces tucked); a squash keeps
  // the flap on the side it was pressed from (not wrapped round the other layers), then folds
  // its new creases one way (the flap's sides both under it); and the flap stays on the side it
  // was pressed from.
  const auto better = [&](const Directed& a, const Directed& b) {
    if (reverse && a.tucked != b.tucked)
      return a.tucked > b.tucked;
    if (!outcome.from_line && a.covered != b.covered)
      return a.covered < b.covered;
    if (!outcome.from_line && oneWay(a.request) != oneWay(b.request))
      return oneWay(a.request);
    return a.covered < b.covered;
  };
  const Directed* chosen = &valid.front();
  for (const Directed& d : valid)
    if (better(d, *chosen))
      chosen = &d;
  Resolved resolved{ chosen->request, CompoundKind::Squash, std::nullopt };
  if (outcome.from_line)
    resolved.kind = outcome.patch      ? CompoundKind::Petal :
                    chosen->tucked > 0 ? CompoundKind::InsideReverse :
                                         CompoundKind::Reverse;
  if (resolved.kind == CompoundKind::InsideReverse)
  {
    // The other way round: the tip wrapped round the layers, none of it between them.
    const Directed* outside = nullptr;
    for (const Directed& d : valid)
      if (d.tucked == 0 && (!outside || d.covered < outside->covered))
        outside = &d;
    if (outside)
      resolved.outside = outside->request;
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

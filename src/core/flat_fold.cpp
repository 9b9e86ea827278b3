#include "virtual_origami/core/flat_fold.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "virtual_origami/core/face_orders.h"
#include "virtual_origami/core/flat_sheet_orders.h"
#include "virtual_origami/core/flat_vertices.h"
#include "virtual_origami/core/kinematics.h"
#include "virtual_origami/core/layer_order.h"
#include "virtual_origami/core/planar_geometry.h"

namespace virtual_origami::core
{
namespace
{
bool insideFace(const Paper& paper, int face, const Vec2& p)
{
  const std::vector<int>& vs = paper.faces[face].vertices;
  for (size_t i = 0; i < vs.size(); ++i)
  {
    const Vec2& a = paper.vertices[vs[i]].crease_pattern;
    const Vec2& b = paper.vertices[vs[(i + 1) % vs.size()]].crease_pattern;
    const Vec2 ab = b - a, ap = p - a;
    if (cross2(ab, ap) < -1e-12)
      return false;
  }
  return true;
}
}  // namespace

int faceContaining(const Paper& paper, const Vec2& point)
{
  for (size_t f = 0; f < paper.faces.size(); ++f)
    if (insideFace(paper, static_cast<int>(f), point))
      return static_cast<int>(f);
  return -1;
}

namespace
{
/// What a request asks of this paper: every edge's angle after the fold, the face that stays.
struct FoldPlan
{
  std::vector<double> angles;
  int root = -1;
  std::vector<int> changed_edges;
};

Expected<FoldPlan> planFold(const Paper& paper, const FlatFoldRequest& request)
{
  using Failure = Expected<FoldPlan>;
  const double tolerance = 1e-9 * paper.scale();
  if (request.creases.empty())
    return Failure::failure("no creases are chosen: mark at least one crease to fold");
  if (!request.fixed_point.allFinite())
    return Failure::failure("the fixed point is not a finite point");
  FoldPlan plan;
  plan.angles.resize(paper.edges.size(), 0.0);
  for (size_t e = 0; e < paper.edges.size(); ++e)
    plan.angles[e] = paper.edges[e].fold_angle;
  for (size_t k = 0; k < request.creases.size(); ++k)
  {
    const CreaseLineAngle& line = request.creases[k];
    const std::string which = "crease line " + std::to_string(k + 1);
    if (!line.start.allFinite() || !line.end.allFinite() || !std::isfinite(line.angle))
      return Failure::failure(which + " has a non-finite value");
    if (std::abs(line.angle) > M_PI + 1e-12)
      return Failure::failure(which + ": a fold angle beyond ±180 degrees would pass the layers through each other");
    if ((line.end - line.start).norm() < tolerance)
      return Failure::failure(which + " has zero length");
    int found = 0;
    for (size_t e = 0; e < paper.edges.size(); ++e)
    {
      const Edge& edge = paper.edges[e];
      if (!edge.isCrease() ||
          pointSegmentDistance(paper.vertices[edge.vertices[0]].crease_pattern, line.start, line.end) > tolerance ||
          pointSegmentDistance(paper.vertices[edge.vertices[1]].crease_pattern, line.start, line.end) > tolerance)
        continue;
      ++found;
      if (plan.angles[e] != line.angle &&
          std::find(plan.changed_edges.begin(), plan.changed_edges.end(), static_cast<int>(e)) == plan.changed_edges.end())
        plan.changed_edges.push_back(static_cast<int>(e));
      plan.angles[e] = line.angle;
    }
    if (found == 0)
      return Failure::failure(which + " runs along no crease (crease it first)");
  }
  plan.root = faceContaining(paper, request.fixed_point);
  if (plan.root < 0)
    return Failure::failure("the fixed point lies off the sheet");
  return plan;
}

}  // namespace

namespace
{
/// The creases whose angle the fold changes on the way from the fixed face to each face (sorted):
/// faces with the same list turn together, those with an empty one stay.
std::vector<std::vector<int>> turnsFromFixedFace(const Paper& paper, const FoldPlan& plan)
{
  std::vector<std::vector<int>> turns(paper.faces.size());
  walkFaces(paper, plan.root, [&](int f, int e, int g) {
    turns[g] = turns[f];
    if (plan.angles[e] != paper.edges[e].fold_angle)
    {
      turns[g].insert(std::lower_bound(turns[g].begin(), turns[g].end(), e), e);
    }
  });
  return turns;
}

/// A layer order that also keeps every flat sheet whole across its unfolded creases
/// (flat_sheet_orders.h), which solveLayerOrder's rules do not say: each clash its order leaves
/// is settled one way, then the other, as a kept order, and the layers ordered again (at most
/// `tries` solves in all). Fails naming the clash when no settling clears it.
Expected<LayerOrder> solveKeepingSheetsWhole(const Paper& next, const LayerOrderOptions& options, int& tries)
{
  Expected<LayerOrder> order = solveLayerOrder(next, options);
  if (!order || !order->complete)
    return order;
  Paper ordered = next;
  ordered.face_orders = order->orders;
  const std::vector<SheetOrderClash> clashes = sheetOrderClashes(ordered, options.tolerance);
  if (clashes.empty())
    return order;
  const SheetOrderClash& clash = clashes.front();
  const int first = faceOrder(ordered, clash.face, clash.other);
  const int second = faceOrder(ordered, clash.face2, clash.other2);
  for (const FaceOrder& settle : { FaceOrder{ clash.face2, clash.other2, clash.relation * first },
                                   FaceOrder{ clash.face, clash.other, clash.relation * second } })
  {
    if (--tries < 0)
      break;
    LayerOrderOptions settled = options;
    settled.kept.push_back(settle);
    Expected<LayerOrder> again = solveKeepingSheetsWhole(next, settled, tries);
    if (again)
      return again;
  }
  return Expected<LayerOrder>::failure("no order of the layers folds flat: " + clash.message);
}

/// The layers the fold moves as one rigid piece: moved faces joined through creases it leaves as
/// they are, one id per piece (-1 for the faces that stay).
std::vector<int> rigidPieces(const Paper& paper, const std::vector<double>& angles, const std::vector<char>& moved)
{
  std::vector<int> piece(paper.faces.size(), -1);
  int pieces = 0;
  for (size_t start = 0; start < paper.faces.size(); ++start)
  {
    if (!moved[start] || piece[start] >= 0)
      continue;
    piece[start] = pieces;
    walkFaces(
        paper, static_cast<int>(start), [&](int, int, int g) { piece[g] = pieces; },
        [&](int e) {
          const Edge& edge = paper.edges[e];
          return angles[e] == edge.fold_angle && moved[edge.faces[0]] && moved[edge.faces[1]];
        });
    ++pieces;
  }
  return piece;
}

/// For each moved layer and each layer it lay on before and lies on after (not moving with it as
/// one piece, whose order holds anyway): the same side of it as before, along the fixed face's
/// normal. The creases alone leave open whether a reverse fold's tip goes in between the layers
/// or round them; the layers of the tip that lay on each other keep their sides, and so the tip
/// goes in between.
std::vector<FaceOrder> sidesAsBefore(const Paper& next, const Paper& before, const std::vector<char>& moved,
                                     const std::vector<int>& piece, int root, double tolerance)
{
  const Vec3 up = before.faceNormal(root);
  const auto along = [&](const Paper& paper, int face) { return paper.faceNormal(face).dot(up) > 0 ? 1 : -1; };
  std::vector<FaceOrder> sides;
  for (const FaceOrder& o : before.face_orders)
  {
    if (o.face < 0 || o.other < 0 || o.face >= static_cast<int>(moved.size()) ||
        o.other >= static_cast<int>(moved.size()) || o.above == 0 || (!moved[o.face] && !moved[o.other]) ||
        (piece[o.face] >= 0 && piece[o.face] == piece[o.other]) || !facesStacked(next, o.face, o.other, tolerance))
      continue;
    const int above_up = o.above * along(before, o.face);
    sides.push_back({ o.face, o.other, above_up * along(next, o.face) });
  }
  return sides;
}

/// The layer order after the fold: the orders of layers that turned together or as one piece
/// hold, the rest follow from the creases (layer_order.h) and no flat sheet changes sides of a
/// layer across an unfolded crease (flat_sheet_orders.h); of those orders, one that keeps the
/// moved layers' sides (sidesAsBefore) when there is one. Fails when no order of the layers folds
/// flat.
Status orderLayers(Paper& next, const Paper& before, const std::vector<std::vector<int>>& turns,
                   const std::vector<char>& moved, const std::vector<int>& piece, int root, double tolerance)
{
  LayerOrderOptions options;
  options.tolerance = tolerance;
  // The sheets' rules as the solver's own constraints: its first order then keeps them, where
  // settling clashes after it took hundreds of solves for a fold that has no such order (a flap
  // drag tries many: its longest update went from 19 to 350 ms).
  options.unfolded_sheets = true;
  for (const FaceOrder& o : before.face_orders)
    if (o.face >= 0 && o.other >= 0 && o.face < static_cast<int>(turns.size()) &&
        o.other < static_cast<int>(turns.size()) &&
        (turns[o.face] == turns[o.other] || (piece[o.face] >= 0 && piece[o.face] == piece[o.other])))
      options.kept.push_back(o);
  constexpr int kSheetTries = 256;
  int tries = kSheetTries;
  Expected<LayerOrder> order = Expected<LayerOrder>::failure("no order of the layers folds flat");
  if (const std::vector<FaceOrder> sides = sidesAsBefore(next, before, moved, piece, root, tolerance); !sides.empty())
  {
    LayerOrderOptions sided = options;
    sided.kept.insert(sided.kept.end(), sides.begin(), sides.end());
    order = solveKeepingSheetsWhole(next, sided, tries);
    tries = kSheetTries;
  }
  if (!order)
    order = solveKeepingSheetsWhole(next, options, tries);
  if (!order && !options.kept.empty())
  {
    // Orders recorded before may not have been complete or right: what the creases allow decides.
    options.kept.clear();
    tries = kSheetTries;
    order = solveKeepingSheetsWhole(next, options, tries);
  }
  if (!order)
    return failure(order.message());
  if (!order->complete)
  {
    // Too many layers to work out: keep the orders of layers that turned together, as a turn does.
    clearFaceOrdersAcross(next, moved);
    pruneFaceOrders(next, tolerance);
    return success();
  }
  next.face_orders = order->orders;
  return success();
}

/// Each face's rigid motion from where it lies now to `fraction` of the way through the fold:
/// every crease's angle `fraction` of the way to the plan's (`shortest`: the way round that turns
/// it less, which ends where the other does, −180° to 90° by −90°, not by 270°: a flap turned
/// about one hinge turns by one angle, whatever the creases' angles were), the faces placed by the
/// turns along the walk from the fixed face (which does not move); `depth`: creases crossed from
/// it.
struct FaceMotions
{
  std::vector<Eigen::Isometry3d> motion;
  std::vector<int> depth;
};

FaceMotions faceMotions(const Paper& paper, const FoldPlan& plan, double fraction, bool shortest = false)
{
  const size_t faces = paper.faces.size(), edges = paper.edges.size();
  std::vector<double> now(edges), then(edges);
  for (size_t e = 0; e < edges; ++e)
  {
    now[e] = paper.edges[e].fold_angle;
    double change = plan.angles[e] - now[e];
    if (shortest)
      change = std::remainder(change, 2 * M_PI);
    then[e] = now[e] + fraction * change;
  }
  const int root = plan.root;
  const Eigen::Isometry3d root_pose = facePose(paper, root);
  std::vector<Eigen::Isometry3d> pose0(faces, root_pose), pose_t(faces, root_pose);
  FaceMotions out{ std::vector<Eigen::Isometry3d>(faces, Eigen::Isometry3d::Identity()), std::vector<int>(faces, -1) };
  out.depth[root] = 0;
  walkFaces(paper, root, [&](int f, int e, int g) {
    pose0[g] = pose0[f] * hingeTransform(paper, e, f, now[e]);
    pose_t[g] = pose_t[f] * hingeTransform(paper, e, f, then[e]);
    out.depth[g] = out.depth[f] + 1;
  });
  for (size_t f = 0; f < faces; ++f)
    if (static_cast<int>(f) != root)
      out.motion[f] = pose_t[f] * pose0[f].inverse();
  return out;
}

/// Whether the creases the fold changes lie on one line of the folded paper: a hinge the moving
/// layers turn about together (a flap to a right angle), where the fold's path is a turn.
bool onOneHinge(const Paper& paper, const FoldPlan& plan, double tolerance)
{
  if (plan.changed_edges.empty())
    return false;
  const Edge& first = paper.edges[plan.changed_edges.front()];
  const Vec3 a = paper.vertices[first.vertices[0]].folded, b = paper.vertices[first.vertices[1]].folded;
  const Vec3 d = (b - a).normalized();
  for (int e : plan.changed_edges)
    for (int v : paper.edges[e].vertices)
    {
      const Vec3 r = paper.vertices[v].folded - a;
      if ((r - r.dot(d) * d).norm() > tolerance)
        return false;
    }
  return true;
}

/// Paper cannot pass through paper: a face the fold turns about one hinge may not set off
/// through a layer that stays, stacked on it (its recorded order says which side that layer is
/// on). The turning face's first motion (a millionth of the fold) must not go towards it. Names
/// the two faces, where they lie on the sheet, when it does. A fold of creases on several lines at
/// once (a squash, a petal fold) is no turn in between (flatFoldFrame); its layers are the layer
/// order's to check (orderLayers).
Status checkNoLayerPassedThrough(const Paper& paper, const FoldPlan& plan, const std::vector<char>& moved)
{
  const double tolerance = 1e-7 * paper.scale();
  if (!onOneHinge(paper, plan, tolerance))
    return success();
  const FaceMotions start = faceMotions(paper, plan, 1e-6, true);
  for (const FaceOrder& o : paper.face_orders)
    for (const auto& [m, s] : { std::pair{ o.face, o.other }, std::pair{ o.other, o.face } })
    {
      if (m < 0 || s < 0 || m >= static_cast<int>(moved.size()) || s >= static_cast<int>(moved.size()) || !moved[m] ||
          moved[s] || !facesStacked(paper, m, s, tolerance))
        continue;
      const int side = faceOrder(paper, m, s);  // where s lies from m, along m's front normal
      if (side == 0)
        continue;
      const Vec3 towards = side * paper.faceNormal(m);
      double moves = 0.0, most = -INFINITY, least = INFINITY;
      std::vector<Vec3> points{ paper.faceCentroid(m) };
      for (int v : paper.faces[m].vertices)
        points.push_back(paper.vertices[v].folded);
      for (const Vec3& p : points)
      {
        const Vec3 d = start.motion[m] * p - p;
        moves = std::max(moves, d.norm());
        most = std::max(most, towards.dot(d));
        least = std::min(least, towards.dot(d));
      }
      if (moves > 0.0 && most > 1e-3 * moves && least > -1e-6 * moves)
      {
        const auto at = [&](int f) {
          Vec2 cp = Vec2::Zero();
          for (int v : paper.faces[f].vertices)
            cp += paper.vertices[v].crease_pattern;
          cp /= static_cast<double>(paper.faces[f].vertices.size());
          std::ostringstream text;
          text.precision(2);
          text << "face " << f << " (about (" << cp.x() << ", " << cp.y() << ") on the sheet)";
          return text.str();
        };
        return failure("the fold would pass " + at(m) + " through " + at(s) +
                       ", which lies on it and stays: paper cannot go through paper; fold the layers in "
                       "its way first, or the other way");
      }
    }
  return success();
}
}  // namespace

Expected<FlatFoldResult> flatFold(Paper& paper, const FlatFoldRequest& request)
{
  using Failure = Expected<FlatFoldResult>;
  const double tolerance = 1e-9 * paper.scale();
  const Expected<FoldPlan> plan = planFold(paper, request);
  if (!plan)
    return Failure::failure(plan.message());
  const std::vector<double>& angles = plan->angles;
  const int root = plan->root;
  FlatFoldResult result;
  result.changed_edges = plan->changed_edges;
  const Expected<std::vector<Vec3>> placed =
      foldedPositionsFromAngles(paper, angles, root, facePose(paper, root), tolerance);
  if (!placed)
    return Failure::failure("the chosen creases do not fold flat: the fold does not close (" + placed.message() + ")");
  // Closing is not enough: a vertex with every crease valley closes too (a turn by π is one by −π).
  if (const Status vertices = checkFlatVertices(paper, angles, plan->changed_edges); !vertices)
    return Failure::failure("the chosen creases do not fold flat: " + vertices.message());

  Paper next = paper;
  for (size_t v = 0; v < next.vertices.size(); ++v)
    next.vertices[v].folded = (*placed)[v];
  for (int v : paper.faces[root].vertices)  // the face that stays, exactly (its pose is a fit)
    next.vertices[v].folded = paper.vertices[v].folded;
  // A face moves when a crease between it and the fixed face turns, even by a full turn (a
  // mountain re-marked valley swings its flap round to the other side: same place, new layers).
  const std::vector<std::vector<int>> turns = turnsFromFixedFace(paper, *plan);
  std::vector<char> moved(paper.faces.size(), 0);
  for (size_t f = 0; f < paper.faces.size(); ++f)
  {
    moved[f] = !turns[f].empty();
    for (int v : paper.faces[f].vertices)
      if ((next.vertices[v].folded - paper.vertices[v].folded).norm() > tolerance)
        moved[f] = 1;
  }
  if (const Status through = checkNoLayerPassedThrough(paper, *plan, moved); !through)
    return Failure::failure(through.message());
  for (size_t f = 0; f < moved.size(); ++f)
    if (moved[f])
      result.moved_faces.push_back(static_cast<int>(f));
  for (size_t e = 0; e < next.edges.size(); ++e)
    next.edges[e].fold_angle = angles[e];  // the branch to measure against
  updateFoldAngles(next);
  const std::vector<int> piece = rigidPieces(paper, angles, moved);
  if (const Status layers = orderLayers(next, paper, turns, moved, piece, root, 1e-7 * paper.scale()); !layers)
    return Failure::failure("the chosen creases do not fold flat: " + layers.message());
  paper = std::move(next);
  return result;
}

Expected<Paper> flatFoldFrame(const Paper& paper, const FlatFoldRequest& request, double fraction)
{
  using Failure = Expected<Paper>;
  if (!(fraction >= 0.0 && fraction <= 1.0))  // NaN fails both
  {
    std::ostringstream given;
    given << fraction;
    return Failure::failure("the fraction of the fold to show must be a number from 0 to 1, not " + given.str());
  }
  // The whole fold first: a frame is shown only of a fold that can be made.
  Paper folded = paper;
  const Expected<FlatFoldResult> result = flatFold(folded, request);
  if (!result)
    return Failure::failure(result.message());
  if (fraction == 0.0)
    return paper;
  if (fraction == 1.0)
    return folded;
  const Expected<FoldPlan> plan = planFold(paper, request);
  if (!plan)
    return Failure::failure(plan.message());

  // Each face's motion from its current place by the walk from the fixed face.
  const size_t faces = paper.faces.size(), edges = paper.edges.size();
  const int root = plan->root;
  const FaceMotions motions = faceMotions(paper, *plan, fraction);
  const std::vector<Eigen::Isometry3d>& motion = motions.motion;
  const std::vector<int>& depth = motions.depth;

  Paper frame = std::move(folded);
  std::vector<int> nearest(paper.vertices.size(), std::numeric_limits<int>::max());
  for (size_t f = 0; f < faces; ++f)
    for (int v : paper.faces[f].vertices)
      nearest[v] = std::min(nearest[v], depth[f]);
  std::vector<Vec3> sum(paper.vertices.size(), Vec3::Zero());
  std::vector<int> count(paper.vertices.size(), 0);
  for (size_t f = 0; f < faces; ++f)
    for (int v : paper.faces[f].vertices)
      if (depth[f] == nearest[v])
      {
        sum[v] += static_cast<int>(f) == root ? paper.vertices[v].folded : Vec3(motion[f] * paper.vertices[v].folded);
        ++count[v];
      }
  for (size_t v = 0; v < paper.vertices.size(); ++v)
    frame.vertices[v].folded = count[v] == 1 ? sum[v] : sum[v] / static_cast<double>(std::max(1, count[v]));
  for (int v : paper.faces[root].vertices)
    frame.vertices[v].folded = paper.vertices[v].folded;  // exactly where it was
  for (size_t e = 0; e < edges; ++e)
    frame.edges[e].fold_angle = paper.edges[e].fold_angle + fraction * (plan->angles[e] - paper.edges[e].fold_angle);
  std::vector<char> moved(faces, 0);
  for (int f : result->moved_faces)
    moved[f] = 1;
  frame.face_orders = paper.face_orders;
  clearFaceOrdersAcross(frame, moved);
  pruneFaceOrders(frame, 1e-7 * paper.scale());
  return frame;
}

}  // namespace virtual_origami::core

#include "virtual_origami/core/flat_fold.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "virtual_origami/core/face_orders.h"
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

/// The layer order after the fold: the orders of layers that turned together hold, the rest
/// follow from the creases (layer_order.h). Fails when no order of the layers folds flat.
Status orderLayers(Paper& next, const Paper& before, const std::vector<std::vector<int>>& turns,
                   const std::vector<char>& moved, double tolerance)
{
  LayerOrderOptions options;
  options.tolerance = tolerance;
  for (const FaceOrder& o : before.face_orders)
    if (o.face >= 0 && o.other >= 0 && o.face < static_cast<int>(turns.size()) &&
        o.other < static_cast<int>(turns.size()) && turns[o.face] == turns[o.other])
      options.kept.push_back(o);
  Expected<LayerOrder> order = solveLayerOrder(next, options);
  if (!order && !options.kept.empty())
  {
    // Orders recorded before may not have been complete or right: what the creases allow decides.
    options.kept.clear();
    order = solveLayerOrder(next, options);
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
  for (size_t f = 0; f < moved.size(); ++f)
    if (moved[f])
      result.moved_faces.push_back(static_cast<int>(f));
  for (size_t e = 0; e < next.edges.size(); ++e)
    next.edges[e].fold_angle = angles[e];  // the branch to measure against
  updateFoldAngles(next);
  if (const Status layers = orderLayers(next, paper, turns, moved, 1e-7 * paper.scale()); !layers)
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

  // Each face's pose by the walk from the fixed face, now (0) and at `fraction` (t), relative
  // to the fixed face's pose; depth: creases crossed from the fixed face.
  const size_t faces = paper.faces.size(), edges = paper.edges.size();
  std::vector<double> now(edges), then(edges);
  for (size_t e = 0; e < edges; ++e)
  {
    now[e] = paper.edges[e].fold_angle;
    then[e] = now[e] + fraction * (plan->angles[e] - now[e]);
  }
  const int root = plan->root;
  const Eigen::Isometry3d root_pose = facePose(paper, root);
  std::vector<Eigen::Isometry3d> pose0(faces, root_pose), pose_t(faces, root_pose);
  std::vector<int> depth(faces, -1);
  depth[root] = 0;
  walkFaces(paper, root, [&](int f, int e, int g) {
    pose0[g] = pose0[f] * hingeTransform(paper, e, f, now[e]);
    pose_t[g] = pose_t[f] * hingeTransform(paper, e, f, then[e]);
    depth[g] = depth[f] + 1;
  });
  // The motion of each face from its current place (the fixed face: none).
  std::vector<Eigen::Isometry3d> motion(faces, Eigen::Isometry3d::Identity());
  for (size_t f = 0; f < faces; ++f)
    if (static_cast<int>(f) != root)
      motion[f] = pose_t[f] * pose0[f].inverse();

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
    frame.edges[e].fold_angle = then[e];
  std::vector<char> moved(faces, 0);
  for (int f : result->moved_faces)
    moved[f] = 1;
  frame.face_orders = paper.face_orders;
  clearFaceOrdersAcross(frame, moved);
  pruneFaceOrders(frame, 1e-7 * paper.scale());
  return frame;
}

}  // namespace virtual_origami::core

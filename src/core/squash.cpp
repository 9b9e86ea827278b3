#include "virtual_origami/core/squash.h"

#include <cmath>

#include <Eigen/Geometry>

#include "virtual_origami/core/kinematics.h"

namespace virtual_origami::core
{
namespace
{
/// The most level face (its normal nearest ±z).
int levelFace(const Paper& paper)
{
  int best = 0;
  for (size_t f = 1; f < paper.faces.size(); ++f)
    if (std::abs(paper.faceNormal(static_cast<int>(f)).z()) > std::abs(paper.faceNormal(best).z()) + 1e-12)
      best = static_cast<int>(f);
  return best;
}

/// The face's pose tilted (about its centroid) to lie flat, then lowered onto z = 0.
Eigen::Isometry3d flattenedPose(const Paper& paper, int face)
{
  const Eigen::Isometry3d pose = facePose(paper, face);
  const Vec3 normal = pose.linear() * Vec3::UnitZ();
  const Vec3 target = normal.z() >= 0 ? Vec3::UnitZ() : Vec3(-Vec3::UnitZ());
  const Vec3 centre = paper.faceCentroid(face);
  Eigen::Isometry3d tilt = Eigen::Isometry3d::Identity();
  tilt.translate(Vec3(centre.x(), centre.y(), 0.0))
      .rotate(Eigen::Quaterniond::FromTwoVectors(normal, target))
      .translate(-centre);
  return tilt * pose;
}
}  // namespace

Expected<SquashResult> squash(Paper& paper, ShapeSolver* solver)
{
  SquashResult result;
  Paper next = paper;
  std::vector<double> flat_angles(paper.edges.size(), 0.0);
  for (size_t e = 0; e < paper.edges.size(); ++e)
  {
    const double a = paper.edges[e].fold_angle;
    flat_angles[e] = std::abs(a) < M_PI / 2 ? 0.0 : std::copysign(M_PI, a);
  }
  const int root = levelFace(paper);
  const Expected<std::vector<Vec3>> rigid =
      foldedPositionsFromAngles(paper, flat_angles, root, flattenedPose(paper, root), 1e-9 * paper.scale());
  if (rigid)
  {
    for (size_t v = 0; v < next.vertices.size(); ++v)
      next.vertices[v].folded = (*rigid)[v];
    for (size_t e = 0; e < next.edges.size(); ++e)
      next.edges[e].fold_angle = flat_angles[e];  // the branch to measure against
    result.exact = true;
  }
  else
  {
    if (!solver)
      return Expected<SquashResult>::failure("the model cannot be pressed flat rigidly (" + rigid.message() +
                                             ") and no solver is selected to restore the faces");
    for (Vertex& v : next.vertices)
      v.folded.z() = 0.0;
    result.solve = solver->solve(next, std::vector<char>(next.vertices.size(), 0));
    if (result.solve.diverged || !result.solve.converged)
      return Expected<SquashResult>::failure(solver->name() + " could not restore the pressed faces: " +
                                             result.solve.message + "; the model is unchanged");
  }
  updateFoldAngles(next);
  paper = std::move(next);
  return result;
}

}  // namespace virtual_origami::core

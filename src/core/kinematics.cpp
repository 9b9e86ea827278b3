#include "virtual_origami/core/kinematics.h"

#include <cmath>
#include <sstream>

#include "virtual_origami/core/geometry.h"

namespace virtual_origami::core
{
Eigen::Isometry3d facePose(const Paper& paper, int face)
{
  const std::vector<int>& vs = paper.faces[face].vertices;
  Vec3 p_mean = Vec3::Zero(), q_mean = Vec3::Zero();
  for (int v : vs)
  {
    const Vec2& c = paper.vertices[v].crease_pattern;
    p_mean += Vec3(c.x(), c.y(), 0.0);
    q_mean += paper.vertices[v].folded;
  }
  p_mean /= static_cast<double>(vs.size());
  q_mean /= static_cast<double>(vs.size());
  Eigen::Matrix3d h = Eigen::Matrix3d::Zero();
  for (int v : vs)
  {
    const Vec2& c = paper.vertices[v].crease_pattern;
    h += (Vec3(c.x(), c.y(), 0.0) - p_mean) * (paper.vertices[v].folded - q_mean).transpose();
  }
  // The crease pattern is planar, so h has rank 2; the determinant fix picks the proper rotation.
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = bestFitRotation(h);
  pose.translation() = q_mean - pose.linear() * p_mean;
  return pose;
}

Eigen::Isometry3d hingeTransform(const Paper& paper, int edge, int face, double fold_angle)
{
  const Edge& e = paper.edges[edge];
  const Vec2& a2 = paper.vertices[e.vertices[0]].crease_pattern;
  const Vec2& b2 = paper.vertices[e.vertices[1]].crease_pattern;
  const Vec3 a(a2.x(), a2.y(), 0.0);
  const Vec3 dir = Vec3(b2.x() - a2.x(), b2.y() - a2.y(), 0.0).normalized();
  // With the left face held, the right face turns by -ρ about a→b for a valley of ρ.
  const double turn = e.faces[0] == face ? -fold_angle : fold_angle;
  Eigen::Isometry3d hinge = Eigen::Isometry3d::Identity();
  hinge.translate(a).rotate(Eigen::AngleAxisd(turn, dir)).translate(-a);
  return hinge;
}

namespace
{
/// Largest distance between where two poses put the face's vertices.
double poseGap(const Paper& paper, int face, const Eigen::Isometry3d& p, const Eigen::Isometry3d& q)
{
  double gap = 0;
  for (int v : paper.faces[face].vertices)
  {
    const Vec2& c = paper.vertices[v].crease_pattern;
    gap = std::max(gap, (p * Vec3(c.x(), c.y(), 0.0) - q * Vec3(c.x(), c.y(), 0.0)).norm());
  }
  return gap;
}
}  // namespace

Expected<std::vector<Vec3>> foldedPositionsFromAngles(const Paper& paper, const std::vector<double>& fold_angles,
                                                      int root_face, const Eigen::Isometry3d& root_pose,
                                                      double tolerance)
{
  if (fold_angles.size() != paper.edges.size())
    return Expected<std::vector<Vec3>>::failure("need one fold angle per edge");
  if (root_face < 0 || root_face >= static_cast<int>(paper.faces.size()))
    return Expected<std::vector<Vec3>>::failure("root face " + std::to_string(root_face) + " does not exist");
  std::vector<Eigen::Isometry3d> pose(paper.faces.size());
  pose[root_face] = root_pose;
  const std::vector<char> placed = walkFaces(paper, root_face, [&](int f, int e, int g) {
    pose[g] = pose[f] * hingeTransform(paper, e, f, fold_angles[e]);
  });
  // Creases off the spanning tree must agree with the poses their faces got.
  for (size_t e = 0; e < paper.edges.size(); ++e)
  {
    const Edge& edge = paper.edges[e];
    if (!edge.isCrease() || !placed[edge.faces[0]] || !placed[edge.faces[1]])
      continue;
    const int f = edge.faces[0], g = edge.faces[1];
    const double gap = poseGap(paper, g, pose[g], pose[f] * hingeTransform(paper, static_cast<int>(e), f, fold_angles[e]));
    if (gap > tolerance)
    {
      std::ostringstream msg;
      msg << "the fold angles do not close around crease " << e << " (its faces disagree by " << gap << ")";
      return Expected<std::vector<Vec3>>::failure(msg.str());
    }
  }
  std::vector<Vec3> positions(paper.vertices.size(), Vec3::Zero());
  std::vector<char> known(paper.vertices.size(), 0);
  for (size_t f = 0; f < paper.faces.size(); ++f)
  {
    if (!placed[f])
      return Expected<std::vector<Vec3>>::failure("face " + std::to_string(f) + " is not connected to face " +
                                                  std::to_string(root_face) + " by creases");
    for (int v : paper.faces[f].vertices)
    {
      const Vec2& c = paper.vertices[v].crease_pattern;
      const Vec3 p = pose[f] * Vec3(c.x(), c.y(), 0.0);
      if (!known[v])
      {
        positions[v] = p;
        known[v] = 1;
      }
      else if ((positions[v] - p).norm() > tolerance)
      {
        std::ostringstream msg;
        msg << "the fold angles do not close at vertex " << v << " (its faces disagree by "
            << (positions[v] - p).norm() << ")";
        return Expected<std::vector<Vec3>>::failure(msg.str());
      }
    }
  }
  return positions;
}

}  // namespace virtual_origami::core

#include "virtual_origami/core/geometry.h"

#include <cmath>
#include <limits>

#include <Eigen/Geometry>
#include <Eigen/SVD>

namespace virtual_origami::core
{
Vec3 rotateAbout(const Vec3& point, const Vec3& origin, const Vec3& axis, double angle)
{
  return origin + Eigen::AngleAxisd(angle, axis) * (point - origin);
}

double pointSegmentDistance(const Vec3& point, const Vec3& a, const Vec3& b)
{
  const Vec3 ab = b - a;
  const double len2 = ab.squaredNorm();
  const double t = len2 > 0 ? std::clamp((point - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (a + t * ab - point).norm();
}

FaceProjection projectOntoFace(const Paper& paper, int face, const Vec3& point)
{
  const std::vector<int>& vs = paper.faces[face].vertices;
  const Vec3 n = paper.faceNormal(face);
  const Vec3 c = paper.faceCentroid(face);
  const Vec3 on_plane = point - n.dot(point - c) * n;
  bool inside = true;
  for (size_t i = 0; i < vs.size(); ++i)
  {
    const Vec3& a = paper.vertices[vs[i]].folded;
    const Vec3& b = paper.vertices[vs[(i + 1) % vs.size()]].folded;
    // Counter-clockwise about the front normal: inside lies left of every side.
    if ((b - a).cross(on_plane - a).dot(n) < -1e-12 * (b - a).squaredNorm())
      inside = false;
  }
  FaceProjection result;
  result.inside = inside;
  if (inside)
  {
    result.closest = on_plane;
  }
  else
  {
    double best = std::numeric_limits<double>::infinity();
    for (size_t i = 0; i < vs.size(); ++i)
    {
      const Vec3& a = paper.vertices[vs[i]].folded;
      const Vec3& b = paper.vertices[vs[(i + 1) % vs.size()]].folded;
      const Vec3 ab = b - a;
      const double t = std::clamp((on_plane - a).dot(ab) / std::max(ab.squaredNorm(), 1e-300), 0.0, 1.0);
      const Vec3 q = a + t * ab;
      if ((q - point).norm() < best)
      {
        best = (q - point).norm();
        result.closest = q;
      }
    }
  }
  result.distance = (result.closest - point).norm();
  return result;
}

int faceAt(const Paper& paper, const Vec3& point, double max_distance)
{
  int best = -1;
  double best_distance = std::numeric_limits<double>::infinity();
  double best_z = -std::numeric_limits<double>::infinity();
  const double tie = 1e-9 * paper.scale();
  for (size_t f = 0; f < paper.faces.size(); ++f)
  {
    const FaceProjection p = projectOntoFace(paper, static_cast<int>(f), point);
    if (p.distance > max_distance)
      continue;
    const double z = p.closest.z();
    if (p.distance < best_distance - tie || (p.distance <= best_distance + tie && z > best_z))
    {
      best = static_cast<int>(f);
      best_distance = p.distance;
      best_z = z;
    }
  }
  return best;
}

bool allFinite(const Vec3& v) { return v.allFinite(); }

Eigen::Matrix3d bestFitRotation(const Eigen::Matrix3d& covariance)
{
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(covariance, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d d = Eigen::Matrix3d::Identity();
  d(2, 2) = (svd.matrixV() * svd.matrixU().transpose()).determinant() < 0 ? -1.0 : 1.0;
  return svd.matrixV() * d * svd.matrixU().transpose();
}

ShapeDistance shapeDistance(const Positions& points, const Positions& target)
{
  const Vec3 pc = points.rowwise().mean(), tc = target.rowwise().mean();
  const Eigen::Matrix3d cov = (points.colwise() - pc) * (target.colwise() - tc).transpose();
  const Eigen::Matrix3d rotation = bestFitRotation(cov);
  const Eigen::VectorXd distance = ((rotation * (points.colwise() - pc)).colwise() + tc - target).colwise().norm();
  ShapeDistance out;
  out.rms = std::sqrt(distance.squaredNorm() / static_cast<double>(distance.size()));
  out.largest = distance.maxCoeff();
  return out;
}

}  // namespace virtual_origami::core

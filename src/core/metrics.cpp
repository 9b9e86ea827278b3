#include "virtual_origami/core/metrics.h"

#include <cmath>

#include <Eigen/Eigenvalues>

#include "virtual_origami/core/kinematics.h"

namespace virtual_origami::core
{
StrainStats edgeStrain(const Paper& paper)
{
  return springStrain(faceSprings(paper), foldedPositions(paper));
}

double facePlanarity(const Paper& paper, int face)
{
  const std::vector<int>& vs = paper.faces[face].vertices;
  const Vec3 centroid = paper.faceCentroid(face);
  Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
  for (int v : vs)
  {
    const Vec3 d = paper.vertices[v].folded - centroid;
    scatter += d * d.transpose();
  }
  // The best plane's normal is the scatter's least eigenvector (ascending order).
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(scatter);
  const Vec3 normal = eigen.eigenvectors().col(0);
  double worst = 0.0;
  for (int v : vs)
    worst = std::max(worst, std::abs(normal.dot(paper.vertices[v].folded - centroid)));
  return worst;
}

std::vector<double> measuredFoldAngles(const Paper& paper)
{
  std::vector<double> angles(paper.edges.size(), 0.0);
  for (size_t e = 0; e < paper.edges.size(); ++e)
  {
    if (!paper.edges[e].isCrease())
      continue;
    double angle = measureFoldAngle(paper, static_cast<int>(e));
    const double recorded = paper.edges[e].fold_angle;
    if (angle - recorded > M_PI)
      angle -= 2 * M_PI;
    else if (recorded - angle > M_PI)
      angle += 2 * M_PI;
    angles[e] = angle;
  }
  return angles;
}

double forceResidual(const Paper& paper, const std::vector<char>& fixed)
{
  Positions forces;
  evaluateSprings(faceSprings(paper), foldedPositions(paper), &forces);
  const std::vector<int> free_index = freeIndices(fixed, paper.vertices.size());
  double worst = 0.0;
  for (Eigen::Index v = 0; v < forces.cols(); ++v)
    if (free_index[v] >= 0)
      worst = std::max(worst, forces.col(v).norm());
  return worst / paper.scale();
}

ShapeMetrics measureShape(const Paper& paper, const std::vector<char>& fixed)
{
  ShapeMetrics m;
  m.strain = edgeStrain(paper);
  for (size_t f = 0; f < paper.faces.size(); ++f)
  {
    const int face = static_cast<int>(f);
    m.planarity = std::max(m.planarity, facePlanarity(paper, face));
    const Eigen::Isometry3d pose = facePose(paper, face);
    for (int v : paper.faces[f].vertices)
    {
      const Vec2& c = paper.vertices[v].crease_pattern;
      m.shape_residual = std::max(m.shape_residual, (pose * Vec3(c.x(), c.y(), 0.0) - paper.vertices[v].folded).norm());
    }
  }
  m.planarity /= paper.scale();
  m.shape_residual /= paper.scale();
  m.force_residual = forceResidual(paper, fixed);
  m.fold_angles = measuredFoldAngles(paper);
  return m;
}

}  // namespace virtual_origami::core

#include "virtual_origami/solvers/rigid_faces.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <sstream>

#include <Eigen/Geometry>
#include <Eigen/SVD>

#include "virtual_origami/core/compliant_faces.h"

namespace virtual_origami::core
{
std::vector<RigidFace> rigidFaces(const Paper& paper, bool exact_rest)
{
  // The convex pieces of a concave face of a loaded file (joined by split edges) are one rigid
  // body: the split edges are no hinges, unless the face is compliant (its facets bend).
  std::vector<int> group(paper.faces.size());
  for (size_t f = 0; f < group.size(); ++f)
    group[f] = static_cast<int>(f);
  const std::function<int(int)> root = [&](int f) { return group[f] == f ? f : group[f] = root(group[f]); };
  for (const Edge& e : paper.edges)
    if (e.split && e.isCrease() && !isFacet(e))
      group[root(e.faces[0])] = root(e.faces[1]);
  std::vector<std::vector<int>> members(paper.faces.size());
  for (size_t f = 0; f < group.size(); ++f)
    members[root(static_cast<int>(f))].push_back(static_cast<int>(f));

  std::vector<RigidFace> faces;
  faces.reserve(paper.faces.size());
  for (const std::vector<int>& body : members)
  {
    if (body.empty())
      continue;
    RigidFace rigid;
    for (int f : body)
      for (int v : paper.faces[f].vertices)
        if (std::find(rigid.vertices.begin(), rigid.vertices.end(), v) == rigid.vertices.end())
          rigid.vertices.push_back(v);
    rigid.rest.resize(2, static_cast<Eigen::Index>(rigid.vertices.size()));
    // Relative to one of its vertices first (as centredFace): exact differences, where a mean of
    // coordinates far from the origin rounds each rest shape by their ulp once more.
    const Vec2 origin = exact_rest ? paper.vertices[rigid.vertices[0]].crease_pattern : Vec2::Zero();
    for (size_t k = 0; k < rigid.vertices.size(); ++k)
      rigid.rest.col(static_cast<Eigen::Index>(k)) = paper.vertices[rigid.vertices[k]].crease_pattern - origin;
    const Eigen::Vector2d mean = rigid.rest.rowwise().mean();
    rigid.rest.colwise() -= mean;
    faces.push_back(std::move(rigid));
  }
  return faces;
}

Eigen::Matrix3Xd centredFace(const RigidFace& face, const Positions& x)
{
  // Relative to one of its own vertices first: the differences of nearby coordinates are exact,
  // where a mean of coordinates far from the origin (a sheet 55 units wide) rounds to their ulp,
  // a noise in every residual and gradient that near-singular balances amplify.
  const Eigen::Index n = face.rest.cols();
  Eigen::Matrix3Xd centred(3, n);
  const Eigen::Vector3d origin = x.col(face.vertices[0]);
  for (Eigen::Index k = 0; k < n; ++k)
    centred.col(k) = x.col(face.vertices[k]) - origin;
  const Eigen::Vector3d mean = centred.rowwise().mean();
  centred.colwise() -= mean;
  return centred;
}

namespace
{
Eigen::Matrix3d fitCentred(const RigidFace& face, const Eigen::Matrix3Xd& centred)
{
  const Eigen::Matrix<double, 3, 2> m = centred * face.rest.transpose();
  // Polar factor q = U Vᵀ of the SVD of m itself. The closed form through mᵀm squares m's
  // condition: on a sliver face (many creases close together) the fit then lost about eight
  // digits, and Newton stalled at a face residual of 1e-11, a strain of 1e-8 on its short edges.
  // Squashed to a segment or a point, any orthonormal fit will do: the SVD gives one.
  const Eigen::JacobiSVD<Eigen::Matrix<double, 3, 2>> svd(m, Eigen::ComputeFullU | Eigen::ComputeFullV);
  const Eigen::Matrix<double, 3, 2> q = svd.matrixU().leftCols<2>() * svd.matrixV().transpose();
  Eigen::Matrix3d r;
  r.col(0) = q.col(0);
  r.col(1) = q.col(1);
  r.col(2) = q.col(0).cross(q.col(1));
  return r;
}
}  // namespace

Eigen::Matrix3d fitRotation(const RigidFace& face, const Positions& x)
{
  return fitCentred(face, centredFace(face, x));
}

RigidFit fitRigidFaces(const std::vector<RigidFace>& faces, const Positions& x)
{
  RigidFit fit;
  fit.rotations.reserve(faces.size());
  for (const RigidFace& face : faces)
  {
    const Eigen::Matrix3Xd centred = centredFace(face, x);
    const Eigen::Matrix3d r = fitCentred(face, centred);
    fit.rotations.push_back(r);
    for (Eigen::Index k = 0; k < face.rest.cols(); ++k)
    {
      const Eigen::Vector3d residual = centred.col(k) - r.leftCols<2>() * face.rest.col(k);
      const double norm = residual.norm();
      fit.energy += 0.5 * norm * norm;
      fit.max_residual = std::isfinite(norm) ? std::max(fit.max_residual, norm) : INFINITY;
    }
  }
  return fit;
}

void finishRigidSolve(const std::string& solver, Paper& paper, const std::vector<Spring>& springs,
                      const Positions& start, const Positions& x, bool diverged, const RigidFit& fit,
                      const std::string& stop_reason, double tolerance, SolveReport& report)
{
  if (diverged)
  {
    setFoldedPositions(paper, start);
    report.diverged = true;
    report.max_strain = springStrain(springs, start).max;
    report.message = solver + " produced non-finite positions; rolled back";
    return;
  }
  setFoldedPositions(paper, x);
  report.max_strain = springStrain(springs, x).max;
  if (!report.converged)
  {
    std::ostringstream msg;
    msg << (stop_reason.empty() ? "stopped" : stop_reason) << " after " << report.iterations
        << " iterations at max strain " << report.max_strain << " (tolerance " << tolerance << "), face residual "
        << fit.max_residual;
    report.message = msg.str();
  }
}

}  // namespace virtual_origami::core

#include "virtual_origami/solvers/rigid_kinematics_solver.h"

#include <cmath>
#include <sstream>

#include <Eigen/Dense>
#include <Eigen/Geometry>

#include "virtual_origami/core/kinematics.h"
#include "virtual_origami/core/face_springs.h"
#include "virtual_origami/core/positions.h"
#include "virtual_origami/solvers/rigid_faces.h"
#include "virtual_origami/numerics/solve_budget.h"

namespace virtual_origami::core
{
namespace
{
/// A spanning tree of faces across creases from a root face.
struct FaceTree
{
  int root = 0;
  std::vector<int> order;        // breadth-first, root first
  std::vector<int> parent;       // parent face, -1 at the root
  std::vector<int> parent_edge;  // the crease to the parent
  std::vector<int> angle_index;  // per edge: its unknown (after the root's 6), or -1
  int unknowns = 6;
};

FaceTree faceTree(const Paper& paper, int root)
{
  FaceTree tree;
  tree.root = root;
  tree.parent.assign(paper.faces.size(), -1);
  tree.parent_edge.assign(paper.faces.size(), -1);
  tree.angle_index.assign(paper.edges.size(), -1);
  tree.order.push_back(root);
  walkFaces(paper, root, [&](int from, int edge, int to) {
    tree.order.push_back(to);
    tree.parent[to] = from;
    tree.parent_edge[to] = edge;
    tree.angle_index[edge] = tree.unknowns++;
  });
  return tree;
}

Vec3 flat(const Paper& paper, int v)
{
  const Vec2& c = paper.vertices[v].crease_pattern;
  return Vec3(c.x(), c.y(), 0.0);
}

/// The sign with which a crease's fold angle turns the child face about the crease's
/// direction (vertices[0]→vertices[1]) in its parent's frame (see kinematics.cpp).
double turnSign(const Edge& edge, int parent)
{
  return edge.faces[0] == parent ? -1.0 : 1.0;
}

struct Placement
{
  std::vector<Eigen::Isometry3d> pose;  // per face
};

Placement place(const Paper& paper, const FaceTree& tree, const Eigen::Isometry3d& root_pose,
                const std::vector<double>& angles)
{
  Placement p;
  p.pose.assign(paper.faces.size(), Eigen::Isometry3d::Identity());
  p.pose[tree.root] = root_pose;
  for (size_t k = 1; k < tree.order.size(); ++k)
  {
    const int f = tree.order[k];
    const int e = tree.parent_edge[f];
    const Edge& edge = paper.edges[e];
    const Vec3 a = flat(paper, edge.vertices[0]);
    const Vec3 dir = (flat(paper, edge.vertices[1]) - a).normalized();
    Eigen::Isometry3d hinge = Eigen::Isometry3d::Identity();
    hinge.translate(a).rotate(Eigen::AngleAxisd(turnSign(edge, tree.parent[f]) * angles[e], dir)).translate(-a);
    p.pose[f] = p.pose[tree.parent[f]] * hinge;
  }
  return p;
}

/// Residuals: for every vertex, where each of its faces after the first puts it against the
/// first; for held vertices, the first face's placement against where it is held; for the
/// others, `stay` times the same against where the solve started.
struct Residuals
{
  Eigen::VectorXd r;
  Eigen::MatrixXd j;
  double hard = 0.0;  // largest closure or held residual
};

class KinematicProblem
{
public:
  KinematicProblem(const Paper& paper, const FaceTree& tree, const std::vector<char>& fixed, const Positions& start)
    : paper_(paper), tree_(tree), fixed_(fixed), start_(start)
  {
    faces_of_.resize(paper.vertices.size());
    for (size_t f = 0; f < paper.faces.size(); ++f)
      for (int v : paper.faces[f].vertices)
        faces_of_[v].push_back(static_cast<int>(f));
  }

  Residuals evaluate(const Placement& p, double stay, bool jacobian) const
  {
    Residuals out;
    std::vector<Eigen::Vector3d> r;
    std::vector<Eigen::MatrixXd> jr;
    for (size_t v = 0; v < paper_.vertices.size(); ++v)
    {
      const std::vector<int>& faces = faces_of_[v];
      if (faces.empty())
        continue;
      const int first = faces[0];
      const Vec3 x0 = p.pose[first] * flat(paper_, static_cast<int>(v));
      Eigen::MatrixXd j0;
      if (jacobian)
        j0 = pointJacobian(p, first, x0);
      for (size_t k = 1; k < faces.size(); ++k)
      {
        const Vec3 xk = p.pose[faces[k]] * flat(paper_, static_cast<int>(v));
        r.push_back(xk - x0);
        out.hard = std::max(out.hard, (xk - x0).norm());
        if (jacobian)
          jr.push_back(pointJacobian(p, faces[k], xk) - j0);
      }
      const bool held = v < fixed_.size() && fixed_[v];
      if (held || stay > 0)
      {
        const double w = held ? 1.0 : stay;
        r.push_back(w * (x0 - start_.col(static_cast<Eigen::Index>(v))));
        if (held)
          out.hard = std::max(out.hard, r.back().norm() / w);
        if (jacobian)
          jr.push_back(w * j0);
      }
    }
    out.r.resize(3 * static_cast<Eigen::Index>(r.size()));
    for (size_t i = 0; i < r.size(); ++i)
      out.r.segment<3>(3 * static_cast<Eigen::Index>(i)) = r[i];
    if (jacobian)
    {
      out.j.resize(out.r.size(), tree_.unknowns);
      for (size_t i = 0; i < jr.size(); ++i)
        out.j.middleRows<3>(3 * static_cast<Eigen::Index>(i)) = jr[i];
    }
    return out;
  }

private:
  /// d x / d unknowns for a point x carried by face f: the root's twist (rotation about the
  /// origin, then translation) and every tree crease on the path from the root to f.
  Eigen::MatrixXd pointJacobian(const Placement& p, int f, const Vec3& x) const
  {
    Eigen::MatrixXd j = Eigen::MatrixXd::Zero(3, tree_.unknowns);
    Eigen::Matrix3d skew;
    skew << 0, x.z(), -x.y(), -x.z(), 0, x.x(), x.y(), -x.x(), 0;  // δφ ↦ δφ × x
    j.leftCols<3>() = skew;
    j.block<3, 3>(0, 3).setIdentity();
    for (int g = f; tree_.parent[g] >= 0; g = tree_.parent[g])
    {
      const int e = tree_.parent_edge[g];
      const Edge& edge = paper_.edges[e];
      const Eigen::Isometry3d& parent_pose = p.pose[tree_.parent[g]];
      const Vec3 a = parent_pose * flat(paper_, edge.vertices[0]);
      const Vec3 axis =
          parent_pose.linear() * (flat(paper_, edge.vertices[1]) - flat(paper_, edge.vertices[0])).normalized();
      j.col(tree_.angle_index[e]) = turnSign(edge, tree_.parent[g]) * axis.cross(x - a);
    }
    return j;
  }

  const Paper& paper_;
  const FaceTree& tree_;
  const std::vector<char>& fixed_;
  const Positions& start_;
  std::vector<std::vector<int>> faces_of_;
};

/// The face with the most held vertices (the turned face in a rotation), else face 0.
int rootFace(const Paper& paper, const std::vector<char>& fixed)
{
  int best = 0, best_count = -1;
  for (size_t f = 0; f < paper.faces.size(); ++f)
  {
    int count = 0;
    for (int v : paper.faces[f].vertices)
      count += v < static_cast<int>(fixed.size()) && fixed[v];
    if (count > best_count)
    {
      best_count = count;
      best = static_cast<int>(f);
    }
  }
  return best;
}

Eigen::Isometry3d twisted(const Eigen::Isometry3d& pose, const Eigen::VectorXd& step)
{
  const Vec3 phi = step.head<3>();
  Eigen::Isometry3d delta = Eigen::Isometry3d::Identity();
  if (phi.norm() > 0)
    delta.linear() = Eigen::AngleAxisd(phi.norm(), phi.normalized()).toRotationMatrix();
  delta.translation() = step.segment<3>(3);
  return delta * pose;
}
}  // namespace

RigidKinematicsSolver::RigidKinematicsSolver(RigidKinematicsOptions options) : options_(options)
{
  limits_.max_iterations = 200;
}

SolveReport RigidKinematicsSolver::solve(Paper& paper, const std::vector<char>& fixed)
{
  numerics::SolveBudget budget(limits_);
  SolveReport report;
  const std::vector<Spring> springs = faceSprings(paper);
  const Positions start = foldedPositions(paper);
  report.max_strain = springStrain(springs, start).max;
  if (paper.faces.empty())
  {
    report.converged = true;
    return report;
  }
  const FaceTree tree = faceTree(paper, rootFace(paper, fixed));
  if (tree.order.size() != paper.faces.size())
  {
    report.message = "rigid kinematics needs every face joined by creases";
    return report;
  }
  const KinematicProblem problem(paper, tree, fixed, start);
  std::vector<double> angles(paper.edges.size(), 0.0);
  for (size_t e = 0; e < paper.edges.size(); ++e)
    angles[e] = paper.edges[e].fold_angle;
  Eigen::Isometry3d root_pose = facePose(paper, tree.root);
  // Faces are exact; strain comes only from where two faces (or a face and a hold) disagree
  // about a vertex, at most twice that gap over the shortest vertex pair.
  double shortest = INFINITY;
  for (const Spring& s : springs)
    shortest = std::min(shortest, s.rest);
  const double tolerance = 0.5 * limits_.tolerance * shortest;

  // Already exact where it stands: leave it untouched.
  if (report.max_strain <= limits_.tolerance &&
      fitRigidFaces(rigidFaces(paper), start).max_residual <= limits_.tolerance * paper.scale())
  {
    report.converged = true;
    return report;
  }

  double stay = options_.stay_weight;
  Placement placement = place(paper, tree, root_pose, angles);
  Residuals res = problem.evaluate(placement, stay, true);
  while (true)
  {
    if (stay == 0 && res.hard <= tolerance)
    {
      report.converged = true;
      break;
    }
    if (budget.exhausted(report.iterations) || !res.r.allFinite())
      break;
    ++report.iterations;
    const Eigen::MatrixXd jtj = res.j.transpose() * res.j;
    const Eigen::VectorXd g = res.j.transpose() * res.r;
    const double mu = options_.damping * std::max(1e-12, jtj.diagonal().maxCoeff()) * std::min(1.0, res.r.norm());
    const Eigen::VectorXd step = (jtj + mu * Eigen::MatrixXd::Identity(jtj.rows(), jtj.cols())).ldlt().solve(-g);
    // Backtracking on the same objective.
    const double before = res.r.squaredNorm();
    double alpha = 1.0;
    bool accepted = false;
    for (int k = 0; k < 30 && !accepted; ++k, alpha *= 0.5)
    {
      std::vector<double> trial_angles = angles;
      for (size_t e = 0; e < angles.size(); ++e)
        if (tree.angle_index[e] >= 0)
          trial_angles[e] += alpha * step(tree.angle_index[e]);
      const Eigen::Isometry3d trial_root = twisted(root_pose, alpha * step);
      const Placement trial = place(paper, tree, trial_root, trial_angles);
      const Residuals trial_res = problem.evaluate(trial, stay, false);
      if (trial_res.r.squaredNorm() <= before + 1e-4 * alpha * g.dot(step))
      {
        angles = trial_angles;
        root_pose = trial_root;
        placement = trial;
        accepted = true;
      }
    }
    stay = stay > 1e-8 ? stay * 0.1 : 0.0;
    res = problem.evaluate(placement, stay, true);
    if (!accepted && stay == 0 && alpha < 1e-8)
      break;
  }
  report.seconds = budget.seconds();
  if (!res.r.allFinite())
  {
    report.diverged = true;
    report.message = "rigid kinematics produced non-finite angles; rolled back";
    return report;
  }
  // Held vertices stay exactly where they are held; the others go where the first of their
  // faces puts them.
  std::vector<char> placed(paper.vertices.size(), 0);
  for (size_t f = 0; f < paper.faces.size(); ++f)
    for (int v : paper.faces[f].vertices)
    {
      if (placed[v] || (v < static_cast<int>(fixed.size()) && fixed[v]))
        continue;
      paper.vertices[v].folded = placement.pose[f] * flat(paper, v);
      placed[v] = 1;
    }
  for (size_t e = 0; e < paper.edges.size(); ++e)
    if (tree.angle_index[e] >= 0)
      paper.edges[e].fold_angle = angles[e];
  report.max_strain = springStrain(springs, foldedPositions(paper)).max;
  if (!report.converged)
  {
    std::ostringstream msg;
    msg << "stopped after " << report.iterations << " iterations with the faces " << res.hard
        << " apart at a shared or held vertex (tolerance " << tolerance << ")";
    report.message = msg.str();
  }
  return report;
}

}  // namespace virtual_origami::core

#include "virtual_origami/ros/spring_solver_node.h"

#include <cmath>

#include "virtual_origami/ros/conversions.h"
#include "virtual_origami/solvers/solver_factory.h"

namespace virtual_origami
{
SpringSolverNode::SpringSolverNode(ros::NodeHandle nh, ros::NodeHandle private_nh)
  : reconfigure_server_(private_nh)
{
  // The server calls reconfigure() once at once with the parameters (or their defaults).
  reconfigure_server_.setCallback([this](SpringSolverConfig& c, uint32_t level) { reconfigure(c, level); });
  service_ = nh.advertiseService("solve", &SpringSolverNode::solve, this);
}

void SpringSolverNode::reconfigure(SpringSolverConfig& config, uint32_t)
{
  std::unique_ptr<core::ShapeSolver> solver = core::makeSolver(config.solver);
  if (!solver)
  {
    ROS_ERROR("spring_solver: no solver named \"%s\"; keeping %s", config.solver.c_str(),
              solver_ ? solver_->name().c_str() : "none");
    if (solver_)
      return;
    solver = core::makeSolver("newton");
  }
  core::SolveLimits limits;
  limits.tolerance = config.tolerance;
  limits.max_iterations = config.max_iterations;
  limits.max_seconds = config.max_seconds;
  solver->setLimits(limits);
  solver_ = std::move(solver);
  ROS_INFO("spring_solver: %s, tolerance %g, at most %d iterations", solver_->name().c_str(), limits.tolerance,
           limits.max_iterations);
}

bool SpringSolverNode::solve(Solve::Request& req, Solve::Response& res)
{
  core::Expected<core::Paper> paper = fromMessage(req.paper);
  res.success = false;
  if (!paper)
  {
    res.message = "cannot solve this paper: " + paper.message();
    return true;
  }
  if (!(req.looser_tolerance >= 0) || !std::isfinite(req.looser_tolerance))
  {
    res.message = "the looser tolerance must be a finite strain of 0 or more";
    return true;
  }
  if (req.stall_window < 0)
  {
    res.message = "the stall window must be 0 (never) or more iterations";
    return true;
  }
  std::vector<char> fixed(paper->vertices.size(), 0);
  for (int v : req.fixed_vertices)
  {
    if (v < 0 || v >= static_cast<int>(fixed.size()))
    {
      res.message = "fixed vertex " + std::to_string(v) + " does not exist";
      return true;
    }
    fixed[v] = 1;
  }
  if (req.prepare)
  {
    solver_->prepare(*paper, fixed);
    res.success = true;
    res.message = solver_->name() + ": prepared";
    for (const core::Vertex& v : paper->vertices)
      res.positions.push_back(toPoint(v.folded));
    return true;
  }
  // This solve's stall window and budget (callbacks take turns: ros::spin), then the node's limits again.
  const core::SolveLimits configured = solver_->limits();
  core::SolveLimits limits = configured;
  limits.stall_window = req.stall_window;
  limits.max_seconds = core::budgetForSize(configured.max_seconds, paper->vertices.size());
  solver_->setLimits(limits);
  const core::SolveReport report = req.frame || req.looser_tolerance > 0 ?
                                       solver_->solveLoosely(*paper, fixed, req.looser_tolerance) :
                                       solver_->solve(*paper, fixed);
  solver_->setLimits(configured);
  ROS_DEBUG("spring_solver: %zu vertices, %d held: %s after %d iterations in %.2f s, strain %g: %s",
            paper->vertices.size(), static_cast<int>(req.fixed_vertices.size()),
            report.converged && !report.diverged ? "converged" : "not converged", report.iterations, report.seconds,
            report.max_strain, report.message.c_str());
  res.success = report.converged && !report.diverged;
  res.message = solver_->name() + ": " + report.message;
  res.iterations = report.iterations;
  res.max_strain = report.max_strain;
  for (const core::Vertex& v : paper->vertices)
    res.positions.push_back(toPoint(v.folded));
  return true;
}

}  // namespace virtual_origami

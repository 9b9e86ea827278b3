#include "virtual_origami/ros/remote_solver.h"

#include <ros/service.h>
#include <virtual_origami/Solve.h>

#include "virtual_origami/ros/conversions.h"

namespace virtual_origami
{
RemoteSolver::RemoteSolver(ros::NodeHandle nh, std::string service, double timeout)
  : nh_(nh), service_(nh.resolveName(service)), timeout_(timeout)
{
}

core::SolveReport RemoteSolver::solve(core::Paper& paper, const std::vector<char>& fixed)
{
  core::SolveReport report;
  if (!ros::service::waitForService(service_, ros::Duration(timeout_)))
  {
    report.message = "the solver service " + service_ + " is not running";
    return report;
  }
  Solve call;
  call.request.paper = toMessage(paper, 0, {});
  for (size_t v = 0; v < fixed.size(); ++v)
    if (fixed[v])
      call.request.fixed_vertices.push_back(static_cast<int>(v));
  if (!ros::service::call(service_, call))
  {
    report.message = "the call to " + service_ + " failed";
    return report;
  }
  report.iterations = call.response.iterations;
  report.max_strain = call.response.max_strain;
  report.message = call.response.message;
  if (!call.response.success || call.response.positions.size() != paper.vertices.size())
  {
    report.diverged = !call.response.success;
    if (call.response.success)
      report.message = "the solver answered with the wrong number of positions";
    return report;
  }
  for (size_t v = 0; v < paper.vertices.size(); ++v)
    paper.vertices[v].folded = toVec3(call.response.positions[v]);
  report.converged = true;
  return report;
}

}  // namespace virtual_origami

// The spring_solver node: restores face shapes for paper_model (SPEC §4.1) with the solver
// and limits chosen live through dynamic_reconfigure.
#pragma once

#include <memory>
#include <string>

#include <dynamic_reconfigure/server.h>
#include <ros/ros.h>
#include <virtual_origami/Solve.h>
#include <virtual_origami/SpringSolverConfig.h>

#include "virtual_origami/core/shape_solver.h"

namespace virtual_origami
{
class SpringSolverNode
{
public:
  SpringSolverNode(ros::NodeHandle nh, ros::NodeHandle private_nh);

private:
  bool solve(Solve::Request& req, Solve::Response& res);
  void reconfigure(SpringSolverConfig& config, uint32_t level);

  std::unique_ptr<core::ShapeSolver> solver_;
  dynamic_reconfigure::Server<SpringSolverConfig> reconfigure_server_;
  ros::ServiceServer service_;
};

}  // namespace virtual_origami

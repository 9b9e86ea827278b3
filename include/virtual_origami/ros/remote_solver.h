// A ShapeSolver that asks the spring_solver node, so the solver can run (and restart) as
// its own process, on another machine if need be.
#pragma once

#include <atomic>
#include <memory>
#include <string>

#include <ros/node_handle.h>
#include <virtual_origami/Solve.h>

#include "virtual_origami/core/shape_solver.h"

namespace virtual_origami
{
class RemoteSolver : public core::ShapeSolver
{
public:
  RemoteSolver(ros::NodeHandle nh, std::string service, double timeout);
  std::string name() const override { return "solver service " + service_; }
  /// Waits up to the timeout for the service and again for its answer; a missing, failing or
  /// stalled solver reports not converged, so the operation is refused and the model stays as it was.
  core::SolveReport solve(core::Paper& paper, const std::vector<char>& fixed) override;
  core::SolveReport solveLoosely(core::Paper& paper, const std::vector<char>& fixed, double looser) override;
  /// Asks the solver to ready itself for `paper` around `fixed` (Solve's `prepare`), within the
  /// same timeout; where it does not answer the first solve readies it instead.
  void prepare(const core::Paper& paper, const std::vector<char>& fixed) override;

private:
  /// One Solve call: `looser` and `frame` as the request's looser_tolerance and frame.
  core::SolveReport solveRemotely(core::Paper& paper, const std::vector<char>& fixed, double looser, bool frame);
  bool callWithin(Solve& call, size_t vertices, std::string& message);

  ros::NodeHandle nh_;
  std::string service_;
  double timeout_;
  static constexpr int kMaxStalledCalls = 4;
  static constexpr int kCallAttempts = 3;
  std::shared_ptr<std::atomic<int>> stalled_ = std::make_shared<std::atomic<int>>(0);  // calls given up on, still open
};

}  // namespace virtual_origami

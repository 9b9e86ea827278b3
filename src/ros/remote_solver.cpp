#include "virtual_origami/ros/remote_solver.h"

#include <chrono>
#include <cstdio>
#include <future>
#include <memory>
#include <thread>

#include <ros/console.h>
#include <ros/service.h>
#include <virtual_origami/Solve.h>

#include "virtual_origami/ros/conversions.h"
#include "virtual_origami/ros/service_call.h"

namespace virtual_origami
{
RemoteSolver::RemoteSolver(ros::NodeHandle nh, std::string service, double timeout)
  : nh_(nh), service_(nh.resolveName(service)), timeout_(timeout)
{
}

core::SolveReport RemoteSolver::solve(core::Paper& paper, const std::vector<char>& fixed)
{
  return solveRemotely(paper, fixed, 0.0, false);
}

core::SolveReport RemoteSolver::solveLoosely(core::Paper& paper, const std::vector<char>& fixed, double looser)
{
  return solveRemotely(paper, fixed, looser, true);
}

/// Calls the solver with `call`'s request within the timeout for a paper of `vertices` (made again
/// where a connection broke); false with `message` where it did not answer.
bool RemoteSolver::callWithin(Solve& call, size_t vertices, std::string& message)
{
  if (!ros::service::waitForService(service_, ros::Duration(timeout_)))
  {
    message = "the solver service " + service_ + " is not running";
    return false;
  }
  // roscpp's call has no deadline, and a stopped solver keeps its connection open: the call runs
  // on a thread of its own, and the model gives up on it after the timeout. The thread ends
  // when the solver answers or its connection breaks; a few stalled ones are refused at once.
  if (stalled_->load() >= kMaxStalledCalls)
  {
    message = "the solver service " + service_ + " has not answered " + std::to_string(kMaxStalledCalls) +
              " calls; it seems stopped";
    return false;
  }
  // A connection made per call was now and then lost under load (seen in contention_bench: one
  // call in 60; callService now avoids roscpp's cause of it). A connection can still break: the
  // solve is a pure function, so a lost call is made again within the deadline.
  // The solver's own budget grows with the paper beyond 10,000 vertices; so does the wait for it.
  const double timeout = core::budgetForSize(timeout_, vertices);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout);
  auto shared = std::make_shared<Solve>(std::move(call));
  for (int attempt = 1;; ++attempt)
  {
    auto answered = std::make_shared<std::promise<bool>>();
    std::future<bool> done = answered->get_future();
    std::thread([service = service_, shared, answered] { answered->set_value(callService(service, *shared)); })
        .detach();
    if (done.wait_until(deadline) != std::future_status::ready)
    {
      // Counted until that thread ends.
      ++*stalled_;
      std::thread([stalled = stalled_, done = std::move(done)]() mutable {
        done.wait();
        --*stalled;
      }).detach();
      char seconds[32];
      std::snprintf(seconds, sizeof seconds, "%g", timeout);
      message = "the solver service " + service_ + " did not answer within solver_timeout (" + seconds +
                " s for this paper's size)";
      return false;
    }
    if (done.get())
      break;
    if (attempt == kCallAttempts || std::chrono::steady_clock::now() >= deadline)
    {
      message = "the call to " + service_ + " failed (" + std::to_string(attempt) + " tries)";
      return false;
    }
  }
  call = std::move(*shared);
  return true;
}

namespace
{
/// A call of the solver for `paper` around `fixed`.
Solve solveCall(const core::Paper& paper, const std::vector<char>& fixed)
{
  Solve call;
  call.request.paper = toMessage(paper, 0, {});
  for (size_t v = 0; v < fixed.size(); ++v)
    if (fixed[v])
      call.request.fixed_vertices.push_back(static_cast<int>(v));
  return call;
}
}  // namespace

core::SolveReport RemoteSolver::solveRemotely(core::Paper& paper, const std::vector<char>& fixed, double looser,
                                              bool frame)
{
  core::SolveReport report;
  Solve call = solveCall(paper, fixed);
  call.request.looser_tolerance = looser;
  call.request.frame = frame;
  call.request.stall_window = limits_.stall_window;  // a closure's (core/assignment_fold.cpp)
  if (!callWithin(call, paper.vertices.size(), report.message))
    return report;
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

void RemoteSolver::prepare(const core::Paper& paper, const std::vector<char>& fixed)
{
  Solve call = solveCall(paper, fixed);
  call.request.prepare = true;
  std::string message;
  if (!callWithin(call, paper.vertices.size(), message))
    ROS_DEBUG("%s", message.c_str());  // a readiness, not an answer: the first solve makes it
}

}  // namespace virtual_origami

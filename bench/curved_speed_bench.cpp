// Speed of the curved-paper solvers (issue 4's target, issue 8's charts): (a) static solves per
// second of small pulls on a 10,000-vertex sheet and on smaller ones, and against the tolerance
// on a 2,025-vertex one; (b) time per step against vertex count up to 100,000 vertices, one
// Newton iteration and one RK4 step, beside the machine's floor measured in the same run
// (memory traffic of an explicit step over the triad bandwidth, one sparse Cholesky
// factorisation for an implicit one); (c) the RK4 stability map, step × stiffness,
// against the predicted limit. Wall time and process CPU time both: the machine is shared, and
// the charts use CPU time (one core: make bench caps CHOLMOD's OpenMP loops to one thread).
//
// (d) the same drag by Newton and by the quasi-Newton method (L-BFGS on a constant matrix) at
// 1,024 to 10,000 vertices, each balance's error against a tight Newton balance, beside the
// quasi-Newton floor (one back-substitution of the constant factor and one gradient).
//
// (e) the drag as a person sees it (issue 37): anytime frames (anytime_frames.h) at 30 Hz, one
// per pointer step, each frame's wall and thread CPU time, its distance to the tight balance
// for the same pointer (solved afresh after the drag, force 1e-10), the snaps' time to their
// branch and the release's to 1e-8; the same drag solved to 1e-8 at every step beside them.
//
//   curved_speed_bench [out_dir] [pulls|stability|scaling|methods|frames]   writes curved_speed.csv
//   and curved_drag_accuracy.csv, curved_stability.csv, curved_scaling.csv, curved_methods.csv,
//   curved_frames.csv (all, or the part named; `methods` and `frames` are not part of the
//   default run)
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include <chrono>
#include <thread>

#include <Eigen/Eigenvalues>

#include "virtual_origami/curved/anytime_frames.h"

#include "virtual_origami/numerics/blas_kernels.h"
#include "virtual_origami/curved/seed_scenes.h"
#include "virtual_origami/numerics/spd_factorization.h"
#include "bench_common.h"

using namespace virtual_origami::core;
namespace numerics = virtual_origami::numerics;
using virtual_origami::bench::gridMesh;
using virtual_origami::bench::now;

namespace
{
double cpuNow()
{
  return static_cast<double>(std::clock()) / CLOCKS_PER_SEC;
}

/// Seed scene 1's sheet meshed as an n × n grid, corner c held, corner a on the scene's pull.
struct PulledSheet
{
  SeedScene scene;
  CurvedMesh mesh;
  Positions rest;
  std::vector<CurvedPin> pins;

  explicit PulledSheet(int n) : scene(*seedScene(1)), mesh(gridMesh(scene.paper, n)), rest(placeNodes(mesh, scene.paper))
  {
    const int fixed = mesh.vertex_nodes[scene.fixed], pulled = mesh.vertex_nodes[scene.pulled];
    pins = { { fixed, rest.col(fixed) }, { pulled, rest.col(pulled) } };
  }
  void pullTo(double s) { pins[1].position = scene.pullAt(s); }
};

/// (a) A sheet of n × n vertices dragged along scene 1's pull from rest: each solve moves the
/// corner by a small step (1/2000 of the pull: a tenth of a mesh spacing at 10,000 vertices)
/// and solves to `tolerance` from the last balance; 200 of them (a tenth of
/// the pull: the sheet buckles off the flat, snaps twice and settles into its curl), unless a
/// minute runs out first. A fixed drag, not a fixed time: its start and snaps are its slowest
/// solves. One row of curved_speed.csv. With `accuracy`, every twentieth balance is also solved
/// on to 1e-11 from where the drag left it (by a solver of its own, outside the timing), and the
/// largest distance of a node between the two, over the sheet's side, is the drag's error
/// there: one row of curved_drag_accuracy.csv.
/// QuasiNewton's steps by conjugate gradients on the exact Hessian (the `methods` part's
/// quasi_newton_krylov); 0: L-BFGS.
int constant_krylov_iterations = 0;
/// The drags' solvers test every balance (check_stability; the `methods` part's *_checked).
bool check_every_balance = false;

struct DragSummary
{
  int solves = 0, converged = 0, iterations = 0, lbfgs_steps = 0, factorizations = 0, handed_over = 0;
  double cpu = 0, median_cpu = 0;
  std::vector<double> errors;  // of the balances checked, over the sheet's side
};

DragSummary dragSheet(int n, double tolerance, std::ostream& csv, std::ostream* accuracy = nullptr,
                      CurvedMethod method = CurvedMethod::Newton, int check_every = 20)
{
  PulledSheet sheet(n);
  CurvedSolver solver(sheet.mesh, sheet.scene.paper);
  solver.options().tolerance = tolerance;
  solver.options().method = method;
  solver.options().constant_krylov_iterations = constant_krylov_iterations;
  solver.options().check_stability = check_every_balance;
  DragSummary summary;
  Positions x = sheet.rest;
  std::vector<double> errors;
  double s = 0;
  const double step = 5e-4;
  int solves = 0, converged = 0, iterations = 0, factorizations = 0, krylov = 0, predicted = 0;
  double worst = 0;
  std::vector<double> solve_cpu;  // per solve: the drag's snaps are a few long ones among many short
  const double start = now();
  while (solves < 200 && now() - start < 60)
  {
    sheet.pullTo(s += step);
    const double solve_start = cpuNow();
    const CurvedReport r = solver.solve(x, sheet.pins);
    solve_cpu.push_back(cpuNow() - solve_start);
    ++solves;
    summary.lbfgs_steps += r.lbfgs_steps;
    summary.handed_over += r.handed_over;
    if (accuracy && solves % check_every == 0 && r.converged)
    {
      CurvedSolver exact(sheet.mesh, sheet.scene.paper);
      exact.options().tolerance = 1e-11;
      exact.options().predict = false;
      Positions balance = x;
      if (exact.solve(balance, sheet.pins).converged)
        errors.push_back(std::sqrt((balance - x).colwise().squaredNorm().maxCoeff()) / sheet.scene.paper.scale());
    }
    converged += r.converged;
    iterations += r.iterations;
    factorizations += r.factorizations;
    krylov += r.krylov_steps;
    predicted += r.predicted;
    worst = std::max(worst, r.max_force);
  }
  const double seconds = now() - start;
  double cpu = 0;  // the drag's solves alone (without the accuracy check's)
  for (double c : solve_cpu)
    cpu += c;
  std::vector<double> sorted = solve_cpu;
  std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
  const double median = sorted[sorted.size() / 2];
  // Solves over five times the median: the start off the flat sheet and the snaps.
  int slow = 0;
  double slow_cpu = 0;
  for (double c : solve_cpu)
    if (c > 5 * median)
    {
      ++slow;
      slow_cpu += c;
    }
  csv << sheet.mesh.nodes.size() << ',' << solves << ',' << converged << ',' << iterations << ',' << factorizations
      << ',' << krylov << ',' << predicted << ',' << seconds << ',' << cpu << ',' << solves / seconds << ','
      << solves / cpu << ',' << median * 1e3 << ',' << slow << ',' << slow_cpu << ',' << step << ','
      << solver.options().tolerance << ',' << worst << '\n';
  if (accuracy && !errors.empty())
  {
    std::vector<double> sorted_errors = errors;
    std::sort(sorted_errors.begin(), sorted_errors.end());
    *accuracy << sheet.mesh.nodes.size() << ',' << tolerance << ',' << solves << ',' << converged << ',' << cpu << ','
              << solves / cpu << ',' << errors.size() << ',' << sorted_errors[sorted_errors.size() / 2] << ','
              << sorted_errors.back() << '\n';
  }
  std::printf("%zu vertices, tolerance %g: %d small pulls (%d converged, %d predicted, %d iterations, %d "
              "factorisations, %d conjugate-gradient steps) in %.2f s (cpu %.2f s): %.2f solves/s (%.2f per cpu "
              "second), median solve %.1f ms of cpu\n",
              sheet.mesh.nodes.size(), tolerance, solves, converged, predicted, iterations, factorizations, krylov,
              seconds, cpu, solves / seconds, solves / cpu, median * 1e3);
  std::fflush(stdout);
  summary.solves = solves;
  summary.converged = converged;
  summary.iterations = iterations;
  summary.factorizations = factorizations;
  summary.cpu = cpu;
  summary.median_cpu = median;
  summary.errors = errors;
  return summary;
}

/// (a) The drag on the 10,000-vertex sheet of the target, and on smaller sheets: how large a
/// sheet one core drags at 30 solves per second.
void smallPulls(const std::string& dir)
{
  std::ofstream csv(dir + "/curved_speed.csv");
  csv << "vertices,solves,converged,iterations,factorizations,krylov_steps,predicted,seconds,cpu_seconds,"
         "solves_per_second,solves_per_cpu_second,median_solve_cpu_ms,slow_solves,slow_cpu_seconds,pull_step,"
         "tolerance,max_force\n";
  const double tolerance = CurvedSolveOptions().tolerance;
  for (int n : { 32, 45, 55, 71, 100 })
    dragSheet(n, tolerance, csv);
  // Speed against accuracy: the same drag on the 2,025-vertex sheet at other tolerances (the
  // rows of curved_speed.csv at the default are left as they are).
  std::ofstream accuracy(dir + "/curved_drag_accuracy.csv");
  accuracy << "vertices,tolerance,solves,converged,cpu_seconds,solves_per_cpu_second,checked,median_error,max_error\n";
  std::ostringstream ignored;
  for (double t : { 1e-4, 1e-6, 1e-8, 1e-10 })
    dragSheet(45, t, ignored, &accuracy);
}

/// (d) The drag of (a) by each static method at four sizes, every tenth balance checked against
/// a tight Newton balance (1e-11) from where the drag left it; and the quasi-Newton floor: one
/// back-substitution of the constant factor and one gradient pass (contact included), each the
/// mean of ten, at the drag's first shape.
void methods(const std::string& dir, const std::vector<int>& sizes, const std::vector<CurvedMethod>& which)
{
  std::ofstream csv(dir + "/curved_methods.csv");
  csv << "vertices,method,solves,converged,handed_over,iterations,lbfgs_steps,factorizations,cpu_seconds,"
         "solves_per_cpu_second,median_solve_cpu_ms,checked,median_error,max_error,floor_back_substitution_ms,"
         "floor_gradient_ms,floor_solves_per_cpu_second\n";
  const double tolerance = CurvedSolveOptions().tolerance;
  for (int n : sizes)
  {
    // The floor, on a constant matrix made as the solver makes it.
    PulledSheet sheet(n);
    sheet.pullTo(5e-4);
    std::vector<int> free_index(sheet.mesh.nodes.size());
    int free_count = 0;
    for (size_t v = 0; v < free_index.size(); ++v)
      free_index[v] = (static_cast<int>(v) == sheet.pins[0].node || static_cast<int>(v) == sheet.pins[1].node) ?
                          -1 :
                          free_count++;
    const CurvedTerms terms = curvedTerms(sheet.mesh, sheet.scene.paper, {});
    Positions x = sheet.rest;
    for (const CurvedPin& pin : sheet.pins)
      x.col(pin.node) = pin.position;
    Eigen::SparseMatrix<double> matrix = blockPattern(free_count, free_index, termGroups(terms));
    Eigen::VectorXd g = Eigen::VectorXd::Zero(3 * free_count);
    BlockHessian blocks{ &matrix };
    evaluateCurved(terms, x, { &free_index, &g, nullptr, &blocks });
    numerics::SpdFactorization factorization;
    double shift = 1e-11;
    while (!factorization.factorize(matrix, shift) && shift < 1e3)
      shift *= 100;
    constexpr int kRepeats = 10;
    double cpu_start = cpuNow();
    double sink = 0;
    for (int k = 0; k < kRepeats; ++k)
      sink += factorization.solve(g)[0];
    const double back_substitution = (cpuNow() - cpu_start) / kRepeats;
    CurvedSolver gradient_solver(sheet.mesh, sheet.scene.paper);
    sink += gradient_solver.maxForce(x, sheet.pins);  // builds the contact candidates, as the drag's first solve
    cpu_start = cpuNow();
    for (int k = 0; k < kRepeats; ++k)
      sink += gradient_solver.maxForce(x, sheet.pins);
    const double gradient = (cpuNow() - cpu_start) / kRepeats;
    if (!std::isfinite(sink))
      std::printf("(non-finite floor)\n");
    for (CurvedMethod method : which)
    {
      std::ostringstream ignored, accuracy;
      const DragSummary d = dragSheet(n, tolerance, ignored, &accuracy, method, 10);
      std::vector<double> errors = d.errors;
      std::sort(errors.begin(), errors.end());
      std::string name = method == CurvedMethod::Newton   ? "newton" :
                         constant_krylov_iterations > 0 ? "quasi_newton_krylov" :
                                                          "quasi_newton";
      if (check_every_balance)
        name += "_checked";
      csv << sheet.mesh.nodes.size() << ',' << name << ',' << d.solves << ',' << d.converged << ',' << d.handed_over
          << ',' << d.iterations << ',' << d.lbfgs_steps << ',' << d.factorizations << ',' << d.cpu << ','
          << d.solves / d.cpu << ',' << d.median_cpu * 1e3 << ',' << errors.size() << ','
          << (errors.empty() ? NAN : errors[errors.size() / 2]) << ',' << (errors.empty() ? NAN : errors.back())
          << ',' << back_substitution * 1e3 << ',' << gradient * 1e3 << ','
          << 1 / (back_substitution + gradient) << '\n';
      csv.flush();
      std::printf("  %s: %d quasi-Newton steps, %d handed over; error median %.3g, max %.3g; floor %.2f + %.2f ms\n",
                  name.c_str(),
                  d.lbfgs_steps, d.handed_over, errors.empty() ? NAN : errors[errors.size() / 2],
                  errors.empty() ? NAN : errors.back(), back_substitution * 1e3, gradient * 1e3);
      std::fflush(stdout);
    }
  }
}

double threadCpuNow()
{
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

std::string loadAverage()
{
  std::ifstream in("/proc/loadavg");
  std::string one, five, fifteen;
  in >> one >> five >> fifteen;
  return one + " " + five + " " + fifteen;
}

double percentile(std::vector<double> values, double p)
{
  if (values.empty())
    return NAN;
  std::sort(values.begin(), values.end());
  return values[std::min(values.size() - 1, static_cast<size_t>(std::ceil(p * values.size())) - (p > 0 ? 1 : 0))];
}

/// (e) The drag of (a) on an n × n sheet as anytime frames: the pointer moves 1/2000 of the pull
/// per frame at 30 Hz (the frames paced in wall time, as pointer events come), `count` frames,
/// then the release. Every `stride`-th frame's shape is kept and, after the drag, solved on to
/// 1e-10 by a Newton solver of its own (predict off: the balance nearest the shown shape); the
/// largest node distance over the side is the frame's error. Frames within 3 of an inertial
/// one (a loss of stability) are reported apart. One row per frame in curved_frames.csv.
void frames(const std::string& dir, int n, int count, int stride, const std::string& budget)
{
  PulledSheet sheet(n);
  AnytimeFrameOptions options;
  options.budget_in_thread_cpu = budget == "cpu";
  if (budget == "sync")
  {
    // The factor made in each frame at the state it shows (what a factorisation as fast as a
    // frame would give): the frames' accuracy without the background's lag; not anytime.
    options.background = false;
    options.refactor_frames = 1;
    options.frame_seconds = INFINITY;
  }
  AnytimeFrames anytime(sheet.mesh, sheet.scene.paper, {}, {}, options);
  // newton: the converged solver beside the frames, each pointer step solved to 1e-8 from the
  // last balance (predicted start), as the node's full solve does; one row per solve.
  const bool converged_solves = budget == "newton";
  CurvedSolver newton(sheet.mesh, sheet.scene.paper);
  newton.options().tolerance = 1e-8;
  Positions solved = sheet.rest;
  const std::string load_before = loadAverage();
  double t = now(), cpu = threadCpuNow();
  if (converged_solves ? !newton.solve(solved, sheet.pins).converged : !anytime.start(sheet.rest, sheet.pins))
    return;
  std::printf("%zu vertices, budget %s: start (first factorisation) %.0f ms wall, %.0f ms cpu; inertial density %.3g; "
              "load %s\n",
              sheet.mesh.nodes.size(), budget.c_str(), (now() - t) * 1e3, (threadCpuNow() - cpu) * 1e3,
              anytime.density(),
              load_before.c_str());
  std::fflush(stdout);
  struct Row
  {
    FrameReport report;
    double cpu = 0, error = NAN;
    std::vector<CurvedPin> pins;
  };
  std::vector<Row> rows;
  std::vector<std::pair<int, Positions>> kept;
  const double h = 1.0 / 30.0;
  const double drag_start = now(), process_start = cpuNow(), factor_cpu_start = anytime.factorCpuSeconds();
  double s = 0;
  for (int k = 1; k <= count; ++k)
  {
    const double due = drag_start + (k - 1) * h;
    if (now() < due)
      std::this_thread::sleep_for(std::chrono::duration<double>(due - now()));
    sheet.pullTo(s += 5e-4);
    const double frame_cpu = threadCpuNow();
    if (converged_solves)
    {
      const double solve_start = now();
      const CurvedReport solve = newton.solve(solved, sheet.pins);
      FrameReport r;
      r.seconds = now() - solve_start;
      r.max_force = solve.max_force;
      r.corrections = solve.iterations;
      r.refused = solve.converged ? 0 : 1;
      rows.push_back({ r, threadCpuNow() - frame_cpu, NAN, sheet.pins });
      if (k % stride == 0)
        kept.emplace_back(k - 1, solved);
      continue;
    }
    const Expected<FrameReport> r = anytime.frame(sheet.pins);
    if (!r)
    {
      std::printf("frame %d refused: %s\n", k, r.message().c_str());
      return;
    }
    rows.push_back({ *r, threadCpuNow() - frame_cpu, NAN, sheet.pins });
    if (k % stride == 0)
      kept.emplace_back(k - 1, anytime.positions());
  }
  const double drag_wall = now() - drag_start, drag_cpu = cpuNow() - process_start;
  const double drag_factor_cpu = anytime.factorCpuSeconds() - factor_cpu_start;
  const int drag_factorizations = anytime.factorizations();
  t = now();
  const ReleaseReport release = converged_solves ? ReleaseReport{} : anytime.release();
  const double release_wall = now() - t;
  const std::string load_after = loadAverage();
  // The tight balances, after the drag (not in its time).
  CurvedSolver exact(sheet.mesh, sheet.scene.paper);
  exact.options().tolerance = 1e-10;
  exact.options().predict = false;
  for (auto& [index, shape] : kept)
  {
    Positions balance = shape;
    if (exact.solve(balance, rows[index].pins).converged)
      rows[index].error = std::sqrt((balance - shape).colwise().squaredNorm().maxCoeff()) / sheet.scene.paper.scale();
  }
  // Near a loss of stability: within 3 frames of an inertial one.
  std::vector<char> near_snap(rows.size(), 0);
  for (size_t k = 0; k < rows.size(); ++k)
    if (rows[k].report.inertial)
      for (size_t j = k >= 3 ? k - 3 : 0; j <= std::min(rows.size() - 1, k + 3); ++j)
        near_snap[j] = 1;
  std::ofstream csv(dir + "/curved_frames_" + std::to_string(sheet.mesh.nodes.size()) + "_" + budget + ".csv");
  csv << "vertices,frame,pull,wall_ms,thread_cpu_ms,start_force,max_force,corrections,refused,inertial,factor_frame,"
         "contact_search,near_snap,error,solve_ms\n";
  std::vector<double> wall, frame_cpu, steady_errors, all_errors, solves;
  for (size_t k = 0; k < rows.size(); ++k)
  {
    const FrameReport& r = rows[k].report;
    wall.push_back(r.seconds);
    if (r.corrections + r.refused > 0)
      solves.push_back(r.solve_seconds / (r.corrections + r.refused));
    frame_cpu.push_back(rows[k].cpu);
    if (std::isfinite(rows[k].error))
    {
      all_errors.push_back(rows[k].error);
      if (!near_snap[k])
        steady_errors.push_back(rows[k].error);
    }
    csv << sheet.mesh.nodes.size() << ',' << k + 1 << ',' << 5e-4 * (k + 1) << ',' << r.seconds * 1e3 << ','
        << rows[k].cpu * 1e3 << ',' << r.start_force << ',' << r.max_force << ',' << r.corrections << ',' << r.refused
        << ',' << r.inertial << ',' << r.factor_frame << ',' << r.contact_search << ',' << int(near_snap[k]) << ','
        << rows[k].error << ',' << r.solve_seconds * 1e3 << '\n';
  }
  // Snaps: from the first inertial frame of a run to the first frame after it at force 1e-6.
  std::printf("  snaps (first inertial frame -> frames until force <= 1e-6):");
  for (size_t k = 0; k < rows.size(); ++k)
    if (rows[k].report.inertial && (k == 0 || !rows[k - 1].report.inertial))
    {
      size_t j = k;
      while (j < rows.size() && !(rows[j].report.max_force <= 1e-6 && !rows[j].report.inertial))
        ++j;
      if (j < rows.size())
        std::printf(" frame %zu: %zu frames (%.2f s);", k + 1, j - k, (j - k) * h);
      else
        std::printf(" frame %zu: not within the drag;", k + 1);
    }
  std::printf("\n");
  int inertial = 0, searches = 0, refused = 0;
  for (const Row& row : rows)
  {
    inertial += row.report.inertial;
    searches += row.report.contact_search;
    refused += row.report.refused;
  }
  std::printf("  %zu frames in %.2f s wall: frame wall p50 %.1f / p95 %.1f / max %.1f ms; frame thread cpu p50 %.1f / "
              "p95 %.1f / max %.1f ms; %d inertial, %d refused corrections, %d contact searches in a frame\n",
              rows.size(), drag_wall, percentile(wall, 0.5) * 1e3, percentile(wall, 0.95) * 1e3,
              percentile(wall, 1.0) * 1e3, percentile(frame_cpu, 0.5) * 1e3, percentile(frame_cpu, 0.95) * 1e3,
              percentile(frame_cpu, 1.0) * 1e3, inertial, refused, searches);
  std::printf("  one back-substitution (wall, median over frames) %.1f ms\n", percentile(solves, 0.5) * 1e3);
  std::printf("  factorising thread: %d factorisations, %.2f s cpu; the process %.2f s cpu over the drag's %.2f s\n",
              drag_factorizations, drag_factor_cpu, drag_cpu, drag_wall);
  std::printf("  error to the tight balance / side: steady frames (%zu checked) median %.3g, p95 %.3g, max %.3g; "
              "all checked (%zu) max %.3g\n",
              steady_errors.size(), percentile(steady_errors, 0.5), percentile(steady_errors, 0.95),
              percentile(steady_errors, 1.0), all_errors.size(), percentile(all_errors, 1.0));
  if (converged_solves)
  {
    int unconverged = 0;
    for (const Row& row : rows)
      unconverged += row.report.refused;
    std::printf("  newton: %d of %zu solves not converged to 1e-8; load %s\n", unconverged, rows.size(),
                load_after.c_str());
  }
  else
    std::printf("  release: %s at force %.3g in %.3f s (%d corrections, %d factorisations, %d Newton iterations); "
                "load %s\n",
                release.converged ? "converged" : "NOT converged", release.max_force, release_wall, release.corrections,
                release.factorizations, release.newton_iterations, load_after.c_str());
  std::fflush(stdout);
}

/// Bytes an RK4 step must move at least: four force evaluations, each reading the term lists
/// and the positions and writing the forces, plus the state vectors of the four stages (about
/// a dozen reads and writes of 3 doubles per vertex).
double rk4Bytes(const CurvedTerms& terms, size_t vertices)
{
  const double term_bytes = terms.stretch.size() * sizeof(StretchTerm) + terms.shear.size() * sizeof(ShearTerm) +
                            terms.bend.size() * sizeof(BendTerm);
  return 4 * (term_bytes + 2 * 24.0 * vertices) + 12 * 24.0 * vertices;
}

/// (b) Time per step against vertex count: one Newton iteration (contact, gradient, Hessian
/// assembly, factorisation, solve, line search: the difference of budgets of 2 and 1
/// iterations, so setup and the symbolic analysis cancel) and one RK4 step (budgets of 11 and
/// 1, over 10: one contact search more or less in two steps made the difference of 2 and 1
/// noise at 100,000 vertices), each from rest with the corner pulled a tenth of a mesh spacing; beside them one CHOLMOD
/// factorisation of the same Hessian (its analysis done first) and the RK4 step's bytes over
/// the triad bandwidth.
void scaling(const std::string& dir)
{
  constexpr int kRk4Steps = 10;
  double check = 0;
  const double bandwidth = virtual_origami::bench::triadBandwidth(&check);
  std::printf("triad bandwidth %.2f GB/s\n", bandwidth / 1e9);
  std::ofstream csv(dir + "/curved_scaling.csv");
  csv << "vertices,newton_iteration_seconds,newton_iteration_cpu_seconds,newton_factorizations,"
         "factorization_seconds,factorization_cpu_seconds,rk4_step_seconds,rk4_step_cpu_seconds,rk4_floor_seconds,rk4_bytes_per_step,"
         "triad_bytes_per_second\n";
  for (int n : { 32, 55, 100, 173, 316 })
  {
    PulledSheet sheet(n);
    sheet.pullTo(0.05 * sheet.mesh.spacing);  // the corner moves about a tenth of a spacing
    const auto run = [&](CurvedMethod method, int budget, int* factorizations) {
      CurvedSolveOptions options;
      options.method = method;
      options.tolerance = 0;
      options.max_iterations = budget;
      options.max_steps = budget;
      options.modified_newton_rate = 0;  // every iteration a fresh Hessian and factorisation
      CurvedSolver solver(sheet.mesh, sheet.scene.paper, {}, {}, options);
      Positions x = sheet.rest;
      const double start = now(), cpu_start = cpuNow();
      const CurvedReport r = solver.solve(x, sheet.pins);
      if (factorizations)
        *factorizations = r.factorizations;
      return std::pair<double, double>(now() - start, cpuNow() - cpu_start);
    };
    int f1 = 0, f2 = 0;
    const auto n1 = run(CurvedMethod::Newton, 1, &f1);
    const auto n2 = run(CurvedMethod::Newton, 2, &f2);
    const auto r1 = run(CurvedMethod::Rk4, 1, nullptr);
    const auto r3 = run(CurvedMethod::Rk4, 1 + kRk4Steps, nullptr);

    // The floor of an implicit step: one numeric factorisation of the Hessian at the start.
    std::vector<int> free_index(sheet.mesh.nodes.size());
    int free_count = 0;
    for (size_t v = 0; v < free_index.size(); ++v)
      free_index[v] = (static_cast<int>(v) == sheet.pins[0].node || static_cast<int>(v) == sheet.pins[1].node) ?
                          -1 :
                          free_count++;
    const CurvedTerms terms = curvedTerms(sheet.mesh, sheet.scene.paper, {});
    Positions x = sheet.rest;
    for (const CurvedPin& pin : sheet.pins)
      x.col(pin.node) = pin.position;
    Eigen::SparseMatrix<double> hessian = blockPattern(free_count, free_index, termGroups(terms));
    Eigen::VectorXd g = Eigen::VectorXd::Zero(3 * free_count);
    BlockHessian blocks{ &hessian };
    evaluateCurved(terms, x, { &free_index, &g, nullptr, &blocks });
    numerics::SpdFactorization factorization;
    double shift = 1e-6;
    while (!factorization.factorize(hessian, shift) && shift < 1e3)
      shift *= 10;
    const double start = now(), cpu_start = cpuNow();
    factorization.factorize(hessian, shift);
    const double factor = now() - start, factor_cpu = cpuNow() - cpu_start;

    const double bytes = rk4Bytes(terms, sheet.mesh.nodes.size());
    const double newton = n2.first - n1.first, newton_cpu = n2.second - n1.second;
    const double rk4 = (r3.first - r1.first) / kRk4Steps, rk4_cpu = (r3.second - r1.second) / kRk4Steps;
    csv << sheet.mesh.nodes.size() << ',' << newton << ',' << newton_cpu << ',' << f2 - f1 << ',' << factor << ','
        << factor_cpu << ',' << rk4 << ',' << rk4_cpu << ',' << bytes / bandwidth << ',' << bytes << ',' << bandwidth << '\n';
    std::printf("  %zu vertices: newton iteration %.1f ms (cpu %.1f, %d factorisations), one factorisation %.1f ms, "
                "rk4 step %.2f ms (cpu %.2f, floor %.3f ms)\n",
                sheet.mesh.nodes.size(), newton * 1e3, newton_cpu * 1e3, f2 - f1, factor * 1e3, rk4 * 1e3,
                rk4_cpu * 1e3, bytes / bandwidth * 1e3);
    std::fflush(stdout);
  }
}

/// (c) RK4's stability map: seed scene 1's sheet (spacing 0.2) one hand step into its pull,
/// at stretch moduli over three decades and steps around the predicted limit Δt = 2.83/ω_max
/// (the imaginary-axis reach of RK4; ω_max² the largest eigenvalue of M⁻¹H at the start).
/// Diverged: the solver's own check, or the force grown a thousandfold.
void stability(const std::string& dir)
{
  std::ofstream csv(dir + "/curved_stability.csv");
  csv << "stretch,omega_max,dt_limit,dt_over_limit,dt,steps,converged,diverged,max_force\n";
  const SeedScene scene = *seedScene(1);
  BubbleMeshOptions mesh_options;
  mesh_options.spacing = 0.2;
  const CurvedMesh mesh = *bubbleMesh(scene.paper, mesh_options);
  const Positions start = placeNodes(mesh, scene.paper);
  const std::vector<CurvedPin> pins = { { mesh.vertex_nodes[scene.fixed], start.col(mesh.vertex_nodes[scene.fixed]) },
                                        { mesh.vertex_nodes[scene.pulled], scene.pullAt(0.05) } };
  for (double stretch : { 0.1, 0.3, 1.0, 3.0, 10.0, 30.0, 100.0 })
  {
    CurvedMaterial material;
    material.stretch = stretch;
    const CurvedTerms terms = curvedTerms(mesh, scene.paper, material);
    std::vector<int> free_index(mesh.nodes.size());
    int free_count = 0;
    for (size_t v = 0; v < free_index.size(); ++v)
      free_index[v] = (static_cast<int>(v) == pins[0].node || static_cast<int>(v) == pins[1].node) ? -1 : free_count++;
    Positions x = start;
    for (const CurvedPin& pin : pins)
      x.col(pin.node) = pin.position;
    std::vector<Eigen::Triplet<double>> triplets;
    Eigen::VectorXd g = Eigen::VectorXd::Zero(3 * free_count);
    evaluateCurved(terms, x, { &free_index, &g, &triplets });
    Eigen::SparseMatrix<double> h(3 * free_count, 3 * free_count);
    h.setFromTriplets(triplets.begin(), triplets.end());
    Eigen::VectorXd inv_sqrt_mass(3 * free_count);
    for (size_t v = 0; v < free_index.size(); ++v)
      if (free_index[v] >= 0)
        inv_sqrt_mass.segment<3>(3 * free_index[v]).setConstant(1 / std::sqrt(terms.mass[v]));
    const Eigen::MatrixXd scaled = inv_sqrt_mass.asDiagonal() * Eigen::MatrixXd(h) * inv_sqrt_mass.asDiagonal();
    const double omega = std::sqrt(Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(scaled).eigenvalues().maxCoeff());
    const double limit = 2.83 / omega;
    for (int k = 0; k <= 12; ++k)
    {
      const double ratio = 0.4 + 0.1 * k;  // 0.4 … 1.6 of the limit
      CurvedSolveOptions options;
      options.method = CurvedMethod::Rk4;
      options.time_step = ratio * limit;
      options.tolerance = 1e-6;
      options.max_steps = 3000;
      CurvedSolver solver(mesh, scene.paper, material, {}, options);
      Positions y = start;
      const double initial = solver.maxForce(y, pins);
      const CurvedReport r = solver.solve(y, pins);
      const bool diverged = r.diverged || !(r.max_force < 1e3 * initial);
      csv << stretch << ',' << omega << ',' << limit << ',' << ratio << ',' << options.time_step << ',' << r.iterations
          << ',' << r.converged << ',' << diverged << ',' << r.max_force << '\n';
    }
  }
}
}  // namespace

int main(int argc, char** argv)
{
  const std::string dir = argc > 1 ? argv[1] : "docs/bench";
  const std::string part = argc > 2 ? argv[2] : "";
  // The factorisations' and back-substitutions' speed is the BLAS kernels'.
  std::cout << "BLAS kernels: " << numerics::blasKernels() << "\n";
  if (part.empty() || part == "pulls")
    smallPulls(dir);
  if (part.empty() || part == "stability")
    stability(dir);
  if (part.empty() || part == "scaling")
    scaling(dir);
  if (part == "frames")
  {
    // curved_speed_bench dir frames [grid side, 100] [frames, 200] [every how many frames checked, 2]
    //   [wall|cpu|sync: the frames' budget counted in wall time (default) or in the frame thread's
    //   CPU time; sync: the factor made in every frame, six corrections, no budget; newton: each
    //   pointer step solved to 1e-8 by Newton instead, the converged solver beside the frames]
    frames(dir, argc > 3 ? std::stoi(argv[3]) : 100, argc > 4 ? std::stoi(argv[4]) : 200,
           argc > 5 ? std::stoi(argv[5]) : 2, argc > 6 ? argv[6] : "wall");
  }
  if (part == "methods")
  {
    // curved_speed_bench dir methods [grid sides, e.g. 32,100] [newton|quasi_newton|quasi_newton_krylov, each optionally _checked]
    std::vector<int> sizes = { 32, 50, 71, 100 };
    if (argc > 3)
    {
      sizes.clear();
      std::stringstream list(argv[3]);
      for (std::string item; std::getline(list, item, ',');)
        sizes.push_back(std::stoi(item));
    }
    std::vector<CurvedMethod> which = { CurvedMethod::QuasiNewton, CurvedMethod::Newton };
    if (argc > 4)
    {
      std::string method = argv[4];
      const std::string checked = "_checked";
      if (method.size() > checked.size() && method.compare(method.size() - checked.size(), checked.size(), checked) == 0)
      {
        check_every_balance = true;
        method.resize(method.size() - checked.size());
      }
      which = { method == "newton" ? CurvedMethod::Newton : CurvedMethod::QuasiNewton };
      if (method == "quasi_newton_krylov")
        constant_krylov_iterations = 30;
    }
    methods(dir, sizes, which);
  }
  std::cout << "wrote the CSV files into " << dir << "\n";
  return 0;
}

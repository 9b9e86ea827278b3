// Curved-paper solvers (SPEC §4.2): the seed's RK4 against the static Newton method on seed
// 002's scenes 1–3 at three mesh resolutions, and static solves per second of a small pull
// on a 10,000-node sheet. Writes one CSV (default docs/bench/curved_solvers.csv); every
// ratio comes from this one run on this machine. Then speed against accuracy on a strip of
// copy paper against Euler's elastica (curved_elastica.csv beside it; see elasticaSpeed).
//
//   curved_bench [output.csv] [rk4 budget seconds per case, default 4]
//   curved_bench elastica [output directory, default docs/bench] [budget seconds per RK4 or
//                quasi-Newton solve, default 20]   (that part alone)
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>

#include "virtual_origami/curved/bubble_mesh.h"
#include "virtual_origami/curved/elastica.h"
#include "virtual_origami/curved/paper_material.h"
#include "virtual_origami/curved/seed_scenes.h"
#include "virtual_origami/curved/strip_scenes.h"
#include "bench_common.h"

using namespace virtual_origami::core;
using virtual_origami::bench::cpuNow;
using virtual_origami::bench::gridMesh;
using virtual_origami::bench::now;

namespace
{
/// Speed against accuracy for curved paper: a 20 × 2 cm strip of ν = 0 copy paper (the scene of
/// Elastica.StripTurned45DegreesConvergesToTheElastica), clamped at one end, the other end
/// turned by 45° and held at (0.8, 0.3) × its length, solved from the balance of the end
/// turned by 40° (the elastica's shape for it: the end turned on by 5° in one solve, as a hand
/// turns it, the strip's length unchanged, so no stretch flings the RK4 dynamics) by each method
/// at each spacing and two balance tolerances, each solve with a budget. Error: the mid-line's largest distance from the
/// elastica's (integrated to 1e-10 of the length, Elastica.ShootingMeetsTheEndConditions…),
/// over the length; time: the solve's CPU time. A solve that runs out of its budget is
/// written with converged 0 and the error of where it stopped.
int elasticaSpeed(const std::string& directory, double budget)
{
  const std::string out_path = directory + "/curved_elastica.csv";
  std::ofstream csv(out_path);
  if (!csv)
  {
    std::cerr << "cannot write " << out_path << "\n";
    return 1;
  }
  csv << "mesher,per_width,spacing,nodes,method,tolerance,converged,iterations,cpu_seconds,error\n";
  const double length = 0.2, width = 0.02, angle = M_PI / 4;
  const Eigen::Vector2d end = Eigen::Vector2d(0.8, 0.3) * length;
  PaperMaterial paper = *paperPreset("copy_paper");
  paper.poisson_ratio = 0.0;
  const CurvedMaterial material = stripMaterial(*curvedMaterial(paper));
  const StripScene scene = *stripScene(length, width, true);
  const HeldElastica elastica = *heldElastica(length, end, angle);
  const ElasticaCurve start_curve = heldElastica(length, end, angle - 5 * M_PI / 180)->curve;
  const double bending_force = bendingStiffness(paper) / length;
  for (double per_width : { 2.0, 4.0, 8.0, 16.0 })
  {
    CurvedMesh mesh = *meshStrip(scene, StripMesher::Bubble, width / per_width);
    holdStripZones(scene, mesh);
    const std::vector<CurvedPin> pins = stripPins(scene, mesh, end, angle);
    for (CurvedMethod method : { CurvedMethod::Newton, CurvedMethod::QuasiNewton, CurvedMethod::Rk4 })
      for (double share : { 1e-2, 1e-4 })
      {
        CurvedSolveOptions options;
        options.method = method;
        // Forces as a share of D/L (the bending force on a node), as in the closed-form tests.
        options.tolerance = share * bending_force / (material.stretch * mesh.spacing);
        options.max_iterations = 500;
        options.max_steps = 100000000;
        options.max_seconds = method == CurvedMethod::Newton ? 120.0 : budget;
        options.hand_over = false;  // the quasi-Newton method on its own
        options.lbfgs_iterations = 5000;  // its budget (it does not watch the clock)
        const char* name = method == CurvedMethod::Newton ? "newton" :
                           method == CurvedMethod::QuasiNewton ? "quasi_newton" : "rk4";
        CurvedSolver solver(mesh, scene.paper, material, {}, options);
        Positions x = stripAlong(scene, mesh, start_curve);
        const double start = cpuNow();
        const CurvedReport report = solver.solve(x, pins);
        const double cpu = cpuNow() - start;
        const Expected<double> error = midlineDeviation(scene, mesh, x, elastica.curve);
        csv << "bubble," << per_width << "," << mesh.spacing << "," << mesh.nodes.size() << "," << name << "," << share
            << "," << report.converged << "," << report.iterations << "," << cpu << ","
            << (error.ok() ? *error : NAN) << "\n";
        std::printf("elastica 45° b/%-2.0f %5zu nodes %-12s tolerance %.0e D/L: converged %d, %6d iterations, %8.3f s "
                    "CPU, mid-line off by %.2e of the length\n",
                    per_width, mesh.nodes.size(), name, share, report.converged, report.iterations, cpu,
                    error.ok() ? *error : NAN);
        std::fflush(stdout);
      }
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv)
{
  if (argc > 1 && std::string(argv[1]) == "elastica")
    return elasticaSpeed(argc > 2 ? argv[2] : "docs/bench", argc > 3 ? std::atof(argv[3]) : 20.0);
  const std::string out_path = argc > 1 ? argv[1] : "docs/bench/curved_solvers.csv";
  const double rk4_budget = argc > 2 ? std::atof(argv[2]) : 4.0;
  std::ofstream csv(out_path);
  if (!csv)
  {
    std::cerr << "cannot write " << out_path << "\n";
    return 1;
  }
  csv << "case,scene,spacing,nodes,method,converged,steps,seconds,max_force,rk4_time_over_newton,solves_per_second\n";

  // 1. One hand step (the first 1/20 of each scene's pull) from the sheet at rest, solved to
  //    the same force tolerance by both methods.
  const double tolerance = 1e-6;
  for (int number = 1; number <= 3; ++number)
    for (double spacing : { 0.2, 0.14, 0.1 })
    {
      const Expected<SeedScene> scene = seedScene(number);
      BubbleMeshOptions mesh_options;
      mesh_options.spacing = spacing;
      const Expected<CurvedMesh> mesh = bubbleMesh(scene->paper, mesh_options);
      if (!scene.ok() || !mesh.ok())
      {
        std::cerr << "scene " << number << ": " << (scene.ok() ? mesh.message() : scene.message()) << "\n";
        return 1;
      }
      const Positions start = placeNodes(*mesh, scene->paper);
      const std::vector<CurvedPin> pins = { { mesh->vertex_nodes[scene->fixed], start.col(mesh->vertex_nodes[scene->fixed]) },
                                            { mesh->vertex_nodes[scene->pulled], scene->pullAt(0.05) } };
      CurvedReport reports[2];
      for (int m = 0; m < 2; ++m)
      {
        CurvedSolveOptions options;
        options.method = m == 0 ? CurvedMethod::Newton : CurvedMethod::Rk4;
        options.tolerance = tolerance;
        options.max_seconds = m == 0 ? 60.0 : rk4_budget;
        Positions x = start;
        CurvedSolver solver(*mesh, scene->paper, {}, {}, options);
        reports[m] = solver.solve(x, pins);
      }
      for (int m = 0; m < 2; ++m)
      {
        const CurvedReport& r = reports[m];
        // RK4 stopped by its budget (converged 0): the true ratio is larger still.
        const double speedup = reports[1].seconds / reports[0].seconds;
        csv << "pull_step," << number << "," << spacing << "," << mesh->nodes.size() << ","
            << (m == 0 ? "newton" : "rk4") << "," << r.converged << "," << r.iterations << "," << r.seconds << ","
            << r.max_force << "," << speedup << ",\n";
        std::printf("scene %d spacing %.2f nodes %zu %s: converged %d steps %d %.3f s force %.2e\n", number, spacing,
                    mesh->nodes.size(), m == 0 ? "newton" : "rk4", r.converged, r.iterations, r.seconds, r.max_force);
      }
    }

  // 2. A 100 × 100 sheet (10,000 nodes), three corners held, the fourth lifted by 1e-3 of the
  //    side per solve, each static solve warm-started from the last balance.
  const Paper sheet = Paper::square(1.0);
  const CurvedMesh grid = gridMesh(sheet, 100);
  CurvedSolveOptions options;
  options.tolerance = tolerance;
  CurvedSolver solver(grid, sheet, {}, {}, options);
  Positions x = placeNodes(grid, sheet);
  std::vector<CurvedPin> pins;
  for (int v = 0; v < 4; ++v)
    pins.push_back({ grid.vertex_nodes[v], sheet.vertices[v].folded });
  const double t0 = now();
  int solves = 0, converged = 0, iterations = 0;
  double last_force = 0;
  while (solves < 30 && now() - t0 < 60)
  {
    pins[0].position.z() += 1e-3;
    const CurvedReport r = solver.solve(x, pins);
    ++solves;
    converged += r.converged;
    iterations += r.iterations;
    last_force = r.max_force;
  }
  const double seconds = now() - t0;
  csv << "sheet_small_pull,0," << grid.spacing << "," << grid.nodes.size() << ",newton," << converged << "/" << solves
      << "," << iterations << "," << seconds << "," << last_force << ",," << solves / seconds << "\n";
  std::printf("10k sheet: %d solves (%d converged, %d Newton iterations) in %.2f s: %.2f solves/s\n", solves, converged,
              iterations, seconds, solves / seconds);
  const size_t slash = out_path.find_last_of('/');
  return elasticaSpeed(slash == std::string::npos ? "." : out_path.substr(0, slash), 20.0);
}

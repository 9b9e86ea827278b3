// Curved-paper solvers (SPEC §4.2): the seed's RK4 against the static Newton method on seed
// 002's scenes 1–3 at three mesh resolutions, and static solves per second of a small pull
// on a 10,000-node sheet. Writes one CSV (default docs/bench/curved_solvers.csv); every
// ratio comes from this one run on this machine.
//
//   curved_bench [output.csv] [rk4 budget seconds per case, default 4]
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>

#include "virtual_origami/curved/bubble_mesh.h"
#include "virtual_origami/curved/seed_scenes.h"
#include "bench_common.h"

using namespace virtual_origami::core;
using virtual_origami::bench::gridMesh;
using virtual_origami::bench::now;

int main(int argc, char** argv)
{
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
  return 0;
}

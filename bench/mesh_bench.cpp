// The two meshers (SPEC §4.2): the seed's bubble mesh and CGAL's Delaunay refinement with
// Lloyd smoothing, on the reference crease patterns at several spacings — node and triangle
// counts, smallest angle, mean radius ratio, share of well-shaped triangles, time; then mesh
// resolution against error and time on seed scene 1 with each mesher, the error measured
// against the finest mesh's solution. Writes two CSVs; every figure from this one run.
//
//   mesh_bench [output directory, default docs/bench] [all | quality | resolution]
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

#include "bench_common.h"
#include "virtual_origami/core/crease.h"
#include "virtual_origami/core/reference_patterns.h"
#include "virtual_origami/curved/bubble_mesh.h"
#include "virtual_origami/curved/cgal_mesh.h"
#include "virtual_origami/curved/seed_scenes.h"

using namespace virtual_origami::core;
using virtual_origami::bench::alignedTo;

namespace
{
double now()
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

constexpr double kDeg = M_PI / 180;

struct Pattern
{
  std::string name;
  Paper paper;
};

std::vector<Pattern> referencePatterns()
{
  std::vector<Pattern> patterns;
  patterns.push_back({ "square", Paper::square(1.0) });
  Paper diagonal = Paper::square(1.0);
  CreaseRequest request;
  request.start = Vec3(1, 0, 0);
  request.end = Vec3(0, 1, 0);
  if (crease(diagonal, request).ok())
    patterns.push_back({ "diagonal", diagonal });
  patterns.push_back({ "miura_3x3", miuraOri(3, 3, 1.0, 1.0, 60 * kDeg) });
  patterns.push_back({ "degree4", degree4Vertex({ M_PI / 2, M_PI / 2, M_PI / 2, M_PI / 2 }) });
  // Sectors 30°, 90°, 150°, 90°: corners of 15° where the 150° sector meets the sheet's side.
  patterns.push_back({ "degree4_narrow", degree4Vertex({ 30 * kDeg, 90 * kDeg, 150 * kDeg, 90 * kDeg }) });
  return patterns;
}

using Mesher = std::function<Expected<CurvedMesh>(const Paper&, double spacing)>;

Expected<CurvedMesh> bubble(const Paper& paper, double spacing)
{
  BubbleMeshOptions options;
  options.spacing = spacing;
  return bubbleMesh(paper, options);
}

Expected<CurvedMesh> cgal(const Paper& paper, double spacing)
{
  CgalMeshOptions options;
  options.spacing = spacing;
  return cgalMesh(paper, options);
}

/// The solution's positions at probe points of the crease pattern (a grid over the sheet),
/// interpolated in the triangles that hold them.
Positions probe(const CurvedMesh& mesh, const Positions& positions, const CurvedMesh& probes)
{
  return transferNodes(mesh, positions, probes, Positions::Zero(3, static_cast<Eigen::Index>(probes.nodes.size())));
}

using Meshers = std::vector<std::pair<std::string, Mesher>>;

/// Quality and time of each mesher on each pattern, spacing relative to the sheet.
bool qualityTable(const std::string& path, const Meshers& meshers)
{
  std::ofstream csv(path);
  if (!csv)
  {
    std::cerr << "cannot write " << path << "\n";
    return false;
  }
  csv << "pattern,mesher,spacing,nodes,triangles,min_angle_deg,max_angle_deg,mean_radius_ratio,share_45_75,mesh_ms\n";
  for (const Pattern& pattern : referencePatterns())
    for (double relative : { 0.2, 0.1, 0.05, 0.025 })
      for (const auto& [name, mesher] : meshers)
      {
        const double spacing = relative * pattern.paper.scale();
        // Best of three: the time of the mesher, not of the machine's other load.
        double best = 1e30;
        Expected<CurvedMesh> mesh = Expected<CurvedMesh>::failure("not run");
        for (int r = 0; r < 3; ++r)
        {
          const double t0 = now();
          mesh = mesher(pattern.paper, spacing);
          best = std::min(best, now() - t0);
        }
        if (!mesh.ok())
        {
          std::cerr << pattern.name << " " << name << " " << spacing << ": " << mesh.message() << "\n";
          return false;
        }
        const MeshQuality q = meshQuality(*mesh, pattern.paper);
        csv << pattern.name << "," << name << "," << spacing << "," << mesh->nodes.size() << ","
            << mesh->triangles.size() << "," << q.min_angle / kDeg << "," << q.max_angle / kDeg << ","
            << q.mean_radius_ratio << "," << q.well_shaped << "," << best * 1e3 << "\n";
        std::printf("%-15s %-6s h %.4f: %5zu nodes %5zu triangles, angles %5.1f°–%5.1f°, 2r/R %.3f, 45–75° %.2f, "
                    "%.1f ms\n",
                    pattern.name.c_str(), name.c_str(), spacing, mesh->nodes.size(), mesh->triangles.size(),
                    q.min_angle / kDeg, q.max_angle / kDeg, q.mean_radius_ratio, q.well_shaped, best * 1e3);
        std::fflush(stdout);
      }
  return true;
}

/// Mesh resolution against error and time: seed scene 1's pull to a fifth (corner a turned
/// 36° up, a smooth curl) in four steps, with each mesher at each spacing; the error is the
/// RMS distance, over a 21 × 21 grid of probe points, from the solution on the finest mesh
/// after the best rigid fit, relative to the side.
bool resolutionSweep(const std::string& path, const Meshers& meshers)
{
  std::ofstream csv(path);
  const Expected<SeedScene> scene = seedScene(1);
  if (!csv || !scene.ok())
  {
    std::cerr << "cannot write " << path << " or " << scene.message() << "\n";
    return false;
  }
  CurvedMesh probes;
  for (int i = 0; i <= 20; ++i)
    for (int j = 0; j <= 20; ++j)
    {
      MeshNode node;
      node.crease_pattern = Vec2(0.05 * i, 0.05 * j);
      probes.nodes.push_back(node);
    }
  SeedSceneOptions options;
  options.steps = 4;
  options.until = 0.2;
  // Card rather than paper: q/k = 1e-2 side² puts the bending length at a tenth of the side,
  // which the meshes resolve. At paper's 1e-6 the curl's shape is set by where the mesh lets
  // it bend (membrane locking) and does not converge under refinement.
  options.material.bend = 1e-2;
  struct Solution
  {
    Positions at_probes;
    size_t nodes = 0;
    double seconds = 0;
    bool passed = false;
  };
  const auto solve = [&](const Mesher& mesher, double spacing) -> std::optional<Solution> {
    const Expected<CurvedMesh> mesh = mesher(scene->paper, spacing);
    if (!mesh.ok())
    {
      std::cerr << "scene 1 at " << spacing << ": " << mesh.message() << "\n";
      return std::nullopt;
    }
    const double t0 = now();
    const SeedSceneRun run = runSeedSceneOn(*scene, *mesh, options);
    Solution s;
    s.seconds = now() - t0;
    s.passed = run.passed();
    s.nodes = run.mesh.nodes.size();
    s.at_probes = probe(run.mesh, run.positions, probes);
    return s;
  };
  const double finest = 0.035;
  const std::optional<Solution> reference = solve(cgal, finest);
  if (!reference)
    return false;
  std::printf("scene 1 reference: cgal h %.3f, %zu nodes, %.2f s, passed %d\n", finest, reference->nodes,
              reference->seconds, reference->passed);
  csv << "scene,mesher,spacing,nodes,passed,solve_seconds,rms_error,max_error\n";
  csv << "1,cgal," << finest << "," << reference->nodes << "," << reference->passed << "," << reference->seconds
      << ",0,0\n";
  for (const auto& [name, mesher] : meshers)
    for (double spacing : { 0.2, 0.14, 0.1, 0.07, 0.05 })
    {
      const std::optional<Solution> s = solve(mesher, spacing);
      if (!s)
        return false;
      const Eigen::VectorXd distance =
          (alignedTo(s->at_probes, reference->at_probes) - reference->at_probes).colwise().norm();
      const double rms = std::sqrt(distance.squaredNorm() / static_cast<double>(distance.size()));
      csv << "1," << name << "," << spacing << "," << s->nodes << "," << s->passed << "," << s->seconds << "," << rms
          << "," << distance.maxCoeff() << "\n";
      std::printf("scene 1 %-6s h %.2f: %4zu nodes, %.2f s, passed %d, error rms %.2e max %.2e\n", name.c_str(),
                  spacing, s->nodes, s->seconds, s->passed, rms, distance.maxCoeff());
      std::fflush(stdout);
    }
  return true;
}
}  // namespace

int main(int argc, char** argv)
{
  const std::string dir = argc > 1 ? argv[1] : "docs/bench";
  const std::string part = argc > 2 ? argv[2] : "all";
  const Meshers meshers = { { "bubble", bubble }, { "cgal", cgal } };
  if ((part == "all" || part == "quality") && !qualityTable(dir + "/meshers.csv", meshers))
    return 1;
  if ((part == "all" || part == "resolution") && !resolutionSweep(dir + "/mesh_resolution.csv", meshers))
    return 1;
  return 0;
}

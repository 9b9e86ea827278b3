#include <gtest/gtest.h>
#include <cstdio>
#include "virtual_origami/curved/paper_material.h"
#include "virtual_origami/curved/plate_bending.h"
#include "virtual_origami/curved/strip_scenes.h"
namespace virtual_origami::core
{
TEST(Scratch, PlateEnergies)
{
  const PaperMaterial paper = *paperPreset("copy_paper");
  CurvedMaterial m = *curvedMaterial(paper);
  m.plate_bending = true;
  m.poisson_ratio = paper.poisson_ratio;
  m.bend = bendingStiffness(paper);
  const double b = 0.02, D = m.bend, nu = paper.poisson_ratio;
  const StripScene scene = *stripScene(0.1, b, false);
  for (StripMesher mesher : { StripMesher::Bubble, StripMesher::Cgal })
    for (int per : { 4, 8, 16 })
    {
      const CurvedMesh mesh = *meshStrip(scene, mesher, b / per);
      const CurvedTerms terms = curvedTerms(mesh, scene.paper, m);
      double area = 0;
      for (size_t t = 0; t < mesh.triangles.size(); ++t) area += mesh.restArea(t);
      const double k = 1e-2;
      auto energy = [&](double kx, double ky, double kxy) {
        Positions x(3, mesh.nodes.size());
        for (size_t v = 0; v < mesh.nodes.size(); ++v)
        {
          const Vec2 p = mesh.nodes[v].crease_pattern;
          const double y = p.y() - b / 2;
          x.col(v) = Vec3(p.x(), p.y(), 0.5 * (kx * p.x() * p.x() + ky * y * y + 2 * kxy * p.x() * y));
        }
        return evaluateCurved(terms, x).bend;
      };
      const double cyl = energy(k, 0, 0) / (0.5 * D * k * k * area);
      const double cyly = energy(0, k, 0) / (0.5 * D * k * k * area);
      const double twist = energy(0, 0, k) / (0.5 * D * 2 * (1 - nu) * k * k * area);
      // beam: minimise over ky
      const double e0 = energy(k, 0, 0), ep = energy(k, k, 0), em = energy(k, -k, 0);
      const double slope = (ep - em) / 2, curv = ep + em - 2 * e0;
      const double beam = (e0 - slope * slope / (2 * curv)) / (0.5 * D * (1 - nu * nu) * k * k * area);
      std::printf("%s b/%d: cyl %.4f cyly %.4f twist %.4f beam %.4f (best ky/kx %.3f)\n", mesher == StripMesher::Bubble ? "bubble" : "cgal", per, cyl, cyly, twist, beam, -slope / curv);
    }
}
}  // namespace virtual_origami::core

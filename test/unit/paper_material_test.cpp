// Paper in physical units: the mesh's moduli give a plate's energies (uniform stretch, shear
// and bend of a meshed sheet against ½·E h·ε², ½·G h·γ², ½·D·κ² per area, on both meshers),
// and bad materials, meshes finer than the paper is thick and pins off the sheet are refused.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "virtual_origami/curved/paper_material.h"
#include "virtual_origami/curved/strip_scenes.h"

namespace virtual_origami::core
{
namespace
{
struct Energies
{
  double stretch_shear = 0.0, bend = 0.0;
};

/// The mesh's energy with every node moved by `map` from its rest position.
template <class Map>
Energies energyOf(const CurvedMesh& mesh, const Paper& paper, const CurvedMaterial& material, Map map)
{
  Positions x(3, mesh.nodes.size());
  for (size_t v = 0; v < mesh.nodes.size(); ++v)
    x.col(v) = map(mesh.nodes[v].crease_pattern);
  const CurvedEnergy e = evaluateCurved(curvedTerms(mesh, paper, material), x);
  return { e.stretch + e.shear, e.bend };
}

double meshArea(const CurvedMesh& mesh)
{
  double a = 0.0;
  for (size_t t = 0; t < mesh.triangles.size(); ++t)
    a += mesh.restArea(static_cast<int>(t));
  return a;
}
}  // namespace

TEST(PaperMaterial, Explore)
{
  const PaperMaterial paper = *paperPreset("copy_paper");
  const double b = 0.02;
  const StripScene scene = *stripScene(10 * b, b, false);
  for (StripMesher mesher : { StripMesher::Bubble, StripMesher::Cgal })
    for (double spacing : { b / 4, b / 8, b / 16 })
    {
      const CurvedMesh mesh = *meshStrip(scene, mesher, spacing);
      const double area = meshArea(mesh);
      for (bool cover : { false, true })
      {
        CurvedMaterial material = *curvedMaterial(paper);
        material.cover_edges = cover;
        const double kappa = 5.0, R = 1 / kappa;
        const Energies bend = energyOf(mesh, scene.paper, material, [&](const Vec2& p) {
          return Vec3(R * std::sin(p.x() / R), p.y(), R * (1 - std::cos(p.x() / R)));
        });
        const Energies bend_y = energyOf(mesh, scene.paper, material, [&](const Vec2& p) {
          return Vec3(p.x(), R * std::sin(p.y() / R), R * (1 - std::cos(p.y() / R)));
        });
        std::printf("%s spacing b/%.0f nodes %zu cover %d: bend %.5f bend_y %.5f\n",
                    mesher == StripMesher::Bubble ? "bubble" : "cgal", b / spacing, mesh.nodes.size(), cover,
                    bend.bend / (0.5 * bendingStiffness(paper) * kappa * kappa * area),
                    bend_y.bend / (0.5 * bendingStiffness(paper) * kappa * kappa * area));
      }
    }
}

}  // namespace virtual_origami::core

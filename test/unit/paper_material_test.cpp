// Paper in physical units: the mesh's moduli give a plate's energies — exactly on a lattice of
// equilateral triangles (uniform stretch ½·E h·ε², shear ½·G h·γ², cylindrical bend ½·D·κ² per
// area), the even stretch exactly on any mesh — and bad materials, meshes finer than the paper
// is thick and pins off the sheet are refused with the running sheet left as it was.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>

#include "virtual_origami/curved/bubble_mesh.h"
#include "virtual_origami/curved/curved_follow.h"
#include "virtual_origami/curved/paper_material.h"
#include "virtual_origami/curved/plate_bending.h"
#include "virtual_origami/curved/strip_scenes.h"

namespace virtual_origami::core
{
namespace
{
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

/// A lattice of equilateral triangles of side `side`, `columns` × `rows`, inside a square sheet.
CurvedMesh latticeMesh(const Paper& paper, double side, int columns, int rows)
{
  CurvedMesh mesh;
  const double height = std::sqrt(3.0) / 2 * side;
  const auto node = [&](int i, int j) { return j * (columns + 1) + i; };
  for (int j = 0; j <= rows; ++j)
    for (int i = 0; i <= columns; ++i)
    {
      MeshNode n;
      n.crease_pattern = Vec2(side * (1 + i + 0.5 * (j % 2)), height * (1 + j));
      n.paper_face = 0;
      mesh.nodes.push_back(n);
    }
  for (int j = 0; j < rows; ++j)
    for (int i = 0; i < columns; ++i)
    {
      if (j % 2 == 0)
      {
        mesh.triangles.push_back({ { node(i, j), node(i + 1, j), node(i, j + 1) }, 0 });
        mesh.triangles.push_back({ { node(i + 1, j), node(i + 1, j + 1), node(i, j + 1) }, 0 });
      }
      else
      {
        mesh.triangles.push_back({ { node(i, j), node(i + 1, j + 1), node(i, j + 1) }, 0 });
        mesh.triangles.push_back({ { node(i, j), node(i + 1, j), node(i + 1, j + 1) }, 0 });
      }
    }
  mesh.spacing = side;
  EXPECT_TRUE(linkMesh(mesh, paper).ok());
  return mesh;
}

template <class Map>
Positions moved(const CurvedMesh& mesh, Map map)
{
  Positions x(3, mesh.nodes.size());
  for (size_t v = 0; v < mesh.nodes.size(); ++v)
    x.col(v) = map(mesh.nodes[v].crease_pattern);
  return x;
}

double meshArea(const CurvedMesh& mesh)
{
  double a = 0.0;
  for (size_t t = 0; t < mesh.triangles.size(); ++t)
    a += mesh.restArea(static_cast<int>(t));
  return a;
}

/// Bending energy per area of a lattice away from its edges (where triangles have fewer hinges):
/// the mean energy of the hinges of each of the three directions whose four nodes lie between
/// `low` and `high`, each direction having half a hinge per triangle.
double innerBendingDensity(const CurvedMesh& mesh, const CurvedTerms& terms, const Positions& x, const Vec2& low,
                           const Vec2& high)
{
  const auto inside = [&](int n) {
    const Vec2& p = mesh.nodes[n].crease_pattern;
    return (p.array() > low.array()).all() && (p.array() < high.array()).all();
  };
  double energy[3] = { 0, 0, 0 };
  int count[3] = { 0, 0, 0 };
  for (const BendTerm& b : terms.bend)
  {
    if (!inside(b.a) || !inside(b.b) || !inside(b.left) || !inside(b.right))
      continue;
    const double phi = hingeAngle(x.col(b.a), x.col(b.b), x.col(b.left), x.col(b.right)) - b.rest;
    const Vec2 e = mesh.nodes[b.b].crease_pattern - mesh.nodes[b.a].crease_pattern;
    double angle = std::atan2(e.y(), e.x());
    if (angle < -1e-9)
      angle += M_PI;
    const int direction = static_cast<int>(std::lround(angle / (M_PI / 3))) % 3;
    energy[direction] += 0.5 * b.weight * phi * phi;
    ++count[direction];
  }
  const double triangle = std::sqrt(3.0) / 4 * mesh.spacing * mesh.spacing;
  double density = 0.0;
  for (int d = 0; d < 3; ++d)
    density += energy[d] / count[d] * 0.5 / triangle;
  return density;
}

Vec3 onCylinder(const Vec2& p, double kappa, bool along_x)
{
  const double r = 1 / kappa, u = along_x ? p.x() : p.y();
  const Vec3 bent(0.0, 0.0, r * (1 - std::cos(u / r)));
  return along_x ? Vec3(r * std::sin(u / r), p.y(), bent.z()) : Vec3(p.x(), r * std::sin(u / r), bent.z());
}
}  // namespace

TEST(PaperMaterial, PresetsAreTheDocumentedPapers)
{
  const PaperMaterial copy = *paperPreset("copy_paper");
  EXPECT_DOUBLE_EQ(copy.thickness, 0.1e-3);
  EXPECT_DOUBLE_EQ(copy.youngs_modulus, 4e9);
  EXPECT_DOUBLE_EQ(copy.poisson_ratio, 0.3);
  EXPECT_DOUBLE_EQ(copy.areal_density, 0.080);
  EXPECT_DOUBLE_EQ(paperPreset("kami")->thickness, 0.07e-3);
  EXPECT_DOUBLE_EQ(paperPreset("kami")->areal_density, 0.060);
  EXPECT_DOUBLE_EQ(paperPreset("card")->thickness, 0.3e-3);
  EXPECT_DOUBLE_EQ(paperPreset("card")->areal_density, 0.300);
  for (const std::string& name : paperPresetNames())
    EXPECT_TRUE(curvedMaterial(*paperPreset(name)).ok()) << name;
  const Expected<PaperMaterial> unknown = paperPreset("vellum");
  ASSERT_FALSE(unknown.ok());
  EXPECT_NE(unknown.message().find("copy_paper, kami, card"), std::string::npos) << unknown.message();
  // D = E h³ / (12 (1 − ν²)): 80 g/m² copy paper, 0.366 mN·m.
  EXPECT_NEAR(bendingStiffness(copy), 4e9 * 1e-12 / (12 * 0.91), 1e-15);
}

TEST(PaperMaterial, MeshModuliFollowFromPlateTheory)
{
  const PaperMaterial paper = *paperPreset("kami");
  const CurvedMaterial m = *curvedMaterial(paper);
  const double eh = paper.youngs_modulus * paper.thickness, nu = paper.poisson_ratio;
  EXPECT_NEAR(m.stretch, eh / (std::sqrt(3.0) * (1 - nu)), 1e-12 * eh);
  EXPECT_NEAR(m.shear, 2 * eh * (1 - 3 * nu) / (9 * (1 - nu * nu)), 1e-12 * eh);
  EXPECT_TRUE(m.plate_bending);
  EXPECT_DOUBLE_EQ(m.bend, bendingStiffness(paper));
  EXPECT_DOUBLE_EQ(m.poisson_ratio, nu);
  const CurvedMaterial hinges = *curvedMaterial(paper, PaperBending::Hinges);
  EXPECT_FALSE(hinges.plate_bending);
  EXPECT_NEAR(hinges.bend, 2 / std::sqrt(3.0) * bendingStiffness(paper), 1e-12 * bendingStiffness(paper));
  EXPECT_DOUBLE_EQ(m.density, paper.areal_density);
  EXPECT_DOUBLE_EQ(m.thickness, paper.thickness);
}

TEST(PaperMaterial, OnAnEquilateralLatticeStretchShearAndHingeBendingCostThePlatesEnergies)
{
  const PaperMaterial paper = *paperPreset("copy_paper");
  const CurvedMaterial material = *curvedMaterial(paper, PaperBending::Hinges);
  const double side = 1e-3;
  const Paper sheet = Paper::square(0.05);
  const CurvedMesh mesh = latticeMesh(sheet, side, 30, 30);
  const CurvedTerms terms = curvedTerms(mesh, sheet, material);
  const double area = meshArea(mesh), eh = paper.youngs_modulus * paper.thickness, nu = paper.poisson_ratio;
  const double eps = 1e-7;  // the springs are exact lengths: their energy is quadratic to O(ε)
  const auto membrane = [&](const Positions& x) {
    const CurvedEnergy e = evaluateCurved(terms, x);
    return e.stretch + e.shear;
  };
  // Uniaxial stress in either direction (lateral contraction ν): ½·E h·ε².
  for (const bool along_x : { true, false })
  {
    const double ex = along_x ? eps : -nu * eps, ey = along_x ? -nu * eps : eps;
    const double e = membrane(moved(mesh, [&](const Vec2& p) { return Vec3(p.x() * (1 + ex), p.y() * (1 + ey), 0); }));
    EXPECT_NEAR(e / (0.5 * eh * eps * eps * area), 1.0, 1e-5) << (along_x ? "along x" : "along y");
  }
  // Simple shear γ: ½·G h·γ²; an even stretch: E h/(1 − ν)·ε².
  const double shear = membrane(moved(mesh, [&](const Vec2& p) { return Vec3(p.x() + eps * p.y(), p.y(), 0); }));
  EXPECT_NEAR(shear / (0.5 * shearStiffness(paper) * eps * eps * area), 1.0, 1e-5);
  const double even = membrane(moved(mesh, [&](const Vec2& p) { return Vec3(p.x() * (1 + eps), p.y() * (1 + eps), 0.0); }));
  EXPECT_NEAR(even / (eh / (1 - nu) * eps * eps * area), 1.0, 1e-5);
  // A cylindrical bend κ (across either direction of the lattice): ½·D·κ² per area, away from
  // the lattice's edges. κ·side = 1e-3: the chords' error is ~(κ·side)².
  const Vec2 low = mesh.nodes.front().crease_pattern + Vec2(3 * side, 3 * side);
  const Vec2 high = mesh.nodes.back().crease_pattern - Vec2(3 * side, 3 * side);
  const double kappa = 1.0, d = bendingStiffness(paper);
  for (const bool along_x : { true, false })
  {
    const Positions x = moved(mesh, [&](const Vec2& p) { return onCylinder(p, kappa, along_x); });
    EXPECT_NEAR(innerBendingDensity(mesh, terms, x, low, high) / (0.5 * d * kappa * kappa), 1.0, 1e-5)
        << (along_x ? "along x" : "along y");
  }
  // Bent both ways at once (z = ½·κ·(x² + y²)) it costs ½·(√3/2)·q·((tr K)² − (8/3)·det K): a
  // plate of Poisson ratio −1/3, whatever the paper's (documented in paper_material.cpp).
  const Vec2 c = 0.5 * (low + high);
  const Positions dome = moved(mesh, [&](const Vec2& p) {
    const Vec2 r = p - c;
    return Vec3(p.x(), p.y(), 0.5 * kappa * r.squaredNorm());
  });
  EXPECT_NEAR(innerBendingDensity(mesh, terms, dome, low, high) / (0.5 * d * (4.0 - 8.0 / 3.0) * kappa * kappa), 1.0,
              1e-3);
}

TEST(PaperMaterial, PlateBendingCostsThePlatesEnergyForAnyUniformCurvatureOnEitherMesher)
{
  // Each triangle's curvature is recovered exactly from three dihedrals (its sides', or a
  // neighbour's beside the sheet's edge): the whole strip, edges and clamp lines included, costs
  // ½·D·(ν (tr K)² + (1 − ν) K : K) per area, at every spacing. Slopes stay under 1e-3 (the
  // dihedrals are the slopes' jumps to that order squared).
  const PaperMaterial paper = *paperPreset("kami");
  CurvedMaterial material = stripMaterial(*curvedMaterial(paper));
  const double d = bendingStiffness(paper), nu = paper.poisson_ratio, kappa = 1e-2;
  const StripScene scene = *stripScene(0.1, 0.01, true);
  const Eigen::Matrix2d shapes[] = { (Eigen::Matrix2d() << 1, 0, 0, 0).finished(),   // along the strip
                                     (Eigen::Matrix2d() << 0, 0, 0, 1).finished(),   // across
                                     (Eigen::Matrix2d() << 1, 0, 0, 1).finished(),   // a dome
                                     (Eigen::Matrix2d() << 1, 0, 0, -1).finished(),  // a saddle
                                     (Eigen::Matrix2d() << 0, 1, 1, 0).finished() };  // a twist
  // The curvature's jumps (plate_smoothing) cost nothing here: within each face it is uniform.
  for (const double smoothing : { 0.0, 1.0 })
  for (StripMesher mesher : { StripMesher::Bubble, StripMesher::Cgal })
    for (double spacing : { 0.0025, 0.00125 })
    {
      material.plate_smoothing = smoothing;
      const CurvedMesh mesh = *meshStrip(scene, mesher, spacing);
      const CurvedTerms terms = curvedTerms(mesh, scene.paper, material);
      ASSERT_TRUE(terms.bend.empty());  // every hinge is in the plate terms
      for (const Eigen::Matrix2d& shape : shapes)
      {
        const Eigen::Matrix2d k = kappa * shape;
        const double energy = evaluateCurved(terms, moved(mesh, [&](const Vec2& p) {
                                               return Vec3(p.x(), p.y(), 0.5 * p.dot(k * p));
                                             })).bend;
        const double plate = 0.5 * d * (nu * k.trace() * k.trace() + (1 - nu) * k.squaredNorm()) * meshArea(mesh);
        EXPECT_NEAR(energy / plate, 1.0, 1e-5) << (mesher == StripMesher::Bubble ? "bubble" : "cgal") << " at "
                                               << spacing << ", curvature\n"
                                               << k;
      }
    }
}

TEST(PaperMaterial, PlateBendingGradientAndHessianMatchFiniteDifferences)
{
  const StripScene scene = *stripScene(0.1, 0.02, true);
  const CurvedMesh mesh = *meshStrip(scene, StripMesher::Cgal, 0.01);
  CurvedMaterial material = stripMaterial(*curvedMaterial(*paperPreset("copy_paper")));
  material.bend = 1e-2 * material.stretch * 0.01 * 0.01;  // bending as strong as stretching here
  material.plate_smoothing = 1.0;                          // the jump terms too
  const CurvedTerms terms = curvedTerms(mesh, scene.paper, material);
  ASSERT_FALSE(terms.plate.empty());
  Positions x = placeNodes(mesh, scene.paper);
  for (Eigen::Index v = 0; v < x.cols(); ++v)  // a generic bent, stretched state
    x.col(v) += 0.003 * Vec3(std::sin(3.1 * v), std::cos(1.7 * v), std::sin(0.9 * v + 1));
  std::vector<int> free_index(x.cols());
  for (Eigen::Index v = 0; v < x.cols(); ++v)
    free_index[v] = static_cast<int>(v);
  Eigen::VectorXd g = Eigen::VectorXd::Zero(3 * x.cols());
  std::vector<Eigen::Triplet<double>> triplets;
  evaluatePlate(terms.plate, x, { &free_index, &g, &triplets });
  Eigen::SparseMatrix<double> h(g.size(), g.size());
  h.setFromTriplets(triplets.begin(), triplets.end());
  const double step = 1e-7, scale = g.cwiseAbs().maxCoeff();
  for (int i = 0; i < g.size(); i += 5)
  {
    Positions plus = x, minus = x;
    plus(i % 3, i / 3) += step;
    minus(i % 3, i / 3) -= step;
    const double fd = (evaluatePlate(terms.plate, plus) - evaluatePlate(terms.plate, minus)) / (2 * step);
    EXPECT_NEAR(g[i], fd, 1e-6 * scale) << i;
    Eigen::VectorXd gp = Eigen::VectorXd::Zero(g.size()), gm = gp;
    evaluatePlate(terms.plate, plus, { &free_index, &gp, nullptr });
    evaluatePlate(terms.plate, minus, { &free_index, &gm, nullptr });
    const Eigen::VectorXd column = (gp - gm) / (2 * step);
    EXPECT_LT((Eigen::VectorXd(h.col(i)) - column).norm(), 1e-5 * (1 + column.norm())) << i;
  }
}

TEST(PaperMaterial, AnEvenStretchCostsThePlatesEnergyOnEitherMesher)
{
  // Every angle kept and each edge weighted by its triangles' area: exact on any mesh.
  const PaperMaterial paper = *paperPreset("card");
  const CurvedMaterial material = *curvedMaterial(paper);
  const StripScene scene = *stripScene(0.1, 0.01, false);
  const double eps = 1e-7, eh = paper.youngs_modulus * paper.thickness;
  for (StripMesher mesher : { StripMesher::Bubble, StripMesher::Cgal })
  {
    const CurvedMesh mesh = *meshStrip(scene, mesher, 0.0025);
    const CurvedEnergy e = evaluateCurved(curvedTerms(mesh, scene.paper, material),
                                          moved(mesh, [&](const Vec2& p) { return Vec3(p.x() * (1 + eps), p.y() * (1 + eps), 0); }));
    EXPECT_NEAR((e.stretch + e.shear) / (eh / (1 - paper.poisson_ratio) * eps * eps * meshArea(mesh)), 1.0, 1e-5);
  }
}

TEST(PaperMaterial, BadMaterialsAreRefusedWithAMessage)
{
  const PaperMaterial good = *paperPreset("copy_paper");
  struct Bad
  {
    const char* what;
    PaperMaterial paper;
  };
  std::vector<Bad> bad;
  for (double v : { 0.0, -1e-4, kNaN, kInf })
  {
    PaperMaterial p = good;
    p.thickness = v;
    bad.push_back({ "thickness", p });
    p = good;
    p.youngs_modulus = v;
    bad.push_back({ "Young", p });
    p = good;
    p.areal_density = v;
    bad.push_back({ "density", p });
  }
  for (double v : { -1.0, -1.5, 0.34, kNaN })
  {
    PaperMaterial p = good;
    p.poisson_ratio = v;
    bad.push_back({ "Poisson", p });
  }
  for (const Bad& b : bad)
  {
    const Expected<CurvedMaterial> m = curvedMaterial(b.paper);
    ASSERT_FALSE(m.ok()) << b.what;
    EXPECT_NE(m.message().find(b.what), std::string::npos) << m.message();
  }
  for (double v : { -0.5, 0.0, 1.0 / 3.0 })  // an auxetic paper, none, the springs' own
  {
    PaperMaterial p = good;
    p.poisson_ratio = v;
    EXPECT_TRUE(curvedMaterial(p).ok()) << v;
  }
  // Moduli given directly.
  for (double v : { 0.0, -1.0, kNaN })
  {
    CurvedMaterial m;
    m.stretch = v;
    EXPECT_FALSE(checkCurvedMaterial(m).ok());
    m = CurvedMaterial{};
    m.bend = v;
    EXPECT_FALSE(checkCurvedMaterial(m).ok());
  }
  CurvedMaterial negative_shear;
  negative_shear.shear = -0.1;
  EXPECT_FALSE(checkCurvedMaterial(negative_shear).ok());
  EXPECT_TRUE(checkCurvedMaterial(CurvedMaterial{}).ok());
  EXPECT_FALSE(checkThicknessAgainstSpacing(0.3e-3, 0.2e-3).ok());
  EXPECT_FALSE(checkThicknessAgainstSpacing(kNaN, 0.2e-3).ok());
  EXPECT_TRUE(checkThicknessAgainstSpacing(0.1e-3, 0.2e-3).ok());
  EXPECT_TRUE(checkThicknessAgainstSpacing(0.0, 0.2e-3).ok());  // no thickness given
}

namespace
{
CurvedSheetFollower followerOf(double spacing, const CurvedMaterial& material)
{
  CurvedFollowOptions options;
  options.material = material;
  options.solve.tolerance = 1e-10;
  return CurvedSheetFollower([spacing](const Paper& p) { BubbleMeshOptions o; o.spacing = spacing; return bubbleMesh(p, o); },
                             options);
}
}  // namespace

TEST(PaperMaterial, TheRunningSheetRefusesABadMaterialAndStaysAsItWas)
{
  // A 15-cm sheet of kami, one corner lifted 1 cm, meshed at 1.5 cm.
  const Paper paper = Paper::square(0.15);
  CurvedSheetFollower follower = followerOf(0.015, *curvedMaterial(*paperPreset("kami")));
  Paper lifted = paper;
  const std::vector<PullTarget> pins = { { 0, Vec3(0, 0, 0) }, { 1, Vec3(0.15, 0, 0) }, { 2, Vec3(0.15, 0.15, 0.01) } };
  ASSERT_TRUE(follower.solveState(lifted, pins).ok());
  const Positions before = follower.positions();

  CurvedMaterial bad = *curvedMaterial(*paperPreset("kami"));
  bad.bend = kNaN;
  const Status refused = follower.setMaterial(bad, {});
  ASSERT_FALSE(refused.ok());
  EXPECT_NE(refused.message().find("bending"), std::string::npos) << refused.message();
  Surroundings no_gravity;
  no_gravity.gravity = kInf;
  EXPECT_FALSE(follower.setMaterial(*curvedMaterial(*paperPreset("kami")), no_gravity).ok());
  // Thicker than the mesh's spacing: 2 cm card on a 1.5-cm mesh.
  CurvedMaterial thick = *curvedMaterial(*paperPreset("card"));
  thick.thickness = 0.02;
  const Status too_thick = follower.setMaterial(thick, {});
  ASSERT_FALSE(too_thick.ok());
  EXPECT_NE(too_thick.message().find("thicker than the mesh spacing"), std::string::npos) << too_thick.message();
  EXPECT_EQ(follower.positions(), before);
  // The sheet still solves as the kami it was: the same pins give the same balance.
  const Expected<CurvedReport> again = follower.follow(pins);
  ASSERT_TRUE(again.ok()) << again.message();
  EXPECT_LT((follower.positions() - before).cwiseAbs().maxCoeff(), 1e-12);
  // A good material is taken: card is stiffer, the same lift bends it the same way (pins hold
  // the shape) but the solver now runs with its moduli.
  EXPECT_TRUE(follower.setMaterial(*curvedMaterial(*paperPreset("card")), {}).ok());
  EXPECT_TRUE(follower.follow(pins).ok());
}

TEST(PaperMaterial, AThinPapersSolvesAreBalancedAsFinelyAsTheDefaultSheets)
{
  // Kami on a 15-cm sheet meshed at 1.5 cm: it bends with D/(k·s²) = 2.4e-6 of its stretch per
  // radian where the default sheet bends with 1e-4, so the tolerance is cut ~40-fold; the
  // default material's is left as it is.
  const Paper paper = Paper::square(0.15);
  BubbleMeshOptions mesh_options;
  mesh_options.spacing = 0.015;
  const CurvedMesh mesh = *bubbleMesh(paper, mesh_options);
  const CurvedMaterial kami = *curvedMaterial(*paperPreset("kami"));
  const double ratio = kami.bend / (kami.stretch * mesh.spacing * mesh.spacing);
  CurvedSolveOptions solve;
  solve.tolerance = 1e-8;
  EXPECT_NEAR(solveOptionsFor(kami, solve, mesh).tolerance, 1e-8 * ratio / 1e-4, 1e-20);
  EXPECT_LT(ratio, 1e-5);
  EXPECT_EQ(solveOptionsFor(CurvedMaterial{}, solve, mesh).tolerance, 1e-8);
}

TEST(PaperMaterial, AMeshFinerThanThePaperIsThickIsRefused)
{
  CurvedMaterial card = *curvedMaterial(*paperPreset("card"));  // 0.3 mm
  CurvedSheetFollower follower = followerOf(0.2e-3, card);
  const Paper tiny = Paper::square(2e-3);
  const Expected<CurvedReport> report = follower.solveState(tiny, { { 0, Vec3(0, 0, 0) } });
  ASSERT_FALSE(report.ok());
  EXPECT_NE(report.message().find("thicker than the mesh spacing"), std::string::npos) << report.message();
  EXPECT_FALSE(follower.hasSheet());
}

TEST(PaperMaterial, APinOffTheSheetIsRefusedAndNothingMoves)
{
  const StripScene scene = *stripScene(0.1, 0.01, false);
  const CurvedMesh mesh = *meshStrip(scene, StripMesher::Cgal, 0.0025);
  CurvedSolver solver(mesh, scene.paper, stripMaterial(*curvedMaterial(*paperPreset("copy_paper"))));
  Positions x = placeNodes(mesh, scene.paper);
  const Positions before = x;
  std::vector<CurvedPin> pins = stripPins(scene, mesh);
  pins.push_back({ static_cast<int>(mesh.nodes.size()), Vec3(0.0, 0.0, 0.01) });
  const CurvedReport off = solver.solve(x, pins);
  EXPECT_TRUE(off.refused);
  EXPECT_FALSE(off.converged);
  EXPECT_NE(off.message.find("off the sheet"), std::string::npos) << off.message;
  EXPECT_EQ(x, before);
  pins.back() = { 3, Vec3(kNaN, 0.0, 0.0) };
  EXPECT_TRUE(solver.solve(x, pins).refused);
  EXPECT_EQ(x, before);
  // A point off the sheet has no place on it.
  EXPECT_FALSE(pointOnSheet(mesh, x, Vec2(0.2, 0.005)).ok());
  EXPECT_TRUE(pointOnSheet(mesh, x, Vec2(0.05, 0.005)).ok());
  // Following a vertex the paper does not have: refused by the follower, as before.
  CurvedSheetFollower follower = followerOf(0.0025, *curvedMaterial(*paperPreset("copy_paper")));
  const Expected<CurvedReport> missing = follower.solveState(scene.paper, { { 99, Vec3(0, 0, 0) } });
  ASSERT_FALSE(missing.ok());
  EXPECT_NE(missing.message().find("does not exist"), std::string::npos);
}

}  // namespace virtual_origami::core

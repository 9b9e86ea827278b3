// Tessellation generators: counts by formula, well-formed flat papers, local flat-foldability,
// the rigidly folded Miura-ori, and patterns chosen by vertex count.
#include "virtual_origami/core/tessellations.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "virtual_origami/core/planar_geometry.h"
#include "virtual_origami/core/reference_patterns.h"
#include "virtual_origami/core/validity.h"

namespace virtual_origami::core
{
namespace
{
using ::testing::HasSubstr;

constexpr double kPi = 3.14159265358979323846;

/// Everything a generated pattern promises, whatever its kind.
void expectWellFormed(const Tessellation& t)
{
  const Paper& paper = t.paper;
  ASSERT_EQ(t.target_fold_angle.size(), paper.edges.size());
  const double scale = paper.scale();
  for (size_t v = 0; v < paper.vertices.size(); ++v)
  {
    const Vertex& vertex = paper.vertices[v];
    ASSERT_EQ(vertex.folded, Vec3(vertex.crease_pattern.x(), vertex.crease_pattern.y(), 0.0)) << "vertex " << v;
  }
  for (size_t e = 0; e < paper.edges.size(); ++e)
  {
    const Edge& edge = paper.edges[e];
    EXPECT_EQ(edge.fold_angle, 0.0) << "edge " << e;
    if (edge.isCrease())
    {
      ASSERT_TRUE(edge.assignment == Assignment::Mountain || edge.assignment == Assignment::Valley) << "edge " << e;
      EXPECT_EQ(t.target_fold_angle[e], edge.assignment == Assignment::Valley ? kPi : -kPi) << "edge " << e;
    }
    else
    {
      EXPECT_EQ(edge.assignment, Assignment::Boundary) << "edge " << e;
      EXPECT_EQ(t.target_fold_angle[e], 0.0) << "edge " << e;
    }
  }
  for (size_t f = 0; f < paper.faces.size(); ++f)
  {
    const std::vector<int>& cycle = paper.faces[f].vertices;
    ASSERT_GE(cycle.size(), 3u) << "face " << f;
    EXPECT_GT(paper.faceArea(static_cast<int>(f)), 1e-9 * scale * scale) << "face " << f;
    for (size_t k = 0; k < cycle.size(); ++k)
    {
      const Vec2& a = paper.vertices[cycle[k]].crease_pattern;
      const Vec2& b = paper.vertices[cycle[(k + 1) % cycle.size()]].crease_pattern;
      const Vec2& c = paper.vertices[cycle[(k + 2) % cycle.size()]].crease_pattern;
      EXPECT_GT((b - a).norm(), 1e-9 * scale) << "face " << f;
      EXPECT_GE(cross2(b - a, c - b), -1e-12 * scale * scale) << "face " << f << " turns clockwise";
    }
  }
  Paper relinked = paper;
  const Status linked = linkTopology(relinked);
  ASSERT_TRUE(linked) << linked.message();
  EXPECT_TRUE(relinked == paper);
  const ValidityReport report = checkValidity(paper);
  EXPECT_TRUE(report.ok()) << report.summary();
}

size_t countAssignment(const Paper& paper, Assignment assignment)
{
  return std::count_if(paper.edges.begin(), paper.edges.end(),
                       [&](const Edge& e) { return e.assignment == assignment; });
}

/// Interior vertices (no boundary edge) and their degrees.
std::vector<int> interiorDegrees(const Paper& paper)
{
  std::vector<int> degree(paper.vertices.size(), 0);
  std::vector<char> boundary(paper.vertices.size(), 0);
  for (const Edge& e : paper.edges)
    for (int v : e.vertices)
    {
      ++degree[v];
      if (!e.isCrease())
        boundary[v] = 1;
    }
  std::vector<int> interior;
  for (size_t v = 0; v < degree.size(); ++v)
    if (!boundary[v])
      interior.push_back(degree[v]);
  return interior;
}

std::string joined(const std::vector<std::string>& lines)
{
  std::string all;
  for (const std::string& l : lines)
    all += l + "\n";
  return all;
}

TEST(Tessellations, MiuraCountsAssignmentsAndFlatFoldability)
{
  for (const auto& [columns, rows] : std::vector<std::pair<int, int>>{ { 1, 1 }, { 2, 3 }, { 7, 4 }, { 10, 10 } })
  {
    SCOPED_TRACE(std::to_string(columns) + "x" + std::to_string(rows));
    const Expected<Tessellation> t = miuraTessellation(columns, rows, 1.5, 1.0, 1.1);
    ASSERT_TRUE(t) << t.message();
    const Paper& paper = t->paper;
    EXPECT_EQ(paper.vertices.size(), static_cast<size_t>((columns + 1) * (rows + 1)));
    EXPECT_EQ(static_cast<long>(paper.vertices.size()),
              tessellationVertexCount(TessellationKind::Miura, columns, rows));
    EXPECT_EQ(paper.faces.size(), static_cast<size_t>(columns * rows));
    // Creases: (columns − 1)·rows zigzag and columns·(rows − 1) straight; boundary 2(columns + rows).
    EXPECT_EQ(paper.edges.size(),
              static_cast<size_t>((columns - 1) * rows + columns * (rows - 1) + 2 * (columns + rows)));
    EXPECT_EQ(t->columns, columns);
    EXPECT_EQ(t->rows, rows);
    EXPECT_TRUE(t->flat_foldable);
    expectWellFormed(*t);
    EXPECT_TRUE(flatFoldabilityProblems(paper).empty()) << joined(flatFoldabilityProblems(paper));
    for (int degree : interiorDegrees(paper))
      EXPECT_EQ(degree, 4);
    // Same geometry and numbering as the reference builder.
    const Paper reference = miuraOri(columns, rows, 1.5, 1.0, 1.1);
    ASSERT_EQ(reference.vertices.size(), paper.vertices.size());
    for (size_t v = 0; v < paper.vertices.size(); ++v)
      EXPECT_EQ(reference.vertices[v].crease_pattern, paper.vertices[v].crease_pattern);
  }
}

TEST(Tessellations, MiuraTargetsAreTheFlatLimitOfItsRigidFold)
{
  const double gamma = 1.2;
  const Expected<Tessellation> t = miuraTessellation(5, 4, 1.0, 1.3, gamma);
  ASSERT_TRUE(t) << t.message();
  const std::vector<double> nearly_flat = miuraFoldAngles(t->paper, 5, 4, gamma, kPi - 1e-9);
  for (size_t e = 0; e < t->paper.edges.size(); ++e)
    EXPECT_NEAR(nearly_flat[e], t->target_fold_angle[e], 1e-6) << "edge " << e;
}

TEST(Tessellations, FoldedMiuraKeepsFaceShapesAndTheClosedFormAngles)
{
  const int columns = 6, rows = 5;
  const double a = 1.0, b = 1.4, gamma = 1.0;
  for (const double rho : { 0.3, 1.5, -2.0, 3.0 })
  {
    SCOPED_TRACE("rho " + std::to_string(rho));
    const Expected<Tessellation> t = miuraTessellationFolded(columns, rows, a, b, gamma, rho);
    ASSERT_TRUE(t) << t.message();
    const Paper& paper = t->paper;
    // Developable and rigid: every face keeps its crease-pattern shape.
    const ValidityReport report = checkValidity(paper);
    EXPECT_TRUE(report.ok()) << report.summary();
    // Every crease is at the closed-form angle, measured back from the folded positions.
    const std::vector<double> expected = miuraFoldAngles(paper, columns, rows, gamma, rho);
    double z_low = 0, z_high = 0;
    for (const Vertex& v : paper.vertices)
    {
      z_low = std::min(z_low, v.folded.z());
      z_high = std::max(z_high, v.folded.z());
    }
    EXPECT_GT(z_high - z_low, 1e-3);  // really folded
    for (size_t e = 0; e < paper.edges.size(); ++e)
    {
      if (!paper.edges[e].isCrease())
        continue;
      EXPECT_NEAR(measureFoldAngle(paper, static_cast<int>(e)), expected[e], 1e-9) << "edge " << e;
      // Folding goes the way the assignment says (all the other way for negative ρ).
      EXPECT_GT(rho * paper.edges[e].fold_angle * t->target_fold_angle[e], 0.0) << "edge " << e;
    }
  }
  // The straight and zigzag angles obey tan(ρz/2) = tan(ρ/2)/cos γ (mode 2 of a degree-4 vertex
  // with sectors γ, π − γ, γ, π − γ).
  const double rho = 1.1;
  const Expected<Tessellation> t = miuraTessellationFolded(columns, rows, a, b, gamma, rho);
  ASSERT_TRUE(t) << t.message();
  const int zig = t->paper.findEdge(1 * (columns + 1) + 2, 2 * (columns + 1) + 2);       // (2, 1)→(2, 2)
  const int straight = t->paper.findEdge(2 * (columns + 1) + 2, 2 * (columns + 1) + 3);  // (2, 2)→(3, 2)
  ASSERT_GE(zig, 0);
  ASSERT_GE(straight, 0);
  EXPECT_NEAR(std::abs(std::tan(measureFoldAngle(t->paper, zig) / 2)),
              std::abs(std::tan(measureFoldAngle(t->paper, straight) / 2)) / std::cos(gamma), 1e-9);
  EXPECT_NEAR(std::abs(measureFoldAngle(t->paper, straight)), rho, 1e-9);

  EXPECT_FALSE(miuraTessellationFolded(2, 2, 1, 1, 1, kPi));
}

TEST(Tessellations, YoshimuraCountsAndFlatFoldability)
{
  for (const auto& [columns, rows] :
       std::vector<std::pair<int, int>>{ { 1, 1 }, { 1, 2 }, { 3, 3 }, { 6, 5 }, { 9, 8 } })
  {
    SCOPED_TRACE(std::to_string(columns) + "x" + std::to_string(rows));
    const Expected<Tessellation> t = yoshimuraTessellation(columns, rows, 2.0, 0.7);
    ASSERT_TRUE(t) << t.message();
    const Paper& paper = t->paper;
    // Even lines hold columns + 1 vertices, odd lines columns + 2.
    const long vertices = (rows / 2 + 1) * (columns + 1L) + ((rows + 1) / 2) * (columns + 2L);
    EXPECT_EQ(static_cast<long>(paper.vertices.size()), vertices);
    EXPECT_EQ(tessellationVertexCount(TessellationKind::Yoshimura, columns, rows), vertices);
    EXPECT_EQ(paper.faces.size(), static_cast<size_t>(rows * (2 * columns + 1)));
    EXPECT_EQ(paper.edges.size(), paper.vertices.size() + paper.faces.size() - 1);
    for (const Face& f : paper.faces)
      EXPECT_EQ(f.vertices.size(), 3u);
    // Mountains are exactly the inner horizontal lines: rows − 1 lines of 2·columns segments… on
    // odd lines, columns on even ones.
    long mountains = 0;
    for (int line = 1; line < rows; ++line)
      mountains += line % 2 ? columns + 1 : columns;
    EXPECT_EQ(static_cast<long>(countAssignment(paper, Assignment::Mountain)), mountains);
    EXPECT_TRUE(t->flat_foldable);  // tan φ = 0.7, φ < 60°
    expectWellFormed(*t);
    EXPECT_TRUE(flatFoldabilityProblems(paper).empty()) << joined(flatFoldabilityProblems(paper));
    for (int degree : interiorDegrees(paper))
      EXPECT_EQ(degree, 6);
  }
  // Steeper than 60° the π − 2φ sector is the smallest and both its creases are valleys.
  const Expected<Tessellation> steep = yoshimuraTessellation(3, 3, 1.0, 2.0);
  ASSERT_TRUE(steep) << steep.message();
  EXPECT_FALSE(steep->flat_foldable);
  expectWellFormed(*steep);
  const std::vector<std::string> problems = flatFoldabilityProblems(steep->paper);
  EXPECT_FALSE(problems.empty());
  EXPECT_THAT(joined(problems), HasSubstr("big-little-big"));
}

TEST(Tessellations, SquareTwistCountsAreasAndFlatFoldability)
{
  const double pitch = 2.0, twist = 0.4, shrink = 0.6;
  for (const auto& [columns, rows] :
       std::vector<std::pair<int, int>>{ { 1, 1 }, { 2, 1 }, { 2, 2 }, { 4, 3 }, { 7, 7 } })
  {
    SCOPED_TRACE(std::to_string(columns) + "x" + std::to_string(rows));
    const Expected<Tessellation> t = squareTwistTessellation(columns, rows, pitch, twist, shrink);
    ASSERT_TRUE(t) << t.message();
    const Paper& paper = t->paper;
    const long tiles = columns * rows;
    const long pleats = (columns - 1L) * rows + columns * (rows - 1L);
    const long twists = (columns - 1L) * (rows - 1L);
    EXPECT_EQ(static_cast<long>(paper.vertices.size()), 4 * tiles);
    EXPECT_EQ(tessellationVertexCount(TessellationKind::SquareTwist, columns, rows), 4 * tiles);
    EXPECT_EQ(static_cast<long>(paper.faces.size()), tiles + pleats + twists);
    EXPECT_EQ(paper.edges.size(), paper.vertices.size() + paper.faces.size() - 1);
    // Creases: each pleat's two tile sides plus the twist squares' sides.
    EXPECT_EQ(static_cast<long>(paper.edges.size() - countAssignment(paper, Assignment::Boundary)),
              2 * pleats + 4 * twists);
    // No overlap: the areas are the closed forms of shrink-rotate (tile s², pleat s(cos α − s),
    // twist square 1 − 2s cos α + s², per pitch²), and a full period sums to pitch².
    const double tile = shrink * shrink, pleat = shrink * (std::cos(twist) - shrink),
                 square = 1 - 2 * shrink * std::cos(twist) + shrink * shrink;
    EXPECT_NEAR(tile + 2 * pleat + square, 1.0, 1e-12);
    EXPECT_NEAR(paper.sheet_area, pitch * pitch * (tiles * tile + pleats * pleat + twists * square), 1e-9);
    EXPECT_TRUE(t->flat_foldable);
    expectWellFormed(*t);
    EXPECT_TRUE(flatFoldabilityProblems(paper).empty()) << joined(flatFoldabilityProblems(paper));
    const std::vector<int> interior = interiorDegrees(paper);
    EXPECT_EQ(static_cast<long>(interior.size()), 4 * twists);
    for (int degree : interior)
      EXPECT_EQ(degree, 4);
  }
}

TEST(Tessellations, SquareTwistCentresAlternateLikeACheckerboard)
{
  const Expected<Tessellation> t = squareTwistTessellation(3, 3);
  ASSERT_TRUE(t) << t.message();
  const Paper& paper = t->paper;
  // The last four faces are the twist squares at grid points (1,1), (2,1), (1,2), (2,2).
  const size_t first = paper.faces.size() - 4;
  std::vector<Assignment> seen;
  for (size_t f = first; f < paper.faces.size(); ++f)
  {
    const Face& face = paper.faces[f];
    for (int e : face.edges)
      EXPECT_EQ(paper.edges[e].assignment, paper.edges[face.edges[0]].assignment) << "face " << f;
    seen.push_back(paper.edges[face.edges[0]].assignment);
  }
  EXPECT_EQ(seen[0], seen[3]);
  EXPECT_EQ(seen[1], seen[2]);
  EXPECT_NE(seen[0], seen[1]);
}

TEST(Tessellations, WaterbombCountsAndItsFlatFoldableCentres)
{
  for (const auto& [columns, rows] :
       std::vector<std::pair<int, int>>{ { 1, 1 }, { 1, 2 }, { 2, 2 }, { 4, 3 }, { 6, 6 } })
  {
    SCOPED_TRACE(std::to_string(columns) + "x" + std::to_string(rows));
    const Expected<Tessellation> t = waterbombTessellation(columns, rows, 2.0, 1.5);
    ASSERT_TRUE(t) << t.message();
    const Paper& paper = t->paper;
    EXPECT_EQ(static_cast<long>(paper.vertices.size()),
              tessellationVertexCount(TessellationKind::Waterbomb, columns, rows));
    EXPECT_EQ(paper.faces.size(), static_cast<size_t>(rows * (4 * columns + 2)));
    EXPECT_EQ(paper.edges.size(), paper.vertices.size() + paper.faces.size() - 1);
    EXPECT_FALSE(t->flat_foldable);
    expectWellFormed(*t);
    // Interior vertices: base centres of degree 6, which fold flat, and row-boundary vertices of
    // degree 4 (two collinear boundary creases), which do not.
    const std::vector<int> interior = interiorDegrees(paper);
    const long centres = std::count(interior.begin(), interior.end(), 6);
    const long joints = std::count(interior.begin(), interior.end(), 4);
    EXPECT_EQ(centres + joints, static_cast<long>(interior.size()));
    // Full bases not touching the sides: even rows columns − ... counted directly below.
    long inner_centres = 0;
    for (int r = 0; r < rows; ++r)
      inner_centres += r % 2 == 0 ? columns : columns - 1;
    EXPECT_EQ(centres, inner_centres);
    EXPECT_EQ(static_cast<long>(flatFoldabilityProblems(paper).size()), joints);
  }
  EXPECT_EQ(tessellationVertexCount(TessellationKind::Waterbomb, 1, 1),
            7);  // four corners, centre, two side mid-points
}

TEST(Tessellations, PatternsByVertexCount)
{
  for (const TessellationKind kind : { TessellationKind::Miura, TessellationKind::Yoshimura,
                                       TessellationKind::SquareTwist, TessellationKind::Waterbomb })
    for (const long n : { 1000L, 4000L, 10000L })
    {
      SCOPED_TRACE(tessellationName(kind) + " " + std::to_string(n));
      const GridSize grid = gridForVertexCount(kind, n);
      const Expected<Tessellation> t = tessellationWithVertices(kind, n);
      ASSERT_TRUE(t) << t.message();
      EXPECT_EQ(t->columns, grid.columns);
      EXPECT_EQ(t->rows, grid.rows);
      const long count = static_cast<long>(t->paper.vertices.size());
      EXPECT_EQ(count, tessellationVertexCount(kind, grid.columns, grid.rows));
      EXPECT_LE(std::abs(count - n), n / 50) << count << " vertices";
      const ValidityReport report = checkValidity(t->paper);
      EXPECT_TRUE(report.ok()) << report.summary();
    }
}

TEST(Tessellations, BadParametersAreRefused)
{
  EXPECT_THAT(miuraTessellation(0, 3).message(), HasSubstr("at least 1"));
  EXPECT_THAT(miuraTessellation(3, 3, -1.0).message(), HasSubstr("positive"));
  EXPECT_THAT(miuraTessellation(3, 3, 1.0, 1.0, kPi / 2).message(), HasSubstr("gamma"));
  EXPECT_THAT(yoshimuraTessellation(2, 2, 1.0, std::nan("")).message(), HasSubstr("positive"));
  EXPECT_THAT(squareTwistTessellation(2, 2, 1.0, 0.0).message(), HasSubstr("twist"));
  EXPECT_THAT(squareTwistTessellation(2, 2, 1.0, 0.5, std::cos(0.5)).message(), HasSubstr("shrink"));
  EXPECT_THAT(waterbombTessellation(2, -1).message(), HasSubstr("at least 1"));
  EXPECT_THAT(miuraTessellation(5000, 5000).message(), HasSubstr("vertices"));
  EXPECT_THAT(tessellationWithVertices(TessellationKind::Miura, 0).message(), HasSubstr("vertex count"));
}

TEST(Tessellations, FlatFoldabilityCheckerCatchesBrokenVertices)
{
  Expected<Tessellation> t = miuraTessellation(3, 3);
  ASSERT_TRUE(t) << t.message();
  // Flip one crease at interior vertex (1, 1): Maekawa fails at both its ends.
  const int e = t->paper.findEdge(1 * 4 + 1, 1 * 4 + 2);
  ASSERT_GE(e, 0);
  Assignment& a = t->paper.edges[e].assignment;
  a = a == Assignment::Mountain ? Assignment::Valley : Assignment::Mountain;
  const std::vector<std::string> problems = flatFoldabilityProblems(t->paper);
  ASSERT_EQ(problems.size(), 2u) << joined(problems);
  EXPECT_THAT(problems[0], HasSubstr("Maekawa"));
  // A degree-4 vertex whose opposite sectors do not sum to π: Kawasaki fails.
  Paper skewed = degree4Vertex({ 1.0, 1.3, 1.2, 2 * kPi - 3.5 });
  skewed.edges[skewed.findEdge(0, 1)].assignment = Assignment::Mountain;
  skewed.edges[skewed.findEdge(0, 2)].assignment = Assignment::Valley;
  skewed.edges[skewed.findEdge(0, 3)].assignment = Assignment::Valley;
  skewed.edges[skewed.findEdge(0, 4)].assignment = Assignment::Valley;
  EXPECT_THAT(joined(flatFoldabilityProblems(skewed)), HasSubstr("Kawasaki"));
}

}  // namespace
}  // namespace virtual_origami::core

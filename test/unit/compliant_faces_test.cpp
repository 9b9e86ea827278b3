// Faces that must bend, bend (issue 35): where rigid faces would lock a crease — the bands between
// curved creases — the faces are cut into triangles whose facets bend, only there; the crease
// driver and the rigid solver fold them, and fold by assignment reports them. Straight-crease
// patterns stay as they were.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <sstream>

#include "library_patterns.h"
#include "virtual_origami/core/assignment_fold.h"
#include "virtual_origami/core/compliant_faces.h"
#include "virtual_origami/core/fold_io.h"
#include "virtual_origami/core/model_file.h"
#include "virtual_origami/core/session.h"
#include "virtual_origami/core/tessellations.h"
#include "virtual_origami/core/validity.h"
#include "virtual_origami/solvers/crease_driver_factory.h"
#include "virtual_origami/solvers/driven_faces.h"
#include "virtual_origami/solvers/solver_factory.h"

using ::testing::HasSubstr;

namespace virtual_origami::core
{
namespace
{
Session foldingSession(Paper paper)
{
  Session session(std::move(paper));
  session.setSolver(makeSolver("newton"));
  session.setCreaseDrivers(makeCreaseDriver());
  return session;
}

/// A unit square with one curved valley crease from its bottom side to its top, bulging right
/// (a sine arc drawn in `segments` straight pieces), its target `degrees`. The face right of it
/// is concave: the loader cuts it into convex pieces.
Paper arcFold(int segments, double degrees)
{
  std::ostringstream fold;
  fold << "{\"file_spec\": 1.1, \"vertices_coords\": [[0,0],[1,0],[1,1],[0,1]";
  for (int k = 0; k <= segments; ++k)
  {
    const double y = static_cast<double>(k) / segments;
    fold << ",[" << 0.5 + 0.15 * std::sin(M_PI * y) << "," << y << "]";
  }
  const int a0 = 4, an = 4 + segments;
  fold << "], \"edges_vertices\": [[0," << a0 << "],[" << a0 << ",1],[1,2],[2," << an << "],[" << an << ",3],[3,0]";
  for (int k = 0; k < segments; ++k)
    fold << ",[" << a0 + k << "," << a0 + k + 1 << "]";
  fold << "], \"edges_assignment\": [\"B\",\"B\",\"B\",\"B\",\"B\",\"B\"";
  for (int k = 0; k < segments; ++k)
    fold << ",\"V\"";
  fold << "], \"edges_foldAngle\": [0,0,0,0,0,0";
  for (int k = 0; k < segments; ++k)
    fold << "," << degrees;
  fold << "]}";
  const Expected<Paper> paper = parseModel(fold.str(), ModelFormat::Fold, 1.0);
  EXPECT_TRUE(paper) << paper.message();
  return paper ? *paper : Paper{};
}

/// A hyperbolic paraboloid: `rings` concentric squares round the centre of a square sheet of
/// side 2, creased valley and mountain in turn (the outermost is the border), and the two
/// diagonals as free hinges: trapezoids between them, which no rigid fold can turn.
Paper quadHypar(int rings)
{
  std::ostringstream fold;
  fold << "{\"file_spec\": 1.1, \"vertices_coords\": [[0,0]";
  const int sx[4] = { 1, -1, -1, 1 }, sy[4] = { 1, 1, -1, -1 };
  for (int k = 1; k <= rings; ++k)
    for (int j = 0; j < 4; ++j)
      fold << ",[" << sx[j] * static_cast<double>(k) / rings << "," << sy[j] * static_cast<double>(k) / rings << "]";
  std::ostringstream edges, assignments;
  const auto corner = [](int k, int j) { return 1 + (k - 1) * 4 + j % 4; };
  const char* sep = "";
  for (int k = 1; k <= rings; ++k)
    for (int j = 0; j < 4; ++j)
    {
      edges << sep << "[" << corner(k, j) << "," << corner(k, j + 1) << "]";
      assignments << sep << (k == rings ? "\"B\"" : k % 2 ? "\"V\"" : "\"M\"");
      sep = ",";
      edges << ",[" << (k == 1 ? 0 : corner(k - 1, j)) << "," << corner(k, j) << "]";
      assignments << ",\"U\"";
    }
  fold << "], \"edges_vertices\": [" << edges.str() << "], \"edges_assignment\": [" << assignments.str() << "]}";
  const Expected<Paper> paper = parseModel(fold.str(), ModelFormat::Fold, 1.0);
  EXPECT_TRUE(paper) << paper.message();
  return paper ? *paper : Paper{};
}

double twiceArea(const Paper& paper, const Face& face)
{
  double twice = 0;
  for (size_t k = 0; k < face.vertices.size(); ++k)
  {
    const Vec2 a = paper.vertices[face.vertices[k]].crease_pattern;
    const Vec2 b = paper.vertices[face.vertices[(k + 1) % face.vertices.size()]].crease_pattern;
    twice += a.x() * b.y() - a.y() * b.x();
  }
  return twice;
}

/// Every face counter-clockwise, the sheet's area kept, and every triangle of a compliant face
/// no sliver: its height at least `thinnest` of its longest side.
void expectSoundCut(const Paper& before, const Paper& cut, double thinnest, const std::string& what)
{
  EXPECT_EQ(cut.vertices.size(), before.vertices.size()) << what;
  double area_before = 0, area_after = 0;
  for (const Face& f : before.faces)
    area_before += twiceArea(before, f);
  for (const Face& f : cut.faces)
  {
    const double twice = twiceArea(cut, f);
    EXPECT_GT(twice, 0) << what;
    area_after += twice;
    if (f.vertices.size() != 3)
      continue;
    double longest = 0;
    for (int k = 0; k < 3; ++k)
      longest = std::max(
          longest,
          (cut.vertices[f.vertices[k]].crease_pattern - cut.vertices[f.vertices[(k + 1) % 3]].crease_pattern).norm());
    EXPECT_GE(twice / (longest * longest), thinnest) << what;
  }
  EXPECT_NEAR(area_after, area_before, 1e-12) << what;
  for (const Edge& e : cut.edges)
    if (isFacet(e))
    {
      EXPECT_EQ(*e.target_angle, 0.0) << what;
      EXPECT_EQ(e.assignment, Assignment::Flat) << what;
    }
}

/// Straight-crease patterns stay as they are, also where the file's creases are drawn a little
/// off their lines (whirlpool's by up to 6e-5 of the sheet, FTpoly7's 1.6e-4, the dragon's
/// 1.8e-4, the house pop-up's 8e-4).
TEST(CompliantFaces, StraightCreasePatternsStayRigid)
{
  std::vector<Paper> papers = { miuraTessellation(4, 4).value().paper, squareTwistTessellation(2, 2).value().paper };
  for (const std::string name : { "Bases/birdBase.svg", "Popup/castlePopup.svg", "Tessellations/whirlpool.svg",
                                  "Tessellations/FTpoly7.svg", "Origami/langKnlDragon.svg", "Popup/housePopup.svg" })
    papers.push_back(test::libraryPattern(name));
  for (Paper& paper : papers)
  {
    const Paper before = paper;
    const CompliantFaces made = makeLockedFacesCompliant(paper);
    EXPECT_EQ(made.bodies, 0);
    EXPECT_TRUE(paper == before);
  }
}

/// A curved crease: both faces beside it are rigid bodies meeting along a bent line, so both
/// are cut into triangles whose every inner edge is a facet; the cut is made once.
TEST(CompliantFaces, TheFacesBesideACurvedCreaseAreCutIntoTriangles)
{
  const Paper paper = arcFold(8, 90.0);
  ASSERT_GT(std::count_if(paper.edges.begin(), paper.edges.end(), [](const Edge& e) { return e.split; }), 0);
  Paper cut = paper;
  const CompliantFaces made = makeLockedFacesCompliant(cut);
  EXPECT_EQ(made.bodies, 2);
  // 13 vertices, 6 of them on the sheet's border: 2·13 − 6 − 2 = 18 triangles and
  // 3·13 − 6 − 3 = 30 edges, 24 inside: 8 creases and 16 facets.
  EXPECT_EQ(made.triangles, 18);
  EXPECT_EQ(static_cast<int>(cut.faces.size()), 18);
  for (const Face& f : cut.faces)
    EXPECT_EQ(f.vertices.size(), 3u);
  EXPECT_EQ(made.facets, 16);
  int facets = 0, creases = 0;
  for (const Edge& e : cut.edges)
  {
    facets += isFacet(e) ? 1 : 0;
    creases += e.isCrease() && !e.split ? 1 : 0;
  }
  EXPECT_EQ(facets, 16);
  EXPECT_EQ(creases, 8);
  expectSoundCut(paper, cut, 0.05, "arc");
  Paper again = cut;
  EXPECT_EQ(makeLockedFacesCompliant(again).bodies, 2);
  EXPECT_TRUE(again == cut);
}

/// The bands of a curved pleat (Origami Simulator's wavy_pleats: six bands cut at load into 156
/// convex pieces, many of them slivers along the finely drawn curves) become triangles that span
/// each band.
TEST(CompliantFaces, CurvedBandsBecomeTrianglesAcrossTheBand)
{
  const Paper paper = test::libraryPattern("Curved/wavy_pleats.svg");
  Paper cut = paper;
  const CompliantFaces made = makeLockedFacesCompliant(cut);
  EXPECT_EQ(made.bodies, 6);
  EXPECT_EQ(made.triangles, static_cast<int>(cut.faces.size()));
  expectSoundCut(paper, cut, 1e-2, "wavy_pleats");
  // The file's creases are all still there, unchanged.
  for (size_t e = 0; e < paper.edges.size(); ++e)
    if (!paper.edges[e].split)
    {
      EXPECT_EQ(cut.edges[e].vertices, paper.edges[e].vertices);
      EXPECT_EQ(cut.edges[e].assignment, paper.edges[e].assignment);
    }
}

/// In the crease driver's energy a facet is a hinge as stiff as a crease of its length
/// (kFacetBending), held at flat whatever the creases are driven to; the rigid solver's faces
/// are the triangles, not the whole band.
TEST(CompliantFaces, FacetsAreHingesHeldFlat)
{
  Paper paper = arcFold(8, 90.0);
  const size_t pieces = rigidFaces(paper).size();
  makeLockedFacesCompliant(paper);
  EXPECT_LT(pieces, paper.faces.size());
  EXPECT_EQ(rigidFaces(paper).size(), paper.faces.size());
  DrivenFaces energy(paper, 1e4);
  std::vector<double> targets(paper.edges.size(), 1.0);
  energy.setTargets(targets);
  int facet_hinges = 0;
  Positions x = foldedPositions(paper);
  x /= paper.scale();
  for (const Hinge& h : energy.hinges())
    if (isFacet(paper.edges[h.edge]))
    {
      ++facet_hinges;
      const double length =
          (paper.vertices[h.a].crease_pattern - paper.vertices[h.b].crease_pattern).norm() / paper.scale();
      EXPECT_GT(h.weight, 0.0);
      EXPECT_LT(h.weight, 10 * length);
    }
  EXPECT_EQ(facet_hinges, 16);
  // Flat: only the creases (driven to 1 rad) pull, each ½ w · 1².
  double crease_energy = 0;
  for (const Hinge& h : energy.hinges())
    if (!isFacet(paper.edges[h.edge]))
      crease_energy += 0.5 * h.weight;
  EXPECT_NEAR(energy.hingeEnergy(x), crease_energy, 1e-12);
}

/// A curved crease folds with its faces bending: committed half way by assignment it is right
/// for paper — strain within the bound, no crease stuck, no crossing — with its bands bent and
/// every crease turned most of the way. Rigid faces hold it flat: every crease stuck.
TEST(CompliantFaces, ACurvedCreaseFoldsWithItsFacesBending)
{
  const Paper paper = arcFold(8, 90.0);
  Paper rigid = paper;
  std::vector<double> goal = creaseTargets(rigid);
  for (double& g : goal)
    g *= 0.5;
  ASSERT_TRUE(makeCreaseDriver()->drive(rigid, goal, std::vector<char>(rigid.vertices.size(), 0)).converged);
  updateFoldAngles(rigid);
  for (const Edge& e : rigid.edges)
  {
    if (e.isCrease() && !e.split)
    {
      EXPECT_LT(std::abs(e.fold_angle), 0.01 * M_PI / 4);
    }
  }
  Session session = foldingSession(paper);
  const Expected<AssignmentFoldResult> half = session.foldByAssignment(0.5);
  ASSERT_TRUE(half) << half.message();
  EXPECT_LE(half->max_strain, 1e-9);
  EXPECT_TRUE(half->rigid);
  EXPECT_EQ(half->stuck, 0);
  EXPECT_EQ(half->asked_to_turn, 8);
  EXPECT_EQ(half->crossings, 0);
  EXPECT_EQ(half->against_target, 0);
  EXPECT_EQ(half->compliant_faces, 2);
  EXPECT_GT(half->largest_bend, 0.02);
  EXPECT_LT(half->angle_error, 0.1);
  for (const Edge& e : session.paper().edges)
  {
    if (e.isCrease() && !e.split)
    {
      EXPECT_NEAR(e.fold_angle, M_PI / 4, 0.15);
    }
  }
}

/// A folded curved crease saves as the file had it (each band one face again: its facets are no
/// creases of the file), its folded-form frame the bent shape, and loads back valid; folded on,
/// its faces bend again.
TEST(CompliantFaces, AFoldedCurvedCreaseSavesAndLoadsBack)
{
  const Paper pattern = arcFold(8, 90.0);
  Session session = foldingSession(pattern);
  ASSERT_TRUE(session.foldByAssignment(0.5));
  const Expected<FoldDocument> back = parseFold(formatFold(session.paper()));
  ASSERT_TRUE(back) << back.message();
  const Paper& read = back->frames.front();
  // The bent faces are written as their triangles, the facets marked as such (a face of a FOLD
  // file is flat: one bent face written whole would not be), and read back as facets.
  EXPECT_EQ(read.faces.size(), session.paper().faces.size());
  EXPECT_EQ(compliantFaceCount(read), compliantFaceCount(session.paper()));
  EXPECT_TRUE(checkValidity(read).ok()) << checkValidity(read).summary();
  // The folded form's frame keeps the bent shape: every distance between two vertices.
  ASSERT_EQ(back->frames.size(), 2u);
  const Paper& form = back->frames.back();
  const Paper& folded = session.paper();
  ASSERT_EQ(form.vertices.size(), folded.vertices.size());
  double largest = 0;
  for (size_t v = 0; v < form.vertices.size(); ++v)
    for (size_t w = v + 1; w < form.vertices.size(); ++w)
      largest = std::max(largest, std::abs((form.vertices[v].folded - form.vertices[w].folded).norm() -
                                           (folded.vertices[v].folded - folded.vertices[w].folded).norm()));
  EXPECT_LT(largest, 1e-9);
  Session again = foldingSession(read);
  const Expected<AssignmentFoldResult> on = again.foldByAssignment(0.75);
  ASSERT_TRUE(on) << on.message();
  EXPECT_EQ(on->compliant_faces, 2);
  EXPECT_EQ(on->stuck, 0);
  EXPECT_LE(on->max_strain, 1e-3);
}

/// A hypar's trapezoids must twist: rigid faces stretch, and closed rigid every crease sticks;
/// the faces beside the stuck creases are made compliant (cut in two along a diagonal that
/// bends) and the hypar folds half way, right for paper.
TEST(CompliantFaces, AHyparsTrapezoidsTwist)
{
  const Paper pattern = quadHypar(4);
  ASSERT_EQ(pattern.faces.size(), 16u);
  Paper rigid = pattern;
  std::vector<double> goal = creaseTargets(rigid);
  for (double& g : goal)
    g *= 0.5;
  // Rigid faces driven there stretch instead (and closed rigid, lie flat: every crease stuck).
  ASSERT_TRUE(makeCreaseDriver()->drive(rigid, goal, std::vector<char>(rigid.vertices.size(), 0)).converged);
  const std::vector<double> stretched = faceStrains(rigid);
  EXPECT_GT(*std::max_element(stretched.begin(), stretched.end()), 1e-3);
  Session session = foldingSession(pattern);
  const Expected<AssignmentFoldResult> half = session.foldByAssignment(0.5);
  ASSERT_TRUE(half) << half.message();
  EXPECT_EQ(half->stuck, 0);
  EXPECT_EQ(half->asked_to_turn, 12);
  EXPECT_LE(half->max_strain, 1e-3);
  EXPECT_EQ(half->crossings, 0);
  EXPECT_EQ(half->against_target, 0);
  EXPECT_EQ(half->compliant_faces, 12);
  EXPECT_GT(half->largest_bend, 0.05);
  // Every driven crease turned, by at least a tenth of the way (a saddle: 0.22–0.33 rad of π/2).
  for (const Edge& e : session.paper().edges)
  {
    if (e.isCrease() && !e.split && e.assignment != Assignment::Unassigned)
    {
      EXPECT_GT(std::abs(e.fold_angle), 0.1 * M_PI / 2);
    }
  }
}

/// A curved pleat folds part way (its bands bending; held rigid it could not turn a crease), and
/// all the way it is refused with its figures — a curved crease cannot fold flat — unless kept.
TEST(CompliantFaces, ACurvedPleatFoldsPartWayAndIsRefusedFlatUnlessKept)
{
  Session session = foldingSession(test::libraryPattern("Curved/wavy_pleats.svg"));
  const Expected<AssignmentFoldResult> half = session.foldByAssignment(0.5);
  ASSERT_TRUE(half) << half.message();
  EXPECT_LE(half->max_strain, 1e-3);
  EXPECT_EQ(half->stuck, 0);
  EXPECT_EQ(half->crossings, 0);
  EXPECT_EQ(half->compliant_faces, 6);
  EXPECT_GT(half->largest_bend, 0.1);
  Session from_flat = foldingSession(test::libraryPattern("Curved/wavy_pleats.svg"));
  AssignmentFoldResult figures;
  const Expected<Computed<AssignmentFoldResult>> flat =
      computeFoldByAssignment(from_flat.workspace(), 1.0, true, {}, &figures);
  ASSERT_FALSE(flat);
  EXPECT_THAT(flat.message(), HasSubstr("RMS) from their targets"));
  EXPECT_GT(figures.angle_error, 0.1);
  EXPECT_EQ(from_flat.revision(), 0u);
  AssignmentFoldAcceptance keep;
  keep.keep = true;
  const Expected<AssignmentFoldResult> kept = from_flat.foldByAssignment(1.0, true, keep);
  ASSERT_TRUE(kept) << kept.message();
  EXPECT_EQ(from_flat.revision(), 1u);
  EXPECT_NEAR(kept->angle_error, figures.angle_error, 1e-9);
  EXPECT_NEAR(kept->max_strain, figures.max_strain, 1e-12);
}

}  // namespace
}  // namespace virtual_origami::core

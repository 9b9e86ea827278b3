// Patterns as people share them: FOLD nulls, several pieces, holes, slits and kirigami cuts,
// loose crease ends (test/data/patterns), each loaded and its topology checked.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "virtual_origami/core/fold_io.h"
#include "virtual_origami/core/planar_geometry.h"
#include "virtual_origami/core/validity.h"

namespace virtual_origami::core
{
namespace
{
using ::testing::HasSubstr;

std::string patternFile(const std::string& name)
{
  return std::string(VO_SOURCE_DIR) + "/test/data/patterns/" + name;
}

Paper loadPattern(const std::string& name)
{
  const Expected<Paper> paper = loadPaper(patternFile(name));
  if (!paper)
  {
    ADD_FAILURE() << name << ": " << paper.message();
    return Paper{};
  }
  return *paper;
}

double totalFaceArea(const Paper& paper)
{
  double area = 0;
  for (size_t f = 0; f < paper.faces.size(); ++f)
    area += paper.faceArea(static_cast<int>(f));
  return area;
}

long euler(const Paper& paper)
{
  return static_cast<long>(paper.vertices.size()) - static_cast<long>(paper.edges.size()) +
         static_cast<long>(paper.faces.size());
}

/// The vertices at a crease-pattern point.
std::vector<int> verticesAt(const Paper& paper, const Vec2& p)
{
  std::vector<int> found;
  for (size_t v = 0; v < paper.vertices.size(); ++v)
    if ((paper.vertices[v].crease_pattern - p).norm() < 1e-12)
      found.push_back(static_cast<int>(v));
  return found;
}

/// Whether a face covers a point strictly inside it.
bool covered(const Paper& paper, const Vec2& p)
{
  for (const Face& face : paper.faces)
  {
    bool inside = true;
    for (size_t i = 0; i < face.vertices.size(); ++i)
    {
      const Vec2& a = paper.vertices[face.vertices[i]].crease_pattern;
      const Vec2& b = paper.vertices[face.vertices[(i + 1) % face.vertices.size()]].crease_pattern;
      inside = inside && cross2(b - a, p - a) > 1e-12;
    }
    if (inside)
      return true;
  }
  return false;
}

int countAssigned(const Paper& paper, Assignment assignment)
{
  int count = 0;
  for (const Edge& edge : paper.edges)
    count += edge.assignment == assignment;
  return count;
}

TEST(SharedPatterns, NullFieldsAndValuesReadAsAbsent)
{
  const Paper paper = loadPattern("null-values.fold");
  // faces_vertices: null is no faces: traced, the diagonal's two triangles.
  ASSERT_EQ(2u, paper.faces.size());
  EXPECT_DOUBLE_EQ(1.0, paper.sheet_area);
  const int diagonal = paper.findEdge(0, 2);
  ASSERT_GE(diagonal, 0);
  EXPECT_EQ(Assignment::Valley, paper.edges[diagonal].assignment);
  ASSERT_TRUE(paper.edges[diagonal].target_angle);
  EXPECT_DOUBLE_EQ(M_PI, *paper.edges[diagonal].target_angle);
  EXPECT_EQ(Assignment::Boundary, paper.edges[paper.findEdge(2, 3)].assignment);  // null: one face, a boundary
  EXPECT_TRUE(checkValidity(paper).ok()) << checkValidity(paper).summary();
}

TEST(SharedPatterns, SeparatePiecesStaySeparate)
{
  const Paper paper = loadPattern("two-pieces.fold");
  ASSERT_EQ(3u, paper.faces.size());  // the left square's two triangles and the right square
  EXPECT_DOUBLE_EQ(2.0, paper.sheet_area);
  EXPECT_EQ(2, euler(paper));  // two pieces, no hole
  EXPECT_EQ(1, countAssigned(paper, Assignment::Valley));
  EXPECT_TRUE(checkValidity(paper).ok()) << checkValidity(paper).summary();
}

TEST(SharedPatterns, AFoldedFormInSeveralPiecesUnfoldsEachBesideTheOther)
{
  const Paper paper = loadPattern("two-pieces-folded.fold");
  ASSERT_EQ(3u, paper.faces.size());
  EXPECT_NEAR(2.0, paper.sheet_area, 1e-12);
  EXPECT_EQ(2, euler(paper));
  const int diagonal = paper.findEdge(0, 2);
  ASSERT_GE(diagonal, 0);
  EXPECT_NEAR(M_PI / 2, std::abs(paper.edges[diagonal].fold_angle), 1e-9);
  // Unfolded, the first piece is a unit square, the second one lies wholly beside it.
  EXPECT_NEAR(std::sqrt(2.0), (paper.vertices[1].crease_pattern - paper.vertices[3].crease_pattern).norm(), 1e-9);
  double first_right = -1e9, second_left = 1e9;
  for (int v = 0; v < 4; ++v)
    first_right = std::max(first_right, paper.vertices[v].crease_pattern.x());
  for (int v = 4; v < 8; ++v)
    second_left = std::min(second_left, paper.vertices[v].crease_pattern.x());
  EXPECT_GT(second_left, first_right);
  // The folded form is as the file has it.
  EXPECT_EQ(Vec3(4, 0, 1), paper.vertices[6].folded);
  EXPECT_TRUE(checkValidity(paper).ok()) << checkValidity(paper).summary();
}

TEST(SharedPatterns, FoldAnglesFoldEveryPiece)
{
  // The creased square is the second piece: it folds from its own first face.
  const Expected<FoldDocument> document = parseFold(R"({
    "vertices_coords": [[2,0],[3,0],[3,1],[2,1],[0,0],[1,0],[1,1],[0,1]],
    "edges_vertices": [[0,1],[1,2],[2,3],[3,0],[4,5],[5,6],[6,7],[7,4],[4,6]],
    "edges_assignment": ["B","B","B","B","B","B","B","B","V"],
    "edges_foldAngle": [0,0,0,0,0,0,0,0,90]})");
  ASSERT_TRUE(document.ok()) << document.message();
  const Paper& paper = document->frames[0];
  EXPECT_NEAR(M_PI / 2, paper.edges[paper.findEdge(4, 6)].fold_angle, 1e-12);
  EXPECT_TRUE(paper.vertices[7].folded.isApprox(Vec3(0.5, 0.5, std::sqrt(0.5)), 1e-12));
  EXPECT_EQ(Vec3(3, 1, 0), paper.vertices[2].folded);
  EXPECT_TRUE(checkValidity(paper).ok()) << checkValidity(paper).summary();
}

TEST(SharedPatterns, AHoleGetsNoFace)
{
  const Paper paper = loadPattern("hole.fold");
  ASSERT_EQ(4u, paper.faces.size());            // four trapezoids round the hole
  EXPECT_DOUBLE_EQ(8.0, totalFaceArea(paper));  // 3 x 3 less the 1 x 1 hole
  EXPECT_DOUBLE_EQ(8.0, paper.sheet_area);
  EXPECT_FALSE(covered(paper, Vec2(1.5, 1.5)));
  EXPECT_TRUE(covered(paper, Vec2(1.5, 0.5)));
  EXPECT_EQ(0, euler(paper));  // one piece, one hole
  EXPECT_EQ(8, countAssigned(paper, Assignment::Boundary));
  EXPECT_EQ(2, countAssigned(paper, Assignment::Mountain));
  EXPECT_EQ(2, countAssigned(paper, Assignment::Valley));
  EXPECT_TRUE(checkValidity(paper).ok()) << checkValidity(paper).summary();
}

TEST(SharedPatterns, AHoleInsideOneFaceIsJoinedToTheOutlineByFlatEdges)
{
  const Paper paper = loadPattern("hole-in-face.fold");
  EXPECT_DOUBLE_EQ(8.0, totalFaceArea(paper));
  EXPECT_FALSE(covered(paper, Vec2(1.5, 1.5)));
  EXPECT_EQ(0, euler(paper));
  // The joints: from the hole's rightmost corner (2, 2) to (3, 2), from its leftmost (1, 1) to (0, 1).
  for (const auto& [a, b] : { std::pair{ Vec2(2, 2), Vec2(3, 2) }, std::pair{ Vec2(1, 1), Vec2(0, 1) } })
  {
    ASSERT_EQ(1u, verticesAt(paper, a).size());
    ASSERT_EQ(1u, verticesAt(paper, b).size());
    const int joint = paper.findEdge(verticesAt(paper, a)[0], verticesAt(paper, b)[0]);
    ASSERT_GE(joint, 0);
    EXPECT_EQ(Assignment::Flat, paper.edges[joint].assignment);
    EXPECT_TRUE(paper.edges[joint].isCrease());
  }
  EXPECT_TRUE(checkValidity(paper).ok()) << checkValidity(paper).summary();
}

TEST(SharedPatterns, ASlitFromTheBorderOpens)
{
  const Paper paper = loadPattern("slit.fold");
  EXPECT_DOUBLE_EQ(4.0, totalFaceArea(paper));
  // Where the cut meets the border, and along it, each side has its own vertex; the tip is one.
  EXPECT_EQ(2u, verticesAt(paper, Vec2(1, 0)).size());
  EXPECT_EQ(2u, verticesAt(paper, Vec2(1, 0.5)).size());
  EXPECT_EQ(1u, verticesAt(paper, Vec2(1, 1)).size());
  EXPECT_EQ(1, euler(paper));                           // a slit from the border leaves one piece without holes
  EXPECT_EQ(0, countAssigned(paper, Assignment::Cut));  // each side of the cut is a boundary
  // The cut's line runs on from its tip as the one crease, flat, so both faces are convex.
  ASSERT_EQ(2u, paper.faces.size());
  EXPECT_EQ(1, countAssigned(paper, Assignment::Flat));
  for (const Edge& edge : paper.edges)
    if (edge.isCrease())
    {
      EXPECT_EQ(Assignment::Flat, edge.assignment);
      EXPECT_EQ(Vec2(1, 1), paper.vertices[edge.vertices[0]].crease_pattern);
      EXPECT_EQ(Vec2(1, 2), paper.vertices[edge.vertices[1]].crease_pattern);
    }
  EXPECT_TRUE(checkValidity(paper).ok()) << checkValidity(paper).summary();
}

TEST(SharedPatterns, AnInteriorSlitOpens)
{
  const Paper paper = loadPattern("interior-slit.fold");
  EXPECT_DOUBLE_EQ(4.0, totalFaceArea(paper));
  EXPECT_EQ(1u, verticesAt(paper, Vec2(0.5, 1)).size());
  EXPECT_EQ(1u, verticesAt(paper, Vec2(1.5, 1)).size());
  const std::vector<int> middle = verticesAt(paper, Vec2(1, 1));
  ASSERT_EQ(2u, middle.size());  // one for each side
  // Each side of the slit is a boundary edge, of a different face.
  std::vector<int> faces;
  for (int v : middle)
    for (const Edge& edge : paper.edges)
      if ((edge.vertices[0] == v || edge.vertices[1] == v) && !edge.isCrease())
        faces.push_back(edge.faces[0] >= 0 ? edge.faces[0] : edge.faces[1]);
  ASSERT_EQ(4u, faces.size());
  EXPECT_EQ(faces[0], faces[1]);
  EXPECT_EQ(faces[2], faces[3]);
  EXPECT_NE(faces[0], faces[2]);
  EXPECT_EQ(0, euler(paper));  // the opened slit is a hole
  EXPECT_TRUE(checkValidity(paper).ok()) << checkValidity(paper).summary();
}

TEST(SharedPatterns, KirigamiCutsOpenAcrossTheFold)
{
  const Paper paper = loadPattern("kirigami.fold");
  EXPECT_DOUBLE_EQ(8.0, totalFaceArea(paper));
  // Each cut crosses the fold line at a vertex that opens into two; its ends stay one.
  for (double x : { 1.5, 2.5 })
  {
    EXPECT_EQ(2u, verticesAt(paper, Vec2(x, 1)).size()) << x;
    EXPECT_EQ(1u, verticesAt(paper, Vec2(x, 0.5)).size()) << x;
    EXPECT_EQ(1u, verticesAt(paper, Vec2(x, 1.5)).size()) << x;
  }
  EXPECT_EQ(-1, euler(paper));  // one piece, two opened cuts
  EXPECT_EQ(0, countAssigned(paper, Assignment::Cut));
  // The box's mountain runs between the cuts, a crease of the box's faces.
  for (const Edge& edge : paper.edges)
    if (edge.assignment == Assignment::Mountain)
    {
      EXPECT_EQ(Vec2(1.5, 1), paper.vertices[edge.vertices[0]].crease_pattern);
      EXPECT_EQ(Vec2(2.5, 1), paper.vertices[edge.vertices[1]].crease_pattern);
      EXPECT_TRUE(edge.isCrease());
    }
  EXPECT_EQ(1, countAssigned(paper, Assignment::Mountain));
  EXPECT_EQ(4, countAssigned(paper, Assignment::Valley));
  EXPECT_TRUE(checkValidity(paper).ok()) << checkValidity(paper).summary();
}

TEST(SharedPatterns, ACutBetweenGivenFacesOpens)
{
  const Paper paper = loadPattern("cut-between-faces.fold");
  ASSERT_EQ(4u, paper.faces.size());
  EXPECT_EQ(2u, verticesAt(paper, Vec2(1, 0)).size());  // where the cut leaves the border
  EXPECT_EQ(1u, verticesAt(paper, Vec2(1, 1)).size());  // its end, inside
  EXPECT_EQ(0, countAssigned(paper, Assignment::Cut));  // its sides, boundaries
  EXPECT_EQ(13u, paper.edges.size());                   // the file's 12, the cut one each side
  EXPECT_EQ(1, euler(paper));
  // The creases keep their ends as the file wrote them.
  EXPECT_GE(paper.findEdge(8, 3), 0);
  EXPECT_EQ(Assignment::Valley, paper.edges[9].assignment);
  EXPECT_EQ(Vec2(1, 1), paper.vertices[paper.edges[9].vertices[0]].crease_pattern);
  EXPECT_TRUE(checkValidity(paper).ok()) << checkValidity(paper).summary();
}

TEST(SharedPatterns, ALooseCreaseEndIsLeftOut)
{
  const Paper paper = loadPattern("loose-crease.fold");
  ASSERT_EQ(1u, paper.faces.size());
  EXPECT_EQ(4u, paper.vertices.size());
  EXPECT_EQ(0, countAssigned(paper, Assignment::Mountain));
  EXPECT_TRUE(checkValidity(paper).ok()) << checkValidity(paper).summary();
}

TEST(SharedPatterns, ACreaseWithOneFaceOnBothSidesIsLeftOut)
{
  const Paper paper = loadPattern("ring-on-a-stick.fold");
  // The valley has the face round the ring on both sides: it goes, and the ring, now touching
  // nothing, is joined to the outline by two flat edges like a hole would be.
  EXPECT_EQ(0, countAssigned(paper, Assignment::Valley));
  EXPECT_EQ(4, countAssigned(paper, Assignment::Mountain));
  int joints = 0;  // flat edges of the file (not those splitting a concave face into convex ones)
  for (const Edge& edge : paper.edges)
    joints += edge.assignment == Assignment::Flat && !edge.split;
  EXPECT_EQ(2, joints);
  EXPECT_DOUBLE_EQ(16.0, totalFaceArea(paper));
  EXPECT_TRUE(covered(paper, Vec2(2, 2)));  // the ring's inside is paper: it was never a hole
  EXPECT_EQ(1, euler(paper));
  EXPECT_TRUE(checkValidity(paper).ok()) << checkValidity(paper).summary();
}

TEST(SharedPatterns, EveryPatternWritesAndReadsBack)
{
  for (const char* name : { "null-values.fold", "two-pieces.fold", "hole.fold", "hole-in-face.fold", "slit.fold",
                            "interior-slit.fold", "kirigami.fold", "loose-crease.fold", "ring-on-a-stick.fold",
                            "cut-between-faces.fold", "two-pieces-folded.fold" })
  {
    const Paper paper = loadPattern(name);
    const Expected<FoldDocument> back = parseFold(formatFold(paper));
    ASSERT_TRUE(back.ok()) << name << ": " << back.message();
    const Paper& read = back->frames.front();
    EXPECT_EQ(paper.vertices.size(), read.vertices.size()) << name;
    EXPECT_EQ(paper.edges.size(), read.edges.size()) << name;
    EXPECT_EQ(paper.faces.size(), read.faces.size()) << name;
    EXPECT_DOUBLE_EQ(paper.sheet_area, read.sheet_area) << name;
    EXPECT_TRUE(checkValidity(read).ok()) << name << ": " << checkValidity(read).summary();
  }
}

}  // namespace
}  // namespace virtual_origami::core

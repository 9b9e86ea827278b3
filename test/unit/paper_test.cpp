#include <gtest/gtest.h>

#include "test_models.h"
#include "virtual_origami/core/kinematics.h"
#include "virtual_origami/core/paper.h"
#include "virtual_origami/core/validity.h"

using namespace virtual_origami::core;
using namespace virtual_origami::core::test;

TEST(Paper, SquareIsValid)
{
  const Paper paper = Paper::square(2.0);
  expectValid(paper);
  EXPECT_EQ(paper.vertices.size(), 4u);
  EXPECT_EQ(paper.edges.size(), 4u);
  EXPECT_EQ(paper.faces.size(), 1u);
  EXPECT_DOUBLE_EQ(paper.sheet_area, 4.0);
  EXPECT_DOUBLE_EQ(paper.faceArea(0), 4.0);
  EXPECT_TRUE(paper.faceNormal(0).isApprox(Vec3::UnitZ()));
}

TEST(Paper, AssignmentLetters)
{
  for (const char* letter : { "B", "M", "V", "F", "U", "C" })
    EXPECT_EQ(std::string(1, assignmentLetter(*assignmentFromLetter(letter))), letter);
  EXPECT_FALSE(assignmentFromLetter("X").has_value());
  EXPECT_FALSE(assignmentFromLetter("").has_value());
}

TEST(Paper, ValleyFoldAngleIsPositive)
{
  // Lift the right half towards the front (+z): a valley of 60°.
  Paper paper = Paper::square(1.0);
  creaseLine(paper, p3(0.5, -1), p3(0.5, 2));
  int hinge = -1;
  for (size_t e = 0; e < paper.edges.size(); ++e)
    if (paper.edges[e].isCrease())
      hinge = static_cast<int>(e);
  ASSERT_GE(hinge, 0);
  const double angle = M_PI / 3;
  for (Vertex& v : paper.vertices)
    if (v.crease_pattern.x() > 0.75)
      v.folded = Vec3(0.5 + 0.5 * std::cos(angle), v.folded.y(), 0.5 * std::sin(angle));
  EXPECT_NEAR(measureFoldAngle(paper, hinge), angle, 1e-12);
  updateFoldAngles(paper);
  EXPECT_EQ(paper.edges[hinge].assignment, Assignment::Valley);
  for (Vertex& v : paper.vertices)
    if (v.crease_pattern.x() > 0.75)
      v.folded.z() = -v.folded.z();
  EXPECT_NEAR(measureFoldAngle(paper, hinge), -angle, 1e-12);
  updateFoldAngles(paper);
  EXPECT_EQ(paper.edges[hinge].assignment, Assignment::Mountain);
  expectValid(paper);
}

TEST(Paper, LinkTopologyRejectsBrokenModels)
{
  Paper paper = Paper::square(1.0);
  paper.faces[0].vertices = { 0, 1, 2 };  // side 2-0 is not an edge
  const Status linked = linkTopology(paper);
  EXPECT_FALSE(linked.ok());
  EXPECT_NE(linked.message().find("not an edge"), std::string::npos);

  Paper twice = Paper::square(1.0);
  twice.faces.push_back(twice.faces[0]);  // every edge gets two faces on one side
  EXPECT_FALSE(linkTopology(twice).ok());
}

TEST(Validity, ReportsEachBrokenInvariant)
{
  Paper stretched = Paper::square(1.0);
  stretched.vertices[2].folded.x() += 1e-3;
  EXPECT_FALSE(checkValidity(stretched).ok());

  Paper clockwise = Paper::square(1.0);
  std::reverse(clockwise.faces[0].vertices.begin(), clockwise.faces[0].vertices.end());
  ASSERT_TRUE(linkTopology(clockwise).ok());
  EXPECT_FALSE(checkValidity(clockwise).ok());

  Paper nan = Paper::square(1.0);
  nan.vertices[1].folded.y() = std::nan("");
  EXPECT_FALSE(checkValidity(nan).ok());

  Paper area = Paper::square(1.0);
  area.sheet_area = 2.0;
  EXPECT_FALSE(checkValidity(area).ok());

  Paper extra = Paper::square(1.0);
  extra.vertices.push_back({});  // V − E + F = 2
  EXPECT_FALSE(checkValidity(extra).ok());
}

TEST(Kinematics, FoldAnglesPlaceFacesRigidly)
{
  Paper paper = Paper::square(1.0);
  const CreaseResult c = creaseLine(paper, p3(0.5, -1), p3(0.5, 2));
  std::vector<double> angles(paper.edges.size(), 0.0);
  angles[c.new_edges[0]] = M_PI / 2;
  const auto positions = foldedPositionsFromAngles(paper, angles, 0, Eigen::Isometry3d::Identity(), 1e-12);
  ASSERT_TRUE(positions.ok()) << positions.message();
  for (size_t v = 0; v < paper.vertices.size(); ++v)
    paper.vertices[v].folded = (*positions)[v];
  updateFoldAngles(paper);
  EXPECT_NEAR(paper.edges[c.new_edges[0]].fold_angle, M_PI / 2, 1e-12);
  expectValid(paper);
  // The pose of each face is recovered from its folded vertices.
  for (size_t f = 0; f < paper.faces.size(); ++f)
    for (int v : paper.faces[f].vertices)
    {
      const Vec2& c2 = paper.vertices[v].crease_pattern;
      EXPECT_LT((facePose(paper, static_cast<int>(f)) * Vec3(c2.x(), c2.y(), 0) - paper.vertices[v].folded).norm(),
                1e-12);
    }
}

TEST(Kinematics, AnglesThatDoNotCloseAreRejected)
{
  // Two creases through the centre (a degree-4 vertex): one folded, the other flat, cannot close.
  Paper paper = Paper::square(1.0);
  const CreaseResult a = creaseLine(paper, p3(0.5, -1), p3(0.5, 2));
  creaseLine(paper, p3(-1, 0.5), p3(2, 0.5));
  std::vector<double> angles(paper.edges.size(), 0.0);
  angles[a.new_edges[0]] = M_PI / 2;
  const auto positions = foldedPositionsFromAngles(paper, angles, 0, Eigen::Isometry3d::Identity(), 1e-9);
  EXPECT_FALSE(positions.ok());
  EXPECT_NE(positions.message().find("do not close"), std::string::npos) << positions.message();
}

TEST(Paper, FindsAVertexByItsCreasePatternPoint)
{
  const Paper paper = Paper::square(2.0);
  const int corner = paper.vertexAt(Vec2(2, 0));
  ASSERT_GE(corner, 0);
  EXPECT_EQ(paper.vertices[corner].crease_pattern, Vec2(2, 0));
  EXPECT_EQ(paper.vertexAt(Vec2(2, 1e-6)), -1);            // not within the default 1e-12
  EXPECT_EQ(paper.vertexAt(Vec2(2, 1e-6), 1e-5), corner);  // within a looser one
  EXPECT_EQ(paper.vertexAt(Vec2(1, 1), 0.5), -1);          // the centre is no vertex
}

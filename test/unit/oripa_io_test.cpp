// ORIPA .cp and .opx read: hand-written files under test/data/oripa (a square with one
// diagonal, crossing lines that must be split, one malformed line of each kind), inline edge
// cases of the planar graph, and generated tessellations read back from their segments.
#include "virtual_origami/core/oripa_io.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "virtual_origami/core/planar_geometry.h"
#include "virtual_origami/core/tessellations.h"
#include "virtual_origami/core/validity.h"

namespace virtual_origami::core
{
namespace
{
using ::testing::HasSubstr;
using ::testing::Not;

std::string dataFile(const std::string& name)
{
  return std::string(VO_SOURCE_DIR) + "/test/data/oripa/" + name;
}

size_t countAssignment(const Paper& paper, Assignment assignment)
{
  return std::count_if(paper.edges.begin(), paper.edges.end(),
                       [&](const Edge& e) { return e.assignment == assignment; });
}

/// What every loaded pattern promises: flat, valid, convex counter-clockwise faces, creases M or
/// V, outline edges Boundary.
void expectFlatValidPaper(const Paper& paper)
{
  const ValidityReport report = checkValidity(paper);
  EXPECT_TRUE(report.ok()) << report.summary();
  Paper relinked = paper;
  ASSERT_TRUE(linkTopology(relinked));
  EXPECT_TRUE(relinked == paper);
  for (const Vertex& v : paper.vertices)
    EXPECT_EQ(v.folded, Vec3(v.crease_pattern.x(), v.crease_pattern.y(), 0.0));
  for (const Edge& e : paper.edges)
  {
    EXPECT_EQ(e.fold_angle, 0.0);
    if (e.isCrease())
      EXPECT_TRUE(e.assignment == Assignment::Mountain || e.assignment == Assignment::Valley);
    else
      EXPECT_EQ(e.assignment, Assignment::Boundary);
  }
  for (size_t f = 0; f < paper.faces.size(); ++f)
  {
    const std::vector<int>& cycle = paper.faces[f].vertices;
    EXPECT_GT(paper.faceArea(static_cast<int>(f)), 0.0);
    for (size_t k = 0; k < cycle.size(); ++k)
    {
      const Vec2& a = paper.vertices[cycle[k]].crease_pattern;
      const Vec2& b = paper.vertices[cycle[(k + 1) % cycle.size()]].crease_pattern;
      const Vec2& c = paper.vertices[cycle[(k + 2) % cycle.size()]].crease_pattern;
      EXPECT_GE(cross2(b - a, c - b), -1e-12) << "face " << f;
    }
  }
}

int degree(const Paper& paper, int vertex)
{
  return static_cast<int>(std::count_if(paper.edges.begin(), paper.edges.end(), [&](const Edge& e) {
    return e.vertices[0] == vertex || e.vertices[1] == vertex;
  }));
}

class SquareWithDiagonal : public ::testing::TestWithParam<std::string>
{};

TEST_P(SquareWithDiagonal, LoadsAsTwoTriangles)
{
  const Expected<Paper> paper = readCreasePatternFile(dataFile(GetParam()));
  ASSERT_TRUE(paper) << paper.message();
  // The bottom side is written in two pieces meeting where an auxiliary line (dropped) touches
  // it: they are joined again.
  EXPECT_EQ(paper->vertices.size(), 4u);
  EXPECT_EQ(paper->edges.size(), 5u);
  EXPECT_EQ(paper->faces.size(), 2u);
  EXPECT_EQ(countAssignment(*paper, Assignment::Boundary), 4u);
  EXPECT_EQ(countAssignment(*paper, Assignment::Valley), 1u);
  // ORIPA's (−200, −200)–(200, 200) square becomes the unit square, y still up.
  const int low = paper->vertexAt(Vec2(0, 0), 1e-12), high = paper->vertexAt(Vec2(1, 1), 1e-12);
  ASSERT_GE(low, 0);
  ASSERT_GE(high, 0);
  EXPECT_GE(paper->vertexAt(Vec2(1, 0), 1e-12), 0);
  EXPECT_GE(paper->vertexAt(Vec2(0, 1), 1e-12), 0);
  const int diagonal = paper->findEdge(low, high);
  ASSERT_GE(diagonal, 0);
  EXPECT_EQ(paper->edges[diagonal].assignment, Assignment::Valley);
  EXPECT_NEAR(paper->sheet_area, 1.0, 1e-12);
  expectFlatValidPaper(*paper);

  const Expected<Paper> bigger = readCreasePatternFile(dataFile(GetParam()), 3.0);
  ASSERT_TRUE(bigger) << bigger.message();
  EXPECT_NEAR(bigger->sheet_area, 9.0, 1e-9);
  EXPECT_GE(bigger->vertexAt(Vec2(3, 3), 1e-9), 0);
}

INSTANTIATE_TEST_SUITE_P(BothFormats, SquareWithDiagonal,
                         ::testing::Values("square_diagonal.cp", "square_diagonal.opx"));

class PreliminaryBase : public ::testing::TestWithParam<std::string>
{};

TEST_P(PreliminaryBase, CrossingLinesAreSplitAndTheCentreFoldsFlat)
{
  const Expected<Paper> paper = readCreasePatternFile(dataFile(GetParam()));
  ASSERT_TRUE(paper) << paper.message();
  // Diagonals and the horizontal mid-line cross at the centre; the mid-lines end on the sides,
  // which the .cp writes split there and the .opx likewise.
  EXPECT_EQ(paper->vertices.size(), 9u);
  EXPECT_EQ(paper->edges.size(), 16u);
  EXPECT_EQ(paper->faces.size(), 8u);
  EXPECT_EQ(countAssignment(*paper, Assignment::Boundary), 8u);
  EXPECT_EQ(countAssignment(*paper, Assignment::Mountain), 3u);
  EXPECT_EQ(countAssignment(*paper, Assignment::Valley), 5u);
  const int centre = paper->vertexAt(Vec2(0.5, 0.5), 1e-12);
  ASSERT_GE(centre, 0);
  EXPECT_EQ(degree(*paper, centre), 8);
  for (const Face& f : paper->faces)
    EXPECT_EQ(f.vertices.size(), 3u);
  expectFlatValidPaper(*paper);
  // Five valleys and three mountains at 45° each: Maekawa and Kawasaki hold.
  const std::vector<std::string> problems = flatFoldabilityProblems(*paper);
  EXPECT_TRUE(problems.empty()) << problems.front();
}

INSTANTIATE_TEST_SUITE_P(BothFormats, PreliminaryBase,
                         ::testing::Values("preliminary_base.cp", "preliminary_base.opx"));

TEST(OripaCp, BlintzCrossingsAreSplitEverywhere)
{
  const Expected<Paper> paper = readCreasePatternFile(dataFile("blintz.cp"));
  ASSERT_TRUE(paper) << paper.message();
  // Four corners, four side mid-points, the centre and the four points where the diamond joining
  // the mid-points crosses the diagonals.
  EXPECT_EQ(paper->vertices.size(), 13u);
  EXPECT_EQ(paper->edges.size(), 28u);
  EXPECT_EQ(paper->faces.size(), 16u);
  EXPECT_EQ(countAssignment(*paper, Assignment::Boundary), 8u);   // sides split at the mid-points (T-junctions)
  EXPECT_EQ(countAssignment(*paper, Assignment::Valley), 8u);     // two diagonals in four pieces each
  EXPECT_EQ(countAssignment(*paper, Assignment::Mountain), 12u);  // mid-lines 2 × 2, diamond 4 × 2
  for (const Vec2& p : { Vec2(0.25, 0.25), Vec2(0.75, 0.25), Vec2(0.75, 0.75), Vec2(0.25, 0.75) })
  {
    const int v = paper->vertexAt(p, 1e-12);
    ASSERT_GE(v, 0) << p.transpose();
    EXPECT_EQ(degree(*paper, v), 4);
  }
  // The auxiliary line at y = 0.25 left nothing behind.
  EXPECT_LT(paper->vertexAt(Vec2(0, 0.25), 1e-9), 0);
  EXPECT_LT(paper->vertexAt(Vec2(0.5, 0.25), 1e-9), 0);
  expectFlatValidPaper(*paper);
}

struct Malformed
{
  std::string file;
  std::string message;
  std::string secret;  // file content the message must not quote
};

class MalformedFile : public ::testing::TestWithParam<Malformed>
{};

TEST_P(MalformedFile, IsRefusedByLineNumber)
{
  const Malformed& m = GetParam();
  const std::string path = dataFile(m.file);
  ASSERT_TRUE(std::filesystem::exists(path));
  const Expected<Paper> paper = readCreasePatternFile(path);
  ASSERT_FALSE(paper);
  EXPECT_THAT(paper.message(), HasSubstr(m.message));
  EXPECT_THAT(paper.message(), HasSubstr(path + ": "));
  if (!m.secret.empty())
  {
    EXPECT_THAT(paper.message(), Not(HasSubstr(m.secret)));
  }
}

INSTANTIATE_TEST_SUITE_P(
    OneOfEachKind, MalformedFile,
    ::testing::Values(Malformed{ "bad_field_count.cp", "line 3: expected 5 numbers (type x1 y1 x2 y2), found 4", "" },
                      Malformed{ "bad_type.cp", "line 2: unknown line type", "" },
                      Malformed{ "bad_number.cp", "line 4: x2 is not a number", "secret" },
                      Malformed{ "nan.cp", "line 5: x1 is not finite", "" },
                      Malformed{ "zero_length.cp", "line 6: zero-length segment", "" },
                      Malformed{ "no_boundary.cp", "no boundary", "" },
                      Malformed{ "dangling.cp", "line 6: the line ends without meeting another line", "" },
                      Malformed{ "bad_number.opx", "line 107: x1 is not a number", "2O0" },
                      Malformed{ "bad_type.opx", "line 44: unknown line type", "" },
                      Malformed{ "unclosed.opx", "line 8: an element opened here is never closed", "" },
                      Malformed{ "no_lines.opx", "no ORIPA lines", "" }));

const char* const kSquare = "1 0 0 4 0\n1 4 0 4 4\n1 4 4 0 4\n1 0 4 0 0\n";

Expected<Paper> square(const std::string& creases)
{
  return parseOripaCp(kSquare + creases);
}

TEST(OripaCp, TJunctionsSplitTheLineTheyMeet)
{
  // A vertical valley across the middle and a mountain from the left side ending on it.
  const Expected<Paper> paper = square("3 2 0 2 4\n2 0 1 2 1\n");
  ASSERT_TRUE(paper) << paper.message();
  EXPECT_EQ(paper->vertices.size(), 8u);
  EXPECT_EQ(paper->edges.size(), 10u);
  EXPECT_EQ(paper->faces.size(), 3u);
  const int t = paper->vertexAt(Vec2(0.5, 0.25), 1e-12);
  ASSERT_GE(t, 0);
  EXPECT_EQ(degree(*paper, t), 3);
  expectFlatValidPaper(*paper);
}

TEST(OripaCp, RepeatedAndOverlappingLinesMerge)
{
  // The same valley twice, once reversed, and a valley overlapping half of it; a mountain drawn
  // over the outline is outline.
  const Expected<Paper> paper = square("3 0 0 4 4\n3 4 4 0 0\n3 2 2 4 4\n2 0 0 4 0\n");
  ASSERT_TRUE(paper) << paper.message();
  EXPECT_EQ(paper->vertices.size(), 4u);
  EXPECT_EQ(paper->edges.size(), 5u);
  EXPECT_EQ(countAssignment(*paper, Assignment::Valley), 1u);
  expectFlatValidPaper(*paper);
}

TEST(OripaCp, ToleratesRoundingNoiseTabsCrlfAndAByteOrderMark)
{
  const std::string text = "\xEF\xBB\xBF"
                           "1\t-200.0\t-200.0\t200.0\t-200.0\r\n"
                           "1 200 -200 200 200\r\n"
                           "1 +200 200 -200 200\r\n"
                           "1 -200 200 -200 -200\r\n"
                           "\r\n"
                           "2 -199.99999999999997 -200 1.4210854715202004E-14 -3.1086244689504478E-15\r\n"
                           "3 0 0 200.00000000000003 199.99999999999994\r\n"
                           "3 -200 200 -1e-13 0\r\n"
                           "2 1.0e-14 0 200 -200\r\n";
  const Expected<Paper> paper = parseOripaCp(text);
  ASSERT_TRUE(paper) << paper.message();
  EXPECT_EQ(paper->vertices.size(), 5u);  // the two diagonals meet at one centre
  EXPECT_EQ(paper->faces.size(), 4u);
  expectFlatValidPaper(*paper);
}

TEST(OripaCp, KeepsTheOutlinesProportions)
{
  const Expected<Paper> paper = parseOripaCp("1 0 0 8 0\n1 8 0 8 4\n1 8 4 0 4\n1 0 4 0 0\n2 4 0 4 4\n", 2.0);
  ASSERT_TRUE(paper) << paper.message();
  EXPECT_GE(paper->vertexAt(Vec2(2, 1), 1e-12), 0);
  EXPECT_GE(paper->vertexAt(Vec2(1, 0), 1e-12), 0);
  EXPECT_NEAR(paper->sheet_area, 2.0, 1e-12);
}

TEST(OripaCp, RefusesWhatIsNotOnePieceOfConvexFaces)
{
  EXPECT_THAT(square("2 0 2 4 2\n3 1 2 3 2\n").message(), HasSubstr("line 5: mountain and valley on the same stretch "
                                                                    "(with line 6)"));
  EXPECT_THAT(square("1 0 2 4 2\n").message(), HasSubstr("line 5: a cut (type 1) line runs inside the paper"));
  EXPECT_THAT(square("2 1 1 3 1\n2 3 1 3 3\n2 3 3 1 3\n2 1 3 1 1\n").message(), HasSubstr("line 5: the line is not "
                                                                                          "connected to the rest of "
                                                                                          "the pattern"));
  EXPECT_THAT(square("2 0 0 5 5\n").message(), HasSubstr("line 5: the segment lies outside the outline"));
  // An L-shaped outline: the face round its inner corner is not convex.
  EXPECT_THAT(parseOripaCp("1 0 0 2 0\n1 2 0 2 1\n1 2 1 1 1\n1 1 1 1 2\n1 1 2 0 2\n1 0 2 0 0\n").message(),
              HasSubstr("is not convex"));
  // Two creases crossing inside a face without reaching anything else.
  EXPECT_THAT(square("2 1 2 3 2\n3 2 1 2 3\n").message(), HasSubstr("loose end"));
  EXPECT_THAT(square("2 0 0 4 4 5\n").message(), HasSubstr("line 5: expected 5 numbers"));
  EXPECT_THAT(square("2 0 0 4 inf\n").message(), HasSubstr("line 5: y2 is not finite"));
  EXPECT_THAT(square("2 0 0 4 1e999\n").message(), HasSubstr("line 5: y2 is not finite"));
  EXPECT_THAT(square("2.5 0 0 4 4\n").message(), HasSubstr("line 5: the line type is not an integer"));
  EXPECT_THAT(parseOripaCp("").message(), HasSubstr("no boundary"));
  EXPECT_THAT(parseOripaCp(kSquare, -1.0).message(), HasSubstr("size"));
}

TEST(OripaOpx, ReadsXmlEncoderOutputTolerantly)
{
  // Properties at their default (0) are left out; whitespace and comments anywhere.
  const std::string text = R"(<?xml version="1.0" encoding="UTF-8"?>
<java version="1.8.0" class="java.beans.XMLDecoder">
 <object class="oripa.DataSet" id="DataSet0">
  <!-- a comment with <tags> inside -->
  <void class="oripa.DataSet" method="getField"><string>lines</string>
   <void method="set"><object idref="DataSet0"/>
    <array class="oripa.OriLineProxy" length="5">
     <void index="0"><object class="oripa.OriLineProxy">
      <void property="type"><int>1</int></void>
      <void property="x1"><double>10.0</double></void></object></void>
     <void index="1"><object class='oripa.OriLineProxy'>
      <void property="type"><int> 1 </int></void>
      <void property="x0"><double>10.0</double></void><void property="x1"><double>10.0</double></void>
      <void property="y1"><double>10.0</double></void></object></void>
     <void index="2"><object class="oripa.OriLineProxy"><void property="type"><int>1</int></void>
      <void property="x0"><double>10.0</double></void><void property="y0"><double>1E1</double></void>
      <void property="y1"><double>10.0</double></void></object></void>
     <void index="3"><object class="oripa.OriLineProxy"><void property="type"><int>1</int></void>
      <void property="y0"><double>10.0</double></void></object></void>
     <void index="4"><object class="oripa.OriLineProxy"><void property="type"><int>2</int></void>
      <void property="selected"><boolean>true</boolean></void>
      <void property="x1"><double>10.0</double></void><void property="y1"><double>10.0</double></void>
     </object></void>
     <void index="5"><object class="oripa.OriLineProxy"/></void>
    </array>
   </void>
  </void>
 </object>
</java>
)";
  const Expected<std::vector<CreaseSegment>> segments = parseOripaOpxSegments(text);
  ASSERT_TRUE(segments) << segments.message();
  ASSERT_EQ(segments->size(), 5u);  // the sixth, all defaults, is auxiliary
  EXPECT_EQ((*segments)[0].line, 8);
  EXPECT_EQ((*segments)[0].a, Vec2(0, 0));
  EXPECT_EQ((*segments)[0].b, Vec2(10, 0));
  EXPECT_EQ((*segments)[4].assignment, Assignment::Mountain);
  const Expected<Paper> paper = parseOripaOpx(text);
  ASSERT_TRUE(paper) << paper.message();
  EXPECT_EQ(paper->faces.size(), 2u);
  expectFlatValidPaper(*paper);

  EXPECT_THAT(
      parseOripaOpx("<java><object class=\"oripa.OriLineProxy\">\n<void property=\"x0\"><double/></void>").message(),
      HasSubstr("line 2: x0 has no value"));
  EXPECT_THAT(parseOripaOpx("<java>\n<object class=\"oripa.OriLineProxy\"></void>").message(), HasSubstr("line 2: a "
                                                                                                         "closing tag "
                                                                                                         "that does "
                                                                                                         "not match "
                                                                                                         "the element "
                                                                                                         "opened on "
                                                                                                         "line 2"));
  EXPECT_THAT(parseOripaOpx("<java>\n\n<object class=\"oripa.OriLineProxy").message(), HasSubstr("line 3: a tag is "
                                                                                                 "never closed"));
  EXPECT_THAT(parseOripaOpx("<java>\n<!-- never closed").message(), HasSubstr("line 2: a comment is never closed"));
  EXPECT_THAT(parseOripaOpx("<java>\n</></java>").message(), HasSubstr("line 2: a tag without a name"));
  EXPECT_THAT(parseOripaOpx("<java>\n</>").message(), HasSubstr("line 2: a tag without a name"));
  EXPECT_THAT(parseOripaOpx("<java><object class=\"oripa.OriLineProxy\">\n<void property=\"type\"><int>NaN</int>"
                            "</void></object></java>")
                  .message(),
              HasSubstr("line 2: the line type is not an integer"));
}

TEST(OripaFiles, ChosenByExtension)
{
  EXPECT_THAT(readCreasePatternFile("pattern.svg").message(), HasSubstr("pattern.svg: not an ORIPA file"));
  EXPECT_THAT(readCreasePatternFile(dataFile("missing.cp")).message(), HasSubstr("cannot be read"));
  // Upper-case extensions, and an .opx that is really text in .cp form, is read as XML (and refused).
  const std::filesystem::path folder = std::filesystem::temp_directory_path() / "vo_oripa_io_test";
  std::filesystem::remove_all(folder);
  std::filesystem::create_directories(folder);
  std::filesystem::copy_file(dataFile("square_diagonal.cp"), folder / "SQUARE.CP");
  std::filesystem::copy_file(dataFile("square_diagonal.cp"), folder / "square.opx");
  const Expected<Paper> upper = readCreasePatternFile((folder / "SQUARE.CP").string());
  ASSERT_TRUE(upper) << upper.message();
  EXPECT_EQ(upper->faces.size(), 2u);
  EXPECT_THAT(readCreasePatternFile((folder / "square.opx").string()).message(), HasSubstr("no ORIPA lines"));
  std::filesystem::remove_all(folder);
}

/// A paper's edges as ORIPA segments.
std::vector<CreaseSegment> segmentsOf(const Paper& paper)
{
  std::vector<CreaseSegment> segments;
  int line = 0;
  for (const Edge& e : paper.edges)
    segments.push_back({ paper.vertices[e.vertices[0]].crease_pattern, paper.vertices[e.vertices[1]].crease_pattern,
                         e.assignment, ++line });
  return segments;
}

TEST(OripaSegments, GeneratedTessellationsReadBackAsThemselves)
{
  for (const TessellationKind kind : { TessellationKind::Miura, TessellationKind::Yoshimura,
                                       TessellationKind::SquareTwist, TessellationKind::Waterbomb })
  {
    SCOPED_TRACE(tessellationName(kind));
    const Expected<Tessellation> t = tessellationWithVertices(kind, 1500);
    ASSERT_TRUE(t) << t.message();
    const Paper& original = t->paper;
    // The reader puts the outline's box at the origin with its longer side 1.
    Vec2 low = original.vertices[0].crease_pattern, high = low;
    for (const Vertex& v : original.vertices)
    {
      low = low.cwiseMin(v.crease_pattern);
      high = high.cwiseMax(v.crease_pattern);
    }
    const double scale = 1.0 / (high - low).maxCoeff();
    const Expected<Paper> read = paperFromSegments(segmentsOf(original));
    ASSERT_TRUE(read) << read.message();
    EXPECT_EQ(read->vertices.size(), original.vertices.size());
    EXPECT_EQ(read->edges.size(), original.edges.size());
    EXPECT_EQ(read->faces.size(), original.faces.size());
    EXPECT_NEAR(read->sheet_area, original.sheet_area * scale * scale, 1e-9);
    for (const Edge& e : original.edges)
    {
      const int a = read->vertexAt((original.vertices[e.vertices[0]].crease_pattern - low) * scale, 1e-9);
      const int b = read->vertexAt((original.vertices[e.vertices[1]].crease_pattern - low) * scale, 1e-9);
      ASSERT_GE(a, 0);
      ASSERT_GE(b, 0);
      const int found = read->findEdge(a, b);
      ASSERT_GE(found, 0);
      EXPECT_EQ(read->edges[found].assignment, e.assignment);
    }
    expectFlatValidPaper(*read);
  }
}

TEST(OripaSegments, LongLinesCrossingEverywhere)
{
  // A 12 × 12 grid drawn as 13 + 13 full-length lines, valleys across and mountains up:
  // every crossing must be found.
  const int n = 12;
  std::vector<CreaseSegment> segments;
  int line = 0;
  for (int k = 0; k <= n; ++k)
  {
    const Assignment across = k == 0 || k == n ? Assignment::Boundary : Assignment::Valley;
    const Assignment up = k == 0 || k == n ? Assignment::Boundary : Assignment::Mountain;
    segments.push_back({ Vec2(0, k), Vec2(n, k), across, ++line });
    segments.push_back({ Vec2(k, 0), Vec2(k, n), up, ++line });
  }
  const Expected<Paper> paper = paperFromSegments(segments);
  ASSERT_TRUE(paper) << paper.message();
  EXPECT_EQ(paper->vertices.size(), static_cast<size_t>((n + 1) * (n + 1)));
  EXPECT_EQ(paper->faces.size(), static_cast<size_t>(n * n));
  EXPECT_EQ(paper->edges.size(), static_cast<size_t>(2 * n * (n + 1)));
  EXPECT_EQ(countAssignment(*paper, Assignment::Boundary), static_cast<size_t>(4 * n));
  expectFlatValidPaper(*paper);
}

}  // namespace
}  // namespace virtual_origami::core

// SVG crease patterns in Origami Simulator's convention: colours to kinds, opacity to target
// angles, transforms, styles and curves, and what is refused.
#include "virtual_origami/core/svg_pattern.h"

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "virtual_origami/core/model_file.h"
#include "virtual_origami/core/validity.h"

namespace virtual_origami::core
{
namespace
{
using ::testing::HasSubstr;

std::string patternText(const std::string& name)
{
  std::ifstream in(std::string(VO_SOURCE_DIR) + "/test/data/patterns/" + name);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

/// The edges between two crease-pattern points' vertices (any copy of each).
std::vector<const Edge*> edgesBetween(const Paper& paper, const Vec2& a, const Vec2& b)
{
  std::vector<const Edge*> found;
  for (const Edge& edge : paper.edges)
  {
    const Vec2& p = paper.vertices[edge.vertices[0]].crease_pattern;
    const Vec2& q = paper.vertices[edge.vertices[1]].crease_pattern;
    if (((p - a).norm() < 1e-12 && (q - b).norm() < 1e-12) || ((p - b).norm() < 1e-12 && (q - a).norm() < 1e-12))
      found.push_back(&edge);
  }
  return found;
}

int verticesAt(const Paper& paper, const Vec2& p)
{
  int count = 0;
  for (const Vertex& v : paper.vertices)
    count += (v.crease_pattern - p).norm() < 1e-12;
  return count;
}

double totalFaceArea(const Paper& paper)
{
  double area = 0;
  for (size_t f = 0; f < paper.faces.size(); ++f)
    area += paper.faceArea(static_cast<int>(f));
  return area;
}

std::string svg(const std::string& body)
{
  return R"(<svg xmlns="http://www.w3.org/2000/svg">)" + body + "</svg>";
}

TEST(SvgPattern, EveryColourIsItsKindAndOpacityItsTargetAngle)
{
  const std::string text = patternText("svg-colours.svg");
  ASSERT_EQ(modelFormat("designs/Colours.SVG"), ModelFormat::Svg);
  const Expected<Paper> loaded = parseModel(text, ModelFormat::Svg, 1.0);
  ASSERT_TRUE(loaded.ok()) << loaded.message();
  const Paper& paper = *loaded;
  EXPECT_TRUE(checkValidity(paper).ok()) << checkValidity(paper).summary();
  EXPECT_NEAR(1.0, totalFaceArea(paper), 1e-12);
  EXPECT_EQ(6u, paper.faces.size());

  // The valley down the middle, split where the mountain and the facet line meet it: 0.25 of 180°.
  for (const auto& [a, b] : { std::pair{ Vec2(0.5, 0), Vec2(0.5, 0.5) }, std::pair{ Vec2(0.5, 0.5), Vec2(0.5, 1) } })
  {
    const std::vector<const Edge*> valley = edgesBetween(paper, a, b);
    ASSERT_EQ(1u, valley.size());
    EXPECT_EQ(Assignment::Valley, valley[0]->assignment);
    ASSERT_TRUE(valley[0]->target_angle);
    EXPECT_DOUBLE_EQ(M_PI / 4, *valley[0]->target_angle);
  }
  // The mountain (red, style attribute): stroke-opacity 0.5, so -90°.
  const std::vector<const Edge*> mountain = edgesBetween(paper, Vec2(0, 0.5), Vec2(0.5, 0.5));
  ASSERT_EQ(1u, mountain.size());
  EXPECT_EQ(Assignment::Mountain, mountain[0]->assignment);
  ASSERT_TRUE(mountain[0]->target_angle);
  EXPECT_DOUBLE_EQ(-M_PI / 2, *mountain[0]->target_angle);
  // Yellow: a facet held flat, split where the cut's line runs on to it.
  for (const auto& [a, b] :
       { std::pair{ Vec2(0.5, 0.5), Vec2(0.75, 0.5) }, std::pair{ Vec2(0.75, 0.5), Vec2(1, 0.5) } })
  {
    const std::vector<const Edge*> facet = edgesBetween(paper, a, b);
    ASSERT_EQ(1u, facet.size());
    EXPECT_EQ(Assignment::Flat, facet[0]->assignment);
    EXPECT_FALSE(facet[0]->target_angle);
  }
  // Magenta: an undriven hinge, no target.
  const std::vector<const Edge*> hinge = edgesBetween(paper, Vec2(0.5, 1), Vec2(1, 0.5));
  ASSERT_EQ(1u, hinge.size());
  EXPECT_EQ(Assignment::Unassigned, hinge[0]->assignment);
  EXPECT_FALSE(hinge[0]->target_angle);
  EXPECT_TRUE(hinge[0]->isCrease());
  // Green: a cut up from the border, opened (two vertices where it leaves the border and along
  // it, one at its tip), its sides boundaries.
  EXPECT_EQ(2, verticesAt(paper, Vec2(0.75, 0)));
  EXPECT_EQ(2, verticesAt(paper, Vec2(0.75, 0.125)));
  EXPECT_EQ(1, verticesAt(paper, Vec2(0.75, 0.25)));
  const std::vector<const Edge*> sides = edgesBetween(paper, Vec2(0.75, 0.125), Vec2(0.75, 0.25));
  ASSERT_EQ(2u, sides.size());
  for (const Edge* side : sides)
    EXPECT_EQ(Assignment::Boundary, side->assignment);
  // Black: the border, corners at the paper's corners (y turned up).
  EXPECT_EQ(1u, edgesBetween(paper, Vec2(0, 0), Vec2(0, 0.5)).size());
  EXPECT_EQ(Assignment::Boundary, edgesBetween(paper, Vec2(0, 0), Vec2(0, 0.5))[0]->assignment);
}

TEST(SvgPattern, GroupsTransformsAndStyleSheetsApply)
{
  const Expected<Paper> loaded = parseSvgPattern(patternText("svg-groups.svg"), 2.0);
  ASSERT_TRUE(loaded.ok()) << loaded.message();
  const Paper& paper = *loaded;
  EXPECT_TRUE(checkValidity(paper).ok()) << checkValidity(paper).summary();
  ASSERT_EQ(2u, paper.faces.size());  // the valley in <defs> and the <text> draw nothing
  EXPECT_NEAR(4.0, totalFaceArea(paper), 1e-12);
  // The diagonal from the square's top left (drawn) to its bottom right: y turns up.
  const std::vector<const Edge*> diagonal = edgesBetween(paper, Vec2(0, 2), Vec2(2, 0));
  ASSERT_EQ(1u, diagonal.size());
  EXPECT_EQ(Assignment::Mountain, diagonal[0]->assignment);
  ASSERT_TRUE(diagonal[0]->target_angle);
  EXPECT_DOUBLE_EQ(-0.75 * M_PI, *diagonal[0]->target_angle);  // the group's stroke-opacity
}

TEST(SvgPattern, OpacityTimesStrokeOpacityIsTheFractionOf180Degrees)
{
  const Expected<std::vector<SvgStroke>> strokes = parseSvgStrokes(svg(R"svg(
    <line x2="1" stroke="blue"/>
    <line x2="1" stroke="red" opacity="50%"/>
    <line x2="1" stroke="#00f" opacity="0.5" stroke-opacity="0.5"/>
    <g stroke-opacity="0.2"><line x2="1" stroke="red" style="opacity: 0"/><line x2="1" stroke="red"/></g>
    <line x2="1" stroke="black" opacity="0.5"/>
    <line x2="1" stroke="#ff0" opacity="0.5"/>)svg"));
  ASSERT_TRUE(strokes.ok()) << strokes.message();
  ASSERT_EQ(7u, strokes->size());
  const std::vector<double> expected = { M_PI, -M_PI / 2, M_PI / 4, -0.0, -0.2 * M_PI };
  for (size_t i = 0; i < expected.size(); ++i)
  {
    ASSERT_TRUE((*strokes)[i].target_angle) << i;
    EXPECT_DOUBLE_EQ(expected[i], *(*strokes)[i].target_angle) << i;
  }
  EXPECT_FALSE((*strokes)[5].target_angle);  // a border folds nowhere
  EXPECT_FALSE((*strokes)[6].target_angle);  // a facet is held flat by its kind
}

TEST(SvgPattern, ReadsStyleSheetsInCdataAndEntitiesInAttributes)
{
  const Expected<std::vector<SvgStroke>> strokes = parseSvgStrokes(R"svg(<?xml version="1.0"?>
<!-- a comment with <line stroke="red"/> in it draws nothing -->
<svg:svg xmlns:svg="http://www.w3.org/2000/svg">
  <svg:style><![CDATA[ svg|x, .m > .n { stroke: blue } line.v { stroke: #0000FF !important } ]]></svg:style>
  <svg:line class="v other" x2="1"/>
  <svg:line stroke="&#35;f00" x2="2"/>
  <svg:line stroke="&#x23;ff0000" style="display:none" x2="3"/>
</svg:svg>)svg");
  ASSERT_TRUE(strokes.ok()) << strokes.message();
  ASSERT_EQ(2u, strokes->size());
  EXPECT_EQ(Assignment::Valley, (*strokes)[0].assignment);  // by the sheet's line.v rule
  EXPECT_EQ(Assignment::Mountain, (*strokes)[1].assignment);
  EXPECT_EQ(Vec2(2, 0), (*strokes)[1].b);
}

TEST(SvgPattern, TransformsCompose)
{
  const Expected<std::vector<SvgStroke>> strokes = parseSvgStrokes(svg(R"svg(
    <g transform="rotate(90)"><line x1="1" y1="0" x2="2" y2="0" stroke="red"/></g>
    <line transform="matrix(1 0 0 1 5 7) scale(2 3)" x1="1" y1="1" x2="0" y2="0" stroke="blue"/>
    <line transform="rotate(180 10 10)" x1="10" y1="0" x2="0" y2="10" stroke="black"/>
    <line transform="skewX(45)" x1="0" y1="1" x2="0" y2="2" stroke="black"/>)svg"));
  ASSERT_TRUE(strokes.ok()) << strokes.message();
  ASSERT_EQ(4u, strokes->size());
  EXPECT_TRUE((*strokes)[0].a.isApprox(Vec2(0, 1), 1e-12));
  EXPECT_TRUE((*strokes)[0].b.isApprox(Vec2(0, 2), 1e-12));
  EXPECT_TRUE((*strokes)[1].a.isApprox(Vec2(7, 10), 1e-12));
  EXPECT_TRUE((*strokes)[1].b.isApprox(Vec2(5, 7), 1e-12));
  EXPECT_TRUE((*strokes)[2].a.isApprox(Vec2(10, 20), 1e-12));
  EXPECT_TRUE((*strokes)[2].b.isApprox(Vec2(20, 10), 1e-12));
  EXPECT_TRUE((*strokes)[3].a.isApprox(Vec2(1, 1), 1e-12));
  EXPECT_TRUE((*strokes)[3].b.isApprox(Vec2(2, 2), 1e-12));
}

TEST(SvgPattern, PathCommandsAndCurvesBecomeStrokes)
{
  // Relative and absolute lines, H (twice: ".5.5" is two numbers) and V, a close; numbers run
  // together as SVG allows.
  const Expected<std::vector<SvgStroke>> lines =
      parseSvgStrokes(svg(R"(<path stroke="#000" d="m1,1l2-0h.5.5V3H1z"/>)"));
  ASSERT_TRUE(lines.ok()) << lines.message();
  const std::vector<Vec2> corners = { { 1, 1 }, { 3, 1 }, { 3.5, 1 }, { 4, 1 }, { 4, 3 }, { 1, 3 }, { 1, 1 } };
  ASSERT_EQ(corners.size() - 1, lines->size());
  for (size_t i = 0; i + 1 < corners.size(); ++i)
  {
    EXPECT_EQ(corners[i], (*lines)[i].a) << i;
    EXPECT_EQ(corners[i + 1], (*lines)[i].b) << i;
  }
  // A cubic curve: 16 strokes through points of the Bézier curve.
  const Expected<std::vector<SvgStroke>> cubic = parseSvgStrokes(svg(R"(<path stroke="red" d="M0 0C0 1 1 1 1 0"/>)"));
  ASSERT_TRUE(cubic.ok()) << cubic.message();
  ASSERT_EQ(16u, cubic->size());
  EXPECT_TRUE((*cubic)[7].b.isApprox(Vec2(0.5, 0.75), 1e-12));  // t = 1/2
  EXPECT_EQ(Vec2(1, 0), cubic->back().b);
  // An arc: a half circle of radius 1 about (1, 0), every point on it.
  const Expected<std::vector<SvgStroke>> arc = parseSvgStrokes(svg(R"(<path stroke="blue" d="M0 0A1 1 0 0 1 2 0"/>)"));
  ASSERT_TRUE(arc.ok()) << arc.message();
  ASSERT_EQ(16u, arc->size());
  for (const SvgStroke& s : *arc)
    EXPECT_NEAR(1.0, (s.b - Vec2(1, 0)).norm(), 1e-12);
  EXPECT_LT((*arc)[7].b.y(), -0.99);  // sweep 1 with y down: through (1, -1)
  EXPECT_TRUE(arc->back().b.isApprox(Vec2(2, 0), 1e-12));
}

TEST(SvgPattern, AHoleDrawnInBlackGetsNoFace)
{
  const Expected<Paper> paper = parseSvgPattern(svg(R"(
    <rect x="0" y="0" width="30" height="30" stroke="black" fill="none"/>
    <rect x="10" y="10" width="10" height="10" stroke="black" fill="none"/>
    <path stroke="#f00" d="M0 0L10 10M30 0L20 10M30 30L20 20M0 30L10 20"/>)"),
                                                3.0);
  ASSERT_TRUE(paper.ok()) << paper.message();
  EXPECT_EQ(4u, paper->faces.size());
  EXPECT_NEAR(8.0, totalFaceArea(*paper), 1e-12);
  EXPECT_TRUE(checkValidity(*paper).ok()) << checkValidity(*paper).summary();
}

TEST(SvgPattern, PointsWithinTheMergeToleranceAreOne)
{
  // A 400-unit square whose diagonal ends 2 units from the corners: within Origami Simulator's 3.
  const Expected<Paper> paper = parseSvgPattern(svg(R"(
    <rect x="0" y="0" width="400" height="400" stroke="black" fill="none"/>
    <line x1="2" y1="1" x2="398" y2="399" stroke="red"/>)"),
                                                1.0);
  ASSERT_TRUE(paper.ok()) << paper.message();
  EXPECT_EQ(4u, paper->vertices.size());
  EXPECT_EQ(2u, paper->faces.size());
}

TEST(SvgPattern, StrokesOnOneStretchKeepOrigamiSimulatorsStrongerKind)
{
  // A square's diagonal drawn as a valley, then as a mountain, then as a hinge: a mountain.
  const Expected<Paper> paper = parseSvgPattern(svg(R"(
    <rect x="0" y="0" width="100" height="100" stroke="black" fill="none"/>
    <line x1="0" y1="0" x2="100" y2="100" stroke="blue"/>
    <line x1="100" y1="100" x2="0" y2="0" stroke="red" stroke-opacity="0.5"/>
    <line x1="0" y1="0" x2="100" y2="100" stroke="magenta"/>
    <line x1="0" y1="0" x2="0" y2="100" stroke="red"/>)"),
                                                1.0);
  ASSERT_TRUE(paper.ok()) << paper.message();
  const std::vector<const Edge*> diagonal = edgesBetween(*paper, Vec2(0, 1), Vec2(1, 0));
  ASSERT_EQ(1u, diagonal.size());
  EXPECT_EQ(Assignment::Mountain, diagonal[0]->assignment);
  EXPECT_DOUBLE_EQ(-M_PI / 2, *diagonal[0]->target_angle);
  // The mountain drawn over the border: a border.
  const std::vector<const Edge*> side = edgesBetween(*paper, Vec2(0, 0), Vec2(0, 1));
  ASSERT_EQ(1u, side.size());
  EXPECT_EQ(Assignment::Boundary, side[0]->assignment);
}

TEST(SvgPattern, RefusesNamingTheElement)
{
  const std::vector<std::pair<std::string, std::string>> cases = {
    { svg("\n<line x1='0' y1='0' x2='1' y2='1' stroke='#808080'/>"), "<line> on line 2: its stroke colour is not one "
                                                                     "of the pattern's" },
    { svg("<path stroke='red' d='M0 0 L1'/>"), "<path> on line 1: path data: the L command is missing a number" },
    { svg("<path stroke='red' d='M0 0 X1 1'/>"), "<path> on line 1: path data has an unknown command X" },
    { svg("<line stroke='red' transform='spin(3)' x2='1'/>"), "transform spin() is not one SVG defines" },
    { svg("<g><line stroke='red' x2='1'></g>"), "line 1: a closing tag that does not match" },
    { "<html></html>", "not an SVG drawing: its root element is <html>" },
    { svg("<rect width='1' height='1' fill='red'/>"), "no strokes in the pattern's colours" },
  };
  for (const auto& [text, expected] : cases)
  {
    const Expected<Paper> paper = parseSvgPattern(text, 1.0);
    EXPECT_FALSE(paper.ok()) << text;
    EXPECT_THAT(paper.message(), HasSubstr(expected)) << text;
  }
}

}  // namespace
}  // namespace virtual_origami::core

// FOLD read and write: round trips, the public example files, and broken input.
#include "virtual_origami/core/fold_io.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Geometry>
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <sys/stat.h>
#include <unistd.h>

#include "virtual_origami/core/crease.h"
#include "virtual_origami/core/validity.h"

namespace virtual_origami::core
{
namespace
{
using ::testing::HasSubstr;

std::string exampleFile(const std::string& name)
{
  return std::string(VO_SOURCE_DIR) + "/test/data/fold-examples/" + name;
}

/// A fresh empty folder for files a test writes.
std::filesystem::path scratchFolder(const std::string& name)
{
  const std::filesystem::path folder = std::filesystem::temp_directory_path() / ("vo_fold_io_test_" + name);
  std::filesystem::remove_all(folder);
  std::filesystem::create_directories(folder);
  return folder;
}

/// A unit square cut along x = 0.5, its right half split by the diagonal (0.5, 0)-(1, 1), and
/// that half turned up about x = 0.5 by `angle` (a valley for angle > 0).
Paper halfFoldedSquare(double angle)
{
  Paper paper;
  const Vec2 corners[6] = { { 0, 0 }, { 0.5, 0 }, { 1, 0 }, { 1, 1 }, { 0.5, 1 }, { 0, 1 } };
  for (const Vec2& c : corners)
    paper.vertices.push_back({ c, Vec3(c.x(), c.y(), 0.0) });
  const auto addEdge = [&](int a, int b, Assignment assignment) {
    Edge edge;  // flat, no faces yet
    edge.vertices = { a, b };
    edge.assignment = assignment;
    paper.edges.push_back(edge);
  };
  for (auto [a, b] : { std::pair{ 0, 1 }, { 1, 2 }, { 2, 3 }, { 3, 4 }, { 4, 5 }, { 5, 0 } })
    addEdge(a, b, Assignment::Boundary);
  addEdge(1, 4, Assignment::Unassigned);
  addEdge(1, 3, Assignment::Unassigned);
  paper.faces.push_back({ { 0, 1, 4, 5 }, {} });
  paper.faces.push_back({ { 1, 2, 3 }, {} });
  paper.faces.push_back({ { 1, 3, 4 }, {} });
  paper.sheet_area = 1.0;
  EXPECT_TRUE(linkTopology(paper).ok());
  const Eigen::AngleAxisd turn(-angle, Vec3::UnitY());
  const Vec3 hinge(0.5, 0.0, 0.0);
  for (int v : { 2, 3 })
    paper.vertices[v].folded = hinge + turn * (paper.vertices[v].folded - hinge);
  updateFoldAngles(paper);
  paper.face_orders.push_back({ 0, 2, 1 });
  return paper;
}

/// Crease pattern, folded positions and topology identical; fold angles within 1e-12.
void expectSamePaper(const Paper& expected, const Paper& actual)
{
  ASSERT_EQ(expected.vertices.size(), actual.vertices.size());
  ASSERT_EQ(expected.edges.size(), actual.edges.size());
  ASSERT_EQ(expected.faces.size(), actual.faces.size());
  for (size_t v = 0; v < expected.vertices.size(); ++v)
  {
    EXPECT_EQ(expected.vertices[v].crease_pattern, actual.vertices[v].crease_pattern) << "vertex " << v;
    EXPECT_EQ(expected.vertices[v].folded, actual.vertices[v].folded) << "vertex " << v;
  }
  for (size_t e = 0; e < expected.edges.size(); ++e)
  {
    EXPECT_EQ(expected.edges[e].vertices, actual.edges[e].vertices) << "edge " << e;
    EXPECT_EQ(expected.edges[e].faces, actual.edges[e].faces) << "edge " << e;
    EXPECT_EQ(expected.edges[e].assignment, actual.edges[e].assignment) << "edge " << e;
    EXPECT_EQ(expected.edges[e].split, actual.edges[e].split) << "edge " << e;
    EXPECT_NEAR(expected.edges[e].fold_angle, actual.edges[e].fold_angle, 1e-12) << "edge " << e;
  }
  for (size_t f = 0; f < expected.faces.size(); ++f)
  {
    EXPECT_EQ(expected.faces[f].vertices, actual.faces[f].vertices) << "face " << f;
    EXPECT_EQ(expected.faces[f].edges, actual.faces[f].edges) << "face " << f;
  }
  EXPECT_EQ(expected.face_orders, actual.face_orders);
  EXPECT_NEAR(expected.sheet_area, actual.sheet_area, 1e-12);
}

FoldDocument parseOrFail(const std::string& text)
{
  Expected<FoldDocument> document = parseFold(text);
  EXPECT_TRUE(document.ok()) << document.message();
  return document.ok() ? *document : FoldDocument{};
}

Paper loadExample(const std::string& name)
{
  Expected<Paper> paper = loadPaper(exampleFile(name));
  EXPECT_TRUE(paper.ok()) << name << ": " << paper.message();
  return paper.ok() ? *paper : Paper{};
}

double totalFaceArea(const Paper& paper)
{
  double area = 0;
  for (size_t f = 0; f < paper.faces.size(); ++f)
    area += paper.faceArea(static_cast<int>(f));
  return area;
}

/// Every edge of every face as long unfolded as folded.
void expectEdgeLengthsKept(const Paper& paper, double tolerance)
{
  for (const Edge& edge : paper.edges)
  {
    const Vertex& a = paper.vertices[edge.vertices[0]];
    const Vertex& b = paper.vertices[edge.vertices[1]];
    EXPECT_NEAR((a.crease_pattern - b.crease_pattern).norm(), (a.folded - b.folded).norm(), tolerance)
        << "edge " << edge.vertices[0] << "-" << edge.vertices[1];
  }
}

std::vector<Vec2> polygonOf(const Paper& paper, int face)
{
  std::vector<Vec2> polygon;
  for (int v : paper.faces[face].vertices)
    polygon.push_back(paper.vertices[v].crease_pattern);
  return polygon;
}

/// Whether some side of a convex counter-clockwise polygon `a` has all of `b` on or beyond it.
bool separatedBySideOf(const std::vector<Vec2>& a, const std::vector<Vec2>& b, double tolerance)
{
  for (size_t i = 0; i < a.size(); ++i)
  {
    const Vec2 side = a[(i + 1) % a.size()] - a[i];
    const Vec2 inward(-side.y(), side.x());
    bool all_outside = true;
    for (const Vec2& p : b)
      all_outside = all_outside && inward.normalized().dot(p - a[i]) <= tolerance;
    if (all_outside)
      return true;
  }
  return false;
}

/// Convex faces' interiors meet unless a side of one separates them (separating axis theorem).
void expectFacesDoNotOverlap(const Paper& paper, double tolerance)
{
  for (size_t f = 0; f < paper.faces.size(); ++f)
    for (size_t g = f + 1; g < paper.faces.size(); ++g)
    {
      const std::vector<Vec2> a = polygonOf(paper, static_cast<int>(f));
      const std::vector<Vec2> b = polygonOf(paper, static_cast<int>(g));
      EXPECT_TRUE(separatedBySideOf(a, b, tolerance) || separatedBySideOf(b, a, tolerance))
          << "faces " << f << " and " << g << " overlap in the crease pattern";
    }
}

int edgeBetween(const Paper& paper, int a, int b)
{
  const int e = paper.findEdge(a, b);
  EXPECT_GE(e, 0) << "no edge " << a << "-" << b;
  return e;
}

TEST(FoldIo, HandBuiltPaperIsValidAndFolded)
{
  const Paper paper = halfFoldedSquare(M_PI / 2);
  EXPECT_TRUE(checkValidity(paper).ok()) << checkValidity(paper).summary();
  const Edge& hinge = paper.edges[edgeBetween(paper, 1, 4)];
  EXPECT_EQ(Assignment::Valley, hinge.assignment);
  EXPECT_NEAR(M_PI / 2, hinge.fold_angle, 1e-12);
}

TEST(FoldIo, RoundTripKeepsCreasePatternFoldedFormAndTopology)
{
  const Paper paper = halfFoldedSquare(M_PI / 2);
  const FoldDocument document = parseOrFail(formatFold(paper, "half fold"));
  EXPECT_EQ("half fold", document.title);
  EXPECT_EQ("virtual_origami", document.creator);
  ASSERT_EQ(2u, document.frames.size());
  expectSamePaper(paper, document.frames[1]);

  // The key frame is the crease pattern, folded by its fold angles to the same state.
  const Paper& key = document.frames[0];
  ASSERT_EQ(paper.vertices.size(), key.vertices.size());
  for (size_t v = 0; v < paper.vertices.size(); ++v)
  {
    EXPECT_EQ(paper.vertices[v].crease_pattern, key.vertices[v].crease_pattern);
    EXPECT_LT((paper.vertices[v].folded - key.vertices[v].folded).norm(), 1e-12) << "vertex " << v;
  }
}

TEST(FoldIo, WrittenFileIsFoldFormat)
{
  const Paper paper = halfFoldedSquare(M_PI / 3);
  const nlohmann::json file = nlohmann::json::parse(formatFold(paper));
  EXPECT_EQ(1.1, file["file_spec"].get<double>());
  EXPECT_EQ("virtual_origami", file["file_creator"]);
  EXPECT_EQ(nlohmann::json({ "singleModel" }), file["file_classes"]);
  EXPECT_EQ(nlohmann::json({ "creasePattern" }), file["frame_classes"]);
  EXPECT_EQ(2u, file["vertices_coords"][0].size());
  EXPECT_EQ("V", file["edges_assignment"][edgeBetween(paper, 1, 4)]);
  EXPECT_NEAR(60.0, file["edges_foldAngle"][edgeBetween(paper, 1, 4)].get<double>(), 1e-12);
  ASSERT_EQ(1u, file["file_frames"].size());
  const nlohmann::json& folded = file["file_frames"][0];
  EXPECT_EQ(nlohmann::json({ "foldedForm" }), folded["frame_classes"]);
  EXPECT_EQ(true, folded["frame_inherit"]);
  EXPECT_EQ(0, folded["frame_parent"]);
  EXPECT_EQ(3u, folded["vertices_coords"][0].size());
  EXPECT_EQ(nlohmann::json({ 2, 0, 1 }), file["faceOrders"][0]);  // FaceOrder{0, 2, +1} as FOLD [2, 0, 1]
}

TEST(FoldIo, WrittenFileLoadsBackIdentical)
{
  const std::filesystem::path folder = scratchFolder("written");
  const std::string path = (folder / "half.fold").string();
  const Paper paper = halfFoldedSquare(2.0);
  const Status written = writeTextFile(path, formatFold(paper));
  ASSERT_TRUE(written.ok()) << written.message();
  EXPECT_FALSE(std::filesystem::exists(path + ".tmp"));
  const Expected<Paper> loaded = loadPaper(path);
  ASSERT_TRUE(loaded.ok()) << loaded.message();
  expectSamePaper(paper, *loaded);
  EXPECT_TRUE(checkValidity(*loaded).ok()) << checkValidity(*loaded).summary();
  std::filesystem::remove_all(folder);
}

TEST(FoldIo, SequenceRoundTripHasOneFramePerStep)
{
  const std::vector<Paper> steps{ halfFoldedSquare(0.0), halfFoldedSquare(M_PI / 4), halfFoldedSquare(-2.5) };
  const FoldDocument document = parseOrFail(formatFoldSequence(steps, "steps"));
  EXPECT_EQ("steps", document.title);
  ASSERT_EQ(steps.size(), document.frames.size());
  for (size_t i = 0; i < steps.size(); ++i)
  {
    SCOPED_TRACE("step " + std::to_string(i));
    expectSamePaper(steps[i], document.frames[i]);
  }
}

TEST(FoldIo, SequenceStepsMayDifferInTopology)
{
  const std::vector<Paper> steps{ Paper::square(2.0), halfFoldedSquare(1.0) };
  const FoldDocument document = parseOrFail(formatFoldSequence(steps));
  ASSERT_EQ(2u, document.frames.size());
  expectSamePaper(steps[0], document.frames[0]);
  expectSamePaper(steps[1], document.frames[1]);
}

TEST(FoldIo, LoadsDiagonalCreasePattern)
{
  const Expected<FoldDocument> document = readFoldFile(exampleFile("diagonal-cp.fold"));
  ASSERT_TRUE(document.ok()) << document.message();
  EXPECT_EQ("diagonal", document->title);
  EXPECT_EQ("Crease Pattern Editor", document->creator);
  ASSERT_EQ(1u, document->frames.size());
  const Paper& paper = document->frames[0];
  EXPECT_EQ(2u, paper.faces.size());
  const Edge& diagonal = paper.edges[edgeBetween(paper, 3, 1)];
  EXPECT_EQ(Assignment::Valley, diagonal.assignment);
  EXPECT_TRUE(diagonal.isCrease());
  EXPECT_EQ(0.0, diagonal.fold_angle);
  EXPECT_DOUBLE_EQ(1.0, paper.sheet_area);
  for (const Vertex& v : paper.vertices)
    EXPECT_EQ(Vec3(v.crease_pattern.x(), v.crease_pattern.y(), 0.0), v.folded);
  EXPECT_TRUE(checkValidity(paper).ok()) << checkValidity(paper).summary();
}

TEST(FoldIo, LoadsCubeNetWithoutFaces)
{
  const Paper paper = loadExample("vertex.fold");
  ASSERT_EQ(6u, paper.faces.size());  // not loaded: stop before indexing its edges
  EXPECT_DOUBLE_EQ(6.0, paper.sheet_area);
  EXPECT_DOUBLE_EQ(6.0, totalFaceArea(paper));
  EXPECT_EQ(1, static_cast<int>(paper.vertices.size()) - static_cast<int>(paper.edges.size()) +
                   static_cast<int>(paper.faces.size()));
  for (size_t f = 0; f < paper.faces.size(); ++f)
    EXPECT_DOUBLE_EQ(1.0, paper.faceArea(static_cast<int>(f))) << "face " << f;
  EXPECT_EQ(Assignment::Valley, paper.edges[edgeBetween(paper, 8, 11)].assignment);
  EXPECT_EQ(Assignment::Boundary, paper.edges[edgeBetween(paper, 3, 4)].assignment);
  EXPECT_TRUE(checkValidity(paper).ok()) << checkValidity(paper).summary();
}

TEST(FoldIo, UnfoldsSimpleFoldedForm)
{
  const Paper paper = loadExample("simple.fold");
  ASSERT_EQ(4u, paper.faces.size());
  expectEdgeLengthsKept(paper, 1e-12);
  EXPECT_NEAR(4.0, paper.sheet_area, 1e-12);  // it unfolds to a right triangle with legs 2√2
  expectFacesDoNotOverlap(paper, 1e-12);
  // Vertices 4 and 5 fold to one point but are different points of the sheet.
  EXPECT_EQ(paper.vertices[4].folded, paper.vertices[5].folded);
  EXPECT_NEAR(4.0, (paper.vertices[4].crease_pattern - paper.vertices[5].crease_pattern).norm(), 1e-12);
  // The valley stands at 90°; the two mountains lie folded flat, on the mountain side.
  EXPECT_NEAR(M_PI / 2, paper.edges[edgeBetween(paper, 0, 2)].fold_angle, 1e-12);
  EXPECT_NEAR(-M_PI, paper.edges[edgeBetween(paper, 0, 1)].fold_angle, 1e-12);
  EXPECT_NEAR(-M_PI, paper.edges[edgeBetween(paper, 1, 2)].fold_angle, 1e-12);
  // Face orders kept: FOLD [f, g, s] is FaceOrder{g, f, s}.
  ASSERT_EQ(12u, paper.face_orders.size());
  EXPECT_EQ((FaceOrder{ 2, 0, -1 }), paper.face_orders[1]);
  EXPECT_EQ((FaceOrder{ 0, 3, -1 }), paper.face_orders[9]);
  EXPECT_TRUE(checkValidity(paper).ok()) << checkValidity(paper).summary();
}

TEST(FoldIo, SimpleFoldedFormFaceOrdersSurviveRewriting)
{
  const std::string path = exampleFile("simple.fold");
  const Paper paper = loadExample("simple.fold");
  std::ifstream in(path);
  const nlohmann::json original = nlohmann::json::parse(in);
  const nlohmann::json rewritten = nlohmann::json::parse(formatFold(paper));
  EXPECT_EQ(original["faceOrders"], rewritten["faceOrders"]);
  const Expected<FoldDocument> reloaded = parseFold(formatFold(paper));
  ASSERT_TRUE(reloaded.ok()) << reloaded.message();
  expectSamePaper(paper, reloaded->frames.back());
}

TEST(FoldIo, UnfoldsSquareTwist)
{
  const Expected<FoldDocument> document = readFoldFile(exampleFile("squaretwist.fold"));
  ASSERT_TRUE(document.ok()) << document.message();
  EXPECT_EQ("Rigidly folded square twist", document->title);
  const Paper& paper = document->frames.back();
  ASSERT_EQ(9u, paper.faces.size());
  expectEdgeLengthsKept(paper, 1e-4);
  expectFacesDoNotOverlap(paper, 1e-6);
  EXPECT_NEAR(paper.sheet_area, totalFaceArea(paper), 1e-12);
  for (size_t f = 0; f < paper.faces.size(); ++f)
    EXPECT_GT(paper.faceArea(static_cast<int>(f)), 0.0) << "face " << f;
  // Face 0 lies flat in z = 0 facing +z: the unfolding keeps it where it is (up to the
  // averaging of the rounded positions its neighbours give its corners).
  for (int v : { 0, 1, 2, 3 })
    EXPECT_LT((paper.vertices[v].folded.head<2>() - paper.vertices[v].crease_pattern).norm(), 1e-5) << "vertex " << v;
  // Measured fold angles have the signs the file assigns.
  for (const Edge& edge : paper.edges)
  {
    if (edge.assignment == Assignment::Mountain)
    {
      EXPECT_LT(edge.fold_angle, 0.0) << edge.vertices[0] << "-" << edge.vertices[1];
    }
    if (edge.assignment == Assignment::Valley)
    {
      EXPECT_GT(edge.fold_angle, 0.0) << edge.vertices[0] << "-" << edge.vertices[1];
    }
  }
  ValidityTolerance rounded;
  rounded.length = 1e-4;
  rounded.convexity = 1e-5;
  EXPECT_TRUE(checkValidity(paper, rounded).ok()) << checkValidity(paper, rounded).summary();
}

TEST(FoldIo, EveryExampleLoadsAndLoadsBackAfterWriting)
{
  for (const char* name : { "diagonal-cp.fold", "vertex.fold", "simple.fold", "squaretwist.fold" })
  {
    SCOPED_TRACE(name);
    const Paper paper = loadExample(name);
    ASSERT_FALSE(paper.faces.empty());
    const Expected<FoldDocument> again = parseFold(formatFold(paper));
    ASSERT_TRUE(again.ok()) << again.message();
    expectSamePaper(paper, again->frames.back());
  }
}

TEST(FoldIo, MirrorsAClockwiseCreasePatternInsteadOfReversingFaces)
{
  const FoldDocument document = parseOrFail(R"({
    "vertices_coords": [[0,0],[1,0],[1,1],[0,1]],
    "edges_vertices": [[0,1],[1,2],[2,3],[3,0],[1,3]],
    "edges_assignment": ["B","B","B","B","M"],
    "faces_vertices": [[0,3,1],[1,3,2]]})");
  const Paper& paper = document.frames[0];
  EXPECT_EQ((std::vector<int>{ 0, 3, 1 }), paper.faces[0].vertices);
  EXPECT_EQ(Vec2(-1, 0), paper.vertices[1].crease_pattern);
  EXPECT_EQ(Assignment::Mountain, paper.edges[4].assignment);
  EXPECT_GT(paper.faceArea(0), 0.0);
  EXPECT_TRUE(checkValidity(paper).ok()) << checkValidity(paper).summary();
}

TEST(FoldIo, FoldsACreasePatternByItsFoldAngles)
{
  const FoldDocument document = parseOrFail(R"({
    "vertices_coords": [[0,0],[1,0],[1,1],[0,1]],
    "edges_vertices": [[0,1],[1,2],[2,3],[3,0],[1,3]],
    "edges_assignment": ["B","B","B","B","V"],
    "edges_foldAngle": [0,0,0,0,90],
    "faces_vertices": [[0,1,3],[1,2,3]]})");
  const Paper& paper = document.frames[0];
  EXPECT_NEAR(M_PI / 2, paper.edges[4].fold_angle, 1e-12);
  EXPECT_EQ(Vec3(0, 0, 0), paper.vertices[0].folded);  // face 0 stays put
  EXPECT_GT(paper.vertices[2].folded.z(), 0.5);        // the valley turns face 1 up
  EXPECT_TRUE(checkValidity(paper).ok()) << checkValidity(paper).summary();
}

// FOLD's null is "no value" (Origami Simulator's own files hold it in edges_foldAngle for the
// boundary): read as absent, entry by entry, not refused.
TEST(FoldIo, ReadsNullAsNoValue)
{
  const FoldDocument document = parseOrFail(R"({
    "vertices_coords": [[0,0],[1,0],[1,1],[0,1]],
    "edges_vertices": [[0,1],[1,2],[2,3],[3,0],[1,3]],
    "edges_assignment": ["B",null,"B","B","V"],
    "edges_foldAngle": [null,null,null,null,90],
    "faces_vertices": [[0,1,3],[1,2,3]]})");
  const Paper& paper = document.frames[0];
  EXPECT_NEAR(M_PI / 2, paper.edges[4].fold_angle, 1e-12);  // the value given still folds
  ASSERT_TRUE(paper.edges[4].target_angle);
  EXPECT_NEAR(M_PI / 2, *paper.edges[4].target_angle, 1e-12);
  EXPECT_EQ(Assignment::Boundary, paper.edges[1].assignment);  // a boundary by its one face
  EXPECT_GT(paper.vertices[2].folded.z(), 0.5);

  // A crease whose angle is null has no target and lies as drawn.
  const FoldDocument unknown = parseOrFail(R"({
    "vertices_coords": [[0,0],[1,0],[1,1],[0,1]],
    "edges_vertices": [[0,1],[1,2],[2,3],[3,0],[1,3]],
    "edges_assignment": ["B","B","B","B","V"],
    "edges_foldAngle": [0,0,0,0,null],
    "faces_vertices": [[0,1,3],[1,2,3]]})");
  EXPECT_FALSE(unknown.frames[0].edges[4].target_angle);
  EXPECT_EQ(0.0, unknown.frames[0].edges[4].fold_angle);
  EXPECT_EQ(Assignment::Valley, unknown.frames[0].edges[4].assignment);
}

TEST(FoldIo, LoadsFlatWhenFoldAnglesDoNotClose)
{
  // Four creases at one vertex all at 90°: no rigid folding has these angles.
  const FoldDocument document = parseOrFail(R"({
    "vertices_coords": [[0,0],[1,0],[2,0],[2,1],[2,2],[1,2],[0,2],[0,1],[1,1]],
    "edges_vertices": [[0,1],[1,2],[2,3],[3,4],[4,5],[5,6],[6,7],[7,0],[8,1],[8,3],[8,5],[8,7]],
    "edges_foldAngle": [0,0,0,0,0,0,0,0,90,90,90,90],
    "faces_vertices": [[0,1,8,7],[1,2,3,8],[8,3,4,5],[7,8,5,6]]})");
  const Paper& paper = document.frames[0];
  for (const Vertex& v : paper.vertices)
    EXPECT_EQ(0.0, v.folded.z());
  for (const Edge& edge : paper.edges)
    EXPECT_EQ(0.0, edge.fold_angle);
  EXPECT_EQ(Assignment::Unassigned, paper.edges[8].assignment);
  EXPECT_EQ(Assignment::Boundary, paper.edges[0].assignment);
}

TEST(FoldIo, ResolvesFrameInheritance)
{
  // Frame 2 inherits from frame 1 (which comes later in the chain than its own parent, 0)
  // and overrides only the coordinates; frame 1 overrides an assignment.
  const FoldDocument document = parseOrFail(R"({
    "file_title": "chain", "frame_title": "key",
    "vertices_coords": [[0,0],[1,0],[1,1],[0,1]],
    "edges_vertices": [[0,1],[1,2],[2,3],[3,0],[1,3]],
    "edges_assignment": ["B","B","B","B","V"],
    "faces_vertices": [[0,1,3],[1,2,3]],
    "file_frames": [
      {"frame_inherit": true, "frame_parent": 0, "edges_assignment": ["B","B","B","B","M"]},
      {"frame_inherit": true, "frame_parent": 1, "frame_classes": ["foldedForm"],
       "vertices_coords": [[0,0,0],[1,0,0],[0.5,0.5,-0.7071067811865476],[0,1,0]]}]})");
  EXPECT_EQ("chain", document.title);
  ASSERT_EQ(3u, document.frames.size());
  EXPECT_EQ(Assignment::Valley, document.frames[0].edges[4].assignment);
  EXPECT_EQ(Assignment::Mountain, document.frames[1].edges[4].assignment);
  const Paper& folded = document.frames[2];
  EXPECT_EQ(Assignment::Mountain, folded.edges[4].assignment);
  EXPECT_EQ(Vec2(1, 1), folded.vertices[2].crease_pattern);  // from the parent crease pattern
  EXPECT_EQ(Vec3(0.5, 0.5, -0.7071067811865476), folded.vertices[2].folded);
  EXPECT_NEAR(-M_PI / 2, folded.edges[4].fold_angle, 1e-12);  // face 1 turned down by the mountain
}

TEST(FoldIo, ReadsACreasePatternGivenInATiltedPlane)
{
  // A 1 x √2 rectangle in the plane z = x: flat, so a crease pattern, laid into z = 0.
  const FoldDocument document = parseOrFail(R"({
    "frame_attributes": ["3D"],
    "vertices_coords": [[0,0,0],[1,0,1],[1,1,1],[0,1,0]],
    "faces_vertices": [[0,1,2,3]]})");
  const Paper& paper = document.frames[0];
  EXPECT_NEAR(std::sqrt(2.0), paper.sheet_area, 1e-12);
  expectEdgeLengthsKept(paper, 1e-12);
  EXPECT_NEAR(std::sqrt(2.0), (paper.vertices[1].folded - paper.vertices[0].folded).norm(), 1e-12);
  for (const Vertex& v : paper.vertices)
    EXPECT_EQ(0.0, v.folded.z());
  EXPECT_TRUE(checkValidity(paper).ok()) << checkValidity(paper).summary();
}

TEST(FoldIo, IgnoresUnknownAndCustomFields)
{
  const FoldDocument document = parseOrFail(R"({
    "file_spec": 1.2, "file_author": "someone", "tm:tree": {"nodes": []},
    "vertices_coords": [[0,0],[1,0],[0,1]],
    "vertices_edges": [[0,2],[0,1],[1,2]],
    "edges_vertices": [[0,1],[1,2],[2,0]],
    "edges_tm:structuralType": [1, 2, 3],
    "faces_vertices": [[0,1,2]]})");
  ASSERT_EQ(1u, document.frames.size());
  EXPECT_DOUBLE_EQ(0.5, document.frames[0].sheet_area);
}

TEST(FoldIo, DerivesEdgesAndAssignmentsFromFaces)
{
  const FoldDocument document = parseOrFail(R"({
    "vertices_coords": [[0,0],[1,0],[1,1],[0,1]],
    "faces_vertices": [[0,1,2],[0,2,3]]})");
  const Paper& paper = document.frames[0];
  EXPECT_EQ(5u, paper.edges.size());
  EXPECT_EQ(Assignment::Unassigned, paper.edges[edgeBetween(paper, 0, 2)].assignment);
  EXPECT_EQ(Assignment::Boundary, paper.edges[edgeBetween(paper, 0, 1)].assignment);
  EXPECT_TRUE(checkValidity(paper).ok()) << checkValidity(paper).summary();
}

TEST(FoldIo, RejectsBrokenFilesNamingTheField)
{
  const std::string square_edges = R"("edges_vertices": [[0,1],[1,2],[2,3],[3,0],[1,3]])";
  const std::string square_faces = R"("faces_vertices": [[0,1,3],[1,2,3]])";
  const std::string square_coords = R"("vertices_coords": [[0,0],[1,0],[1,1],[0,1]])";
  // Each case: the text, then what its message must contain.
  // clang-format off
  const std::vector<std::pair<std::string, std::string>> cases{
    { R"({"vertices_coords": [[0,0],)", "invalid JSON" },
    { R"({"vertices_coords": [[NaN,0]]})", "invalid JSON" },
    { R"([1, 2])", "JSON object" },
    { "{" + square_edges + "}", "vertices_coords is missing" },
    { R"({"vertices_coords": 5, "faces_vertices": []})", "vertices_coords is a number, not an array" },
    { "{" + square_coords + "," + square_edges + R"(, "edges_assignment": ["B","B","B","B"]})",
      "edges_assignment has 4 entries but edges_vertices has 5" },
    { "{" + square_coords + R"(, "edges_vertices": [[0,1],[1,2],[2,3],[3,9]]})",
      "edges_vertices[3] names vertex 9 but there are 4 vertices" },
    { "{" + square_coords + "," + square_edges + R"(, "edges_assignment": ["B","B","X","B","V"]})",
      "edges_assignment[2] is not one of the letters B M V F U C" },
    { R"({"vertices_coords": [[0,0],[null,0],[0,1]], "faces_vertices": [[0,1,2]]})",
      "vertices_coords[1][0] is null, not a number" },
    { R"({"vertices_coords": [[0,0],[1,"one"],[0,1]], "faces_vertices": [[0,1,2]]})",
      "vertices_coords[1][1] is a string, not a number" },
    { R"({"vertices_coords": [[0,0],[1,0,0,0],[0,1]], "faces_vertices": [[0,1,2]]})",
      "vertices_coords[1] has 4 coordinates" },
    { R"({"vertices_coords": [[0,0],[1,0],[0,1]], "faces_vertices": [[0,1]]})",
      "faces_vertices[0] has 2 vertices" },
    { R"({"vertices_coords": [[0,0],[3,0],[0,2],[1,2]], "faces_vertices": [[0,1,2,3]]})",
      "faces_vertices[0] crosses or touches itself in the crease pattern (its sides 1-2 and 3-0 meet)" },
    { R"({"vertices_coords": [[0,0],[2,0],[2,2],[1,0],[0,2]], "faces_vertices": [[0,1,2,3,4]]})",
      "faces_vertices[0] crosses or touches itself" },  // vertex 3 on side 0-1: a pinch
    { R"({"vertices_coords": [[1,0],[0.309,0.951],[-0.809,0.588],[-0.809,-0.588],[0.309,-0.951]],
         "faces_vertices": [[0,2,4,1,3]]})",
      "faces_vertices[0] winds around twice in the crease pattern" },
    { R"({"vertices_coords": [[0,0],[2,0],[1,0],[1,2]], "faces_vertices": [[0,1,2,3]]})",
      "faces_vertices[0] doubles back on itself in the crease pattern (at vertex 1)" },
    { R"({"vertices_coords": [[0,0],[1,0],[0,1],[5,5]], "faces_vertices": [[0,1,2]]})",
      "vertex 3 (vertices_coords[3]) is used by no face" },
    { R"({"vertices_coords": [[0,0],[1,0],[1,1],[0,1]], "faces_vertices": [[0,1,3],[1,3,2]]})",
      "has two faces on one side" },
    { R"({"vertices_coords": [[0,0],[1,0],[0,1],[2,0],[3,0],[2,1]], "faces_vertices": [[0,1,2],[3,5,4]]})",
      "faces_vertices[1] is clockwise but faces_vertices[0] is counter-clockwise" },
    { R"({"vertices_coords": [[0,0],[1,0]]})",
      "edges_vertices and faces_vertices are both missing" },
    { R"({"vertices_coords": [[0,0],[1,0],[2,1]], "edges_vertices": [[0,1],[1,2]]})",
      "edges_vertices: tracing the faces: the lines enclose no paper" },
    { "{" + square_coords + "," + square_edges + "," + square_faces + R"(, "edges_foldAngle": [0,0,0,0]})",
      "edges_foldAngle has 4 entries but edges_vertices has 5" },
    { "{" + square_coords + "," + square_faces + R"(, "faceOrders": [[0,7,1]]})",
      "faceOrders[0] names face 7 but there are 2 faces" },
    { R"({"frame_classes": ["foldedForm"], "vertices_coords": [[0,0,0],[1,0,0],[0,1,1]],
         "edges_vertices": [[0,1],[1,2],[2,0]]})",
      "a folded form needs faces_vertices" },
    { R"({"vertices_coords": [[0,0,1],[1,1,0],[1,-1,0],[-1,-1,0],[-1,1,0]],
         "faces_vertices": [[0,1,4],[0,4,3],[0,3,2],[0,2,1]]})",
      "folded form is not developable at vertex" },
    { "{" + square_coords + "," + square_faces + R"(, "file_frames": {}})",
      "file_frames is an object, not an array" },
    { "{" + square_coords + "," + square_faces + R"(, "file_frames": [{"frame_inherit": true, "frame_parent": 4}]})",
      "file_frames[0]: frame_parent is 4 but there are 2 frames" },
    { "{" + square_coords + "," + square_faces +
        R"(, "file_frames": [{"frame_inherit": true, "frame_parent": 2}, {"frame_inherit": true, "frame_parent": 1}]})",
      "frame_parent leads round in a loop" },
    { "{" + square_coords + "," + square_faces + R"(, "file_frames": [{"vertices_coords": [[0,0]]}]})",
      "file_frames[0]: edges_vertices and faces_vertices are both missing" },
  };
  // clang-format on
  for (const auto& [text, expected] : cases)
  {
    const Expected<FoldDocument> document = parseFold(text);
    EXPECT_FALSE(document.ok()) << text;
    EXPECT_THAT(document.message(), HasSubstr(expected)) << text;
  }
}

TEST(FoldIo, ReadingAMissingFileFails)
{
  const Expected<FoldDocument> document = readFoldFile("/nonexistent/folder/x.fold");
  ASSERT_FALSE(document.ok());
  EXPECT_THAT(document.message(), HasSubstr("cannot open /nonexistent/folder/x.fold"));
  EXPECT_THAT(document.message(), HasSubstr("No such file"));
  EXPECT_FALSE(loadPaper("/nonexistent/folder/x.fold").ok());
}

TEST(FoldIo, WritingToAMissingFolderFails)
{
  const std::filesystem::path folder = scratchFolder("missing");
  const std::string path = (folder / "no" / "such" / "folder" / "x.fold").string();
  const Status written = writeTextFile(path, formatFold(Paper::square()));
  ASSERT_FALSE(written.ok());
  EXPECT_THAT(written.message(), HasSubstr(path));
  EXPECT_THAT(written.message(), HasSubstr("No such file or directory"));
  std::filesystem::remove_all(folder);
}

TEST(FoldIo, WritingReplacesAnExistingFile)
{
  const std::filesystem::path folder = scratchFolder("replace");
  const std::string path = (folder / "x.fold").string();
  ASSERT_TRUE(writeTextFile(path, "old").ok());
  ASSERT_TRUE(writeTextFile(path, formatFold(Paper::square(3.0))).ok());
  const Expected<Paper> loaded = loadPaper(path);
  ASSERT_TRUE(loaded.ok()) << loaded.message();
  EXPECT_DOUBLE_EQ(9.0, loaded->sheet_area);
  std::filesystem::remove_all(folder);
}

// ---------------------------------------------------------------------------------------------
// Concave faces

/// An L-shaped face (area 3) with a square (area 1) on its right, and the L above the square.
const char* const kConcaveFile = R"({
  "vertices_coords": [[0,0],[2,0],[2,1],[1,1],[1,2],[0,2],[3,0],[3,1]],
  "edges_vertices": [[0,1],[1,6],[6,7],[7,2],[2,3],[3,4],[4,5],[5,0],[1,2]],
  "edges_assignment": ["B","B","B","B","B","B","B","B","V"],
  "faces_vertices": [[0,1,2,3,4,5],[1,6,7,2]],
  "faceOrders": [[0,1,1]]
})";

/// An arrow (chevron) pointing up, concave at (1, 0.5): area 1.5.
const char* const kArrowFile = R"({
  "vertices_coords": [[0,0],[1,0.5],[2,0],[1,2]],
  "faces_vertices": [[0,1,2,3]]
})";

/// The model of a one-frame file (empty, failing the test, when it does not load).
Paper onlyFrame(const std::string& text)
{
  const FoldDocument document = parseOrFail(text);
  EXPECT_EQ(1u, document.frames.size());
  return document.frames.empty() ? Paper{} : document.frames[0];
}

int splitEdgeCount(const Paper& paper)
{
  int count = 0;
  for (const Edge& edge : paper.edges)
    count += edge.split;
  return count;
}

void expectSplitIntoConvexPieces(const Paper& paper, double area, size_t file_faces)
{
  EXPECT_TRUE(checkValidity(paper).ok()) << checkValidity(paper).summary();  // convex, areas, Euler
  EXPECT_GT(paper.faces.size(), file_faces);
  EXPECT_EQ(static_cast<size_t>(splitEdgeCount(paper)), paper.faces.size() - file_faces);
  EXPECT_NEAR(area, paper.sheet_area, 1e-12);
  EXPECT_NEAR(area, totalFaceArea(paper), 1e-12);
  for (const Edge& edge : paper.edges)
    if (edge.split)
    {
      EXPECT_TRUE(edge.isCrease());
      EXPECT_EQ(Assignment::Flat, edge.assignment);
      EXPECT_EQ(0.0, edge.fold_angle);
    }
  expectFacesDoNotOverlap(paper, 1e-12);
}

TEST(FoldIo, SplitsAConcaveFaceIntoConvexPieces)
{
  const Paper paper = onlyFrame(kConcaveFile);
  expectSplitIntoConvexPieces(paper, 4.0, 2);
  EXPECT_EQ(3u, paper.faces.size());  // the L in two pieces: one edge from its inner corner
  // The file's faces keep their numbers; face 0 starts at the file's first vertex and side.
  EXPECT_EQ(0, paper.faces[0].vertices[0]);
  EXPECT_EQ(1, paper.faces[0].vertices[1]);
  EXPECT_EQ((std::vector<int>{ 1, 6, 7, 2 }), paper.faces[1].vertices);
  // The L lies above the square: both its pieces do.
  EXPECT_EQ((std::vector<FaceOrder>{ { 1, 0, 1 }, { 1, 2, 1 } }), paper.face_orders);

  const Paper arrow = onlyFrame(kArrowFile);
  expectSplitIntoConvexPieces(arrow, 1.5, 1);
  EXPECT_EQ(2u, arrow.faces.size());
}

TEST(FoldIo, WritesAConcaveFaceBackAsTheFileHadIt)
{
  const nlohmann::json file = nlohmann::json::parse(kConcaveFile);
  const Paper paper = onlyFrame(kConcaveFile);
  const std::string text = formatFold(paper);
  const nlohmann::json written = nlohmann::json::parse(text);
  EXPECT_EQ(file["faces_vertices"], written["faces_vertices"]);
  EXPECT_EQ(file["edges_vertices"], written["edges_vertices"]);
  EXPECT_EQ(file["edges_assignment"], written["edges_assignment"]);
  EXPECT_EQ(file["faceOrders"], written["faceOrders"]);
  EXPECT_EQ(file["vertices_coords"], written["vertices_coords"]);
  // And it reads back to the same model, pieces and all.
  const FoldDocument again = parseOrFail(text);
  ASSERT_EQ(2u, again.frames.size());
  expectSamePaper(paper, again.frames[0]);
  expectSamePaper(paper, again.frames[1]);

  const Paper arrow = onlyFrame(kArrowFile);
  const nlohmann::json arrow_written = nlohmann::json::parse(formatFold(arrow));
  EXPECT_EQ(nlohmann::json::parse(kArrowFile)["faces_vertices"], arrow_written["faces_vertices"]);
  EXPECT_EQ(4u, arrow_written["edges_vertices"].size());
  expectSamePaper(arrow, onlyFrame(formatFoldSequence({ arrow })));
}

TEST(FoldIo, AConcaveFaceCreasedSinceStillWritesAValidFold)
{
  Paper paper = onlyFrame(kConcaveFile);
  // Across the L's lower arm and the square, then up its left arm: both cut its pieces.
  for (const auto& [a, b] :
       { std::pair{ Vec3(-0.1, 0.5, 0), Vec3(3.1, 0.5, 0) }, std::pair{ Vec3(0.5, -0.1, 0), Vec3(0.5, 2.1, 0) } })
  {
    CreaseRequest request;
    request.start = a;
    request.end = b;
    const Expected<CreaseResult> creased = crease(paper, request);
    ASSERT_TRUE(creased.ok()) << creased.message();
  }
  ASSERT_TRUE(checkValidity(paper).ok()) << checkValidity(paper).summary();
  const nlohmann::json written = nlohmann::json::parse(formatFold(paper));
  // The pieces still joined by flat split edges are written as one face each, without them.
  size_t joined = 0;
  for (const Edge& edge : paper.edges)
    joined += edge.split;
  EXPECT_GT(joined, 0u);
  EXPECT_EQ(paper.edges.size() - joined, written["edges_vertices"].size());
  EXPECT_EQ(paper.faces.size() - joined, written["faces_vertices"].size());
  const FoldDocument again = parseOrFail(written.dump());
  ASSERT_EQ(2u, again.frames.size());
  for (const Paper& frame : again.frames)
  {
    EXPECT_TRUE(checkValidity(frame).ok()) << checkValidity(frame).summary();
    EXPECT_NEAR(4.0, frame.sheet_area, 1e-12);
    for (size_t v = 0; v < paper.vertices.size(); ++v)
      EXPECT_EQ(paper.vertices[v].crease_pattern, frame.vertices[v].crease_pattern);
  }
}

TEST(FoldIo, CreasingAlongASplitEdgeMakesItACrease)
{
  Paper paper = onlyFrame(kArrowFile);
  int split = -1;
  for (size_t e = 0; e < paper.edges.size(); ++e)
    if (paper.edges[e].split)
      split = static_cast<int>(e);
  ASSERT_GE(split, 0);
  const Edge edge = paper.edges[split];
  const Vec3 a = paper.vertices[edge.vertices[0]].folded, b = paper.vertices[edge.vertices[1]].folded;
  CreaseRequest request;
  request.start = a + 0.1 * (a - b);
  request.end = b + 0.1 * (b - a);
  const Expected<CreaseResult> creased = crease(paper, request);
  ASSERT_TRUE(creased.ok()) << creased.message();
  EXPECT_EQ(std::vector<int>{ split }, creased->new_edges);
  EXPECT_FALSE(paper.edges[split].split);
  EXPECT_EQ(Assignment::Unassigned, paper.edges[split].assignment);
  // Now a crease of the model: written as an edge between two faces.
  const nlohmann::json written = nlohmann::json::parse(formatFold(paper));
  EXPECT_EQ(2u, written["faces_vertices"].size());
  EXPECT_EQ(5u, written["edges_vertices"].size());
}

// ---------------------------------------------------------------------------------------------
// Messages never quote the file

TEST(FoldIo, NoMessageQuotesWhatTheFileHolds)
{
  // Each text holds the marker Qz7 where the reader trips over it: as a stray byte, in a
  // string where a number or array belongs, as a key, a number too large, bad UTF-8.
  const std::vector<std::string> texts{
    "Qz7",
    "{\"vertices_coords\": Qz7}",
    "[1, 2, Qz7",
    "{\"a\": 1}\nQz7",
    "\"Qz7\"",
    "[\"Qz7\"]",
    "{\"vertices_coords\": \"Qz7\", \"faces_vertices\": []}",
    "{\"vertices_coords\": [[0,0],[1,\"Qz7\"],[0,1]], \"faces_vertices\": [[0,1,2]]}",
    "{\"vertices_coords\": [[0,0],[1,0],[0,1]], \"edges_vertices\": [[0,1],[1,2],[2,0]],"
    " \"edges_assignment\": [\"B\",\"Qz7\",\"B\"]}",
    "{\"vertices_coords\": [[0,0],[1,0],[0,1]], \"faces_vertices\": [[0,1,2]], \"file_title\": [\"Qz7\"]}",
    "{\"vertices_coords\": [[0,0],[1,0],[0,1]], \"faces_vertices\": [[0,1,\"Qz7\"]]}",
    "{\"vertices_coords\": [[0,0],[1,0],[0,1]], \"faces_vertices\": [[0,1,2]], \"faceOrders\": [[0,0,\"Qz7\"]]}",
    "{\"vertices_coords\": [[0,0],[1,0],[0,1]], \"faces_vertices\": [[0,1,2]], \"file_frames\": [\"Qz7\"]}",
    "{\"vertices_coords\": [[0,0],[1,0],[0,1]], \"faces_vertices\": [[0,1,2]], \"file_frames\": [{\"frame_inherit\":"
    " \"Qz7\"}]}",
    "{\"vertices_coords\": [[0,0],[1,0],[0,1]], \"edges_vertices\": [[0,1],[1,2],[2,0]],"
    " \"edges_foldAngle\": [0, 1234567, 0]}",
    "{\"vertices_coords\": [[0,0],[1e999,0],[0,1]], \"faces_vertices\": [[0,1,2]]}",
    "{\"vertices_coords\": [[0,0],[1,0],[0,1]], \"faces_vertices\": [[0,1,2]], \"frame_title\": \"Qz7\xff\"}",
    "{\"Qz7\": [1, 2,, 3]}",
  };
  const std::filesystem::path folder = scratchFolder("quotes");
  for (const std::string& text : texts)
  {
    const Expected<FoldDocument> parsed = parseFold(text);
    ASSERT_FALSE(parsed.ok()) << text;
    const std::string path = (folder / "secret.fold").string();
    std::ofstream(path, std::ios::binary) << text;
    for (const std::string& message : { parsed.message(), readFoldFile(path).message(), loadPaper(path).message() })
    {
      EXPECT_FALSE(message.empty()) << text;
      EXPECT_THAT(message, ::testing::Not(HasSubstr("Qz7"))) << text;
      EXPECT_THAT(message, ::testing::Not(HasSubstr("last read"))) << text;
      EXPECT_THAT(message, ::testing::Not(HasSubstr("1234567"))) << text;
      EXPECT_THAT(message, ::testing::Not(HasSubstr("1e999"))) << text;
    }
  }
  // A syntax error says where instead.
  const std::string where = parseFold("{\"a\": 1,\n  \"b\": Qz7}").message();
  EXPECT_THAT(where, HasSubstr("invalid JSON: syntax error at line 2, column 8"));
  std::filesystem::remove_all(folder);
}

// ---------------------------------------------------------------------------------------------
// Writing files safely

std::string contentOf(const std::filesystem::path& path)
{
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

TEST(FoldIo, WritingNeverFollowsALinkPlantedAtTheTemporaryName)
{
  const std::filesystem::path folder = scratchFolder("planted");
  const std::filesystem::path victim = folder / "victim.txt", path = folder / "x.fold";
  std::ofstream(victim) << "keep me";
  std::filesystem::create_symlink(victim, folder / "x.fold.tmp");
  const Status written = writeTextFile(path.string(), "new");
  ASSERT_TRUE(written.ok()) << written.message();
  EXPECT_EQ("new", contentOf(path));
  EXPECT_EQ("keep me", contentOf(victim));
  EXPECT_TRUE(std::filesystem::is_symlink(folder / "x.fold.tmp"));
  // Nothing else is left in the folder.
  EXPECT_EQ(3, std::distance(std::filesystem::directory_iterator(folder), std::filesystem::directory_iterator()));
  std::filesystem::remove_all(folder);
}

TEST(FoldIo, WritingRefusesALinkAFolderOrAReadOnlyFile)
{
  const std::filesystem::path folder = scratchFolder("refused");
  const std::filesystem::path victim = folder / "victim.txt";
  std::ofstream(victim) << "keep me";
  const auto expectRefused = [&](const std::filesystem::path& path, const std::string& words) {
    const Status written = writeTextFile(path.string(), "new");
    EXPECT_FALSE(written.ok()) << path;
    EXPECT_THAT(written.message(), HasSubstr("cannot write " + path.string() + ": " + words));
    EXPECT_EQ("keep me", contentOf(victim));
  };
  // A link at the target: rename would replace the link, not the file it names.
  std::filesystem::create_symlink(victim, folder / "link.fold");
  expectRefused(folder / "link.fold", "it is a symbolic link");
  EXPECT_TRUE(std::filesystem::is_symlink(folder / "link.fold"));
  std::filesystem::create_directory(folder / "folder.fold");
  expectRefused(folder / "folder.fold", "not a regular file");
  ASSERT_EQ(0, ::mkfifo((folder / "fifo.fold").c_str(), 0600));
  expectRefused(folder / "fifo.fold", "not a regular file");
  // No write permission for anyone: refused even as root, whom access() lets write anything.
  ASSERT_EQ(0, ::chmod(victim.c_str(), 0444));
  expectRefused(victim, "the file is read-only");
  EXPECT_EQ(4, std::distance(std::filesystem::directory_iterator(folder), std::filesystem::directory_iterator()));
  std::filesystem::remove_all(folder);
}

TEST(FoldIo, WritingKeepsTheReplacedFilesPermissions)
{
  const std::filesystem::path folder = scratchFolder("mode");
  const std::filesystem::path path = folder / "x.fold";
  std::ofstream(path) << "old";
  ASSERT_EQ(0, ::chmod(path.c_str(), 0640));
  ASSERT_TRUE(writeTextFile(path.string(), "new").ok());
  EXPECT_EQ("new", contentOf(path));
  struct stat written;
  ASSERT_EQ(0, ::stat(path.c_str(), &written));
  EXPECT_EQ(0640u, written.st_mode & 07777);
  std::filesystem::remove_all(folder);
}

}  // namespace
}  // namespace virtual_origami::core

// A bend kept as the paper's state (kept_bend.h; issue 38 item 1): a sheet bent into flat strips
// turned by a fixed angle each, the closed form (every triangle the same shape as flat, every
// facet between strips at that angle), kept, undone, journaled, saved to FOLD and read back,
// and folded on beside it.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include <unistd.h>

#include "bent_strips.h"
#include "virtual_origami/core/compliant_faces.h"
#include "virtual_origami/core/fold_io.h"
#include "virtual_origami/core/kept_bend.h"
#include "virtual_origami/core/metrics.h"
#include "virtual_origami/core/obj_export.h"
#include "virtual_origami/core/session.h"
#include "virtual_origami/core/session_journal.h"
#include "virtual_origami/core/validity.h"
#include "virtual_origami/solvers/crease_driver_factory.h"
#include "virtual_origami/solvers/solver_factory.h"

using namespace virtual_origami::core;
using ::testing::HasSubstr;

namespace
{
constexpr int kCells = 8;           // the sheet's grid: kCells × kCells squares, two triangles each
constexpr double kStripTurn = 0.2;  // radians between neighbouring strips

BentSheet stripsBentFrom(double from_x)
{
  return test::stripsBentFrom(from_x, kCells, kStripTurn);
}

Vec3 p3(double x, double y)
{
  return Vec3(x, y, 0.0);
}

Session foldingSession(Paper paper = Paper::square(1.0))
{
  Session session(std::move(paper));
  session.setSolver(makeSolver("newton"));
  session.setCreaseDrivers(makeCreaseDriver());
  return session;
}

/// The unit square with a crease down its middle, flat.
Paper creasedDownTheMiddle()
{
  Session session;
  EXPECT_TRUE(session.crease({ p3(0.5, -0.1), p3(0.5, 1.1), std::nullopt, false }).ok());
  return session.paper();
}

int facetCount(const Paper& paper)
{
  int n = 0;
  for (const Edge& e : paper.edges)
    n += isFacet(e) ? 1 : 0;
  return n;
}
}  // namespace

TEST(KeptBend, ASheetBentIntoStripsIsKeptAsTheClosedFormSaysWithItsMesh)
{
  Paper paper = Paper::square(1.0);
  const BentSheet sheet = stripsBentFrom(0.0);
  const Expected<KeptBend> kept = keepBend(paper, sheet);
  ASSERT_TRUE(kept) << kept.message();
  EXPECT_EQ(kept->bent_faces, std::vector<int>{ 0 });
  EXPECT_EQ(kept->triangles, 2 * kCells * kCells);
  EXPECT_EQ(paper.faces.size(), static_cast<size_t>(2 * kCells * kCells));
  EXPECT_EQ(paper.vertices.size(), sheet.points.size());
  // Inner sides of the grid's triangles: every side less the boundary's.
  const int sides = 2 * kCells * (kCells + 1) + kCells * kCells;
  EXPECT_EQ(kept->facets, sides - 4 * kCells);
  EXPECT_EQ(facetCount(paper), kept->facets);
  EXPECT_TRUE(checkValidity(paper).ok()) << checkValidity(paper).summary();
  // Every node where the sheet put it; no side stretched.
  for (size_t v = 0; v < paper.vertices.size(); ++v)
  {
    const int k = static_cast<int>(std::lround(paper.vertices[v].crease_pattern.y() * kCells)) * (kCells + 1) +
                  static_cast<int>(std::lround(paper.vertices[v].crease_pattern.x() * kCells));
    EXPECT_EQ(paper.vertices[v].folded, sheet.positions[k]) << "vertex " << v;
  }
  EXPECT_LE(kept->max_strain, 1e-14);
  // The facets between strips at the strip turn (valley: the strips turn up), the rest flat;
  // each held at the angle it keeps.
  EXPECT_NEAR(kept->largest_bend, kStripTurn, 1e-12);
  int between_strips = 0;
  for (const Edge& e : paper.edges)
  {
    if (!isFacet(e))
      continue;
    EXPECT_EQ(*e.target_angle, e.fold_angle);
    EXPECT_EQ(e.assignment, Assignment::Flat) << "a facet is not a crease";
    const Vec2 a = paper.vertices[e.vertices[0]].crease_pattern, b = paper.vertices[e.vertices[1]].crease_pattern;
    const bool vertical = std::abs(a.x() - b.x()) < 1e-12;
    if (vertical)
    {
      ++between_strips;
      EXPECT_NEAR(e.fold_angle, kStripTurn, 1e-12);
    }
    else
      EXPECT_NEAR(e.fold_angle, 0.0, 1e-12);
  }
  EXPECT_EQ(between_strips, (kCells - 1) * kCells);
}

TEST(KeptBend, OnlyTheFaceThatBentIsMeshedAndTheCreaseBesideItIsSplitAtItsNodes)
{
  Paper paper = creasedDownTheMiddle();
  ASSERT_EQ(paper.faces.size(), 2u);
  const int left = paper.faceCentroid(0).x() < 0.5 ? 0 : 1;
  const Expected<KeptBend> kept = keepBend(paper, stripsBentFrom(0.5));
  ASSERT_TRUE(kept) << kept.message();
  ASSERT_EQ(kept->bent_faces.size(), 1u);
  EXPECT_NE(kept->bent_faces[0], left);
  EXPECT_EQ(kept->triangles, kCells * kCells);
  EXPECT_EQ(paper.faces.size(), static_cast<size_t>(1 + kCells * kCells));
  EXPECT_TRUE(checkValidity(paper).ok()) << checkValidity(paper).summary();
  // The flat half stays one face; its side on the crease holds the bent half's nodes.
  EXPECT_EQ(paper.faces[left].vertices.size(), static_cast<size_t>(4 + kCells - 1));
  for (int v : paper.faces[left].vertices)
    EXPECT_NEAR(paper.vertices[v].folded.z(), 0.0, 1e-15);
  // The crease, in pieces, folds by the first strip's turn, as the creased paper's crease
  // (no facet), its assignment as before.
  int pieces = 0;
  for (const Edge& e : paper.edges)
  {
    const Vec2 a = paper.vertices[e.vertices[0]].crease_pattern, b = paper.vertices[e.vertices[1]].crease_pattern;
    if (e.isCrease() && !isFacet(e) && std::abs(a.x() - 0.5) < 1e-12 && std::abs(b.x() - 0.5) < 1e-12)
    {
      ++pieces;
      EXPECT_NEAR(e.fold_angle, kStripTurn, 1e-12);
    }
  }
  EXPECT_EQ(pieces, kCells);
}

TEST(KeptBend, UndoReturnsTheFlatFacesExactlyAndRedoTheBend)
{
  Session session = foldingSession(creasedDownTheMiddle());
  const Paper flat = session.paper();
  const Expected<KeptBend> kept = session.keepBend(stripsBentFrom(0.5));
  ASSERT_TRUE(kept) << kept.message();
  const Paper bent = session.paper();
  const Operation kept_op = session.log().back();
  EXPECT_EQ(kept_op.kind, Operation::Kind::KeepBend);
  ASSERT_TRUE(session.undo().ok());
  EXPECT_TRUE(session.paper() == flat);
  ASSERT_TRUE(session.redo().ok());
  EXPECT_TRUE(session.paper() == bent);
  // Applying the logged operation again (a replay) lands on the same state, bit for bit.
  Session replay = foldingSession(creasedDownTheMiddle());
  const Status replayed = replay.apply(kept_op);
  ASSERT_TRUE(replayed.ok()) << replayed.message();
  EXPECT_TRUE(replay.paper() == bent);
}

TEST(KeptBend, AKeptBendSurvivesAJournalRoundTrip)
{
  const std::string path =
      (std::filesystem::temp_directory_path() / ("vo_kept_bend_" + std::to_string(::getpid()) + ".journal")).string();
  Session session = foldingSession(creasedDownTheMiddle());
  SessionJournal journal;
  ASSERT_TRUE(journal.start(path, session).ok());
  Session next = session;
  ASSERT_TRUE(next.keepBend(stripsBentFrom(0.5)));
  ASSERT_TRUE(journal.append(session, next.log().back(), &next.paper()).ok());
  session = std::move(next);
  next = session;
  ASSERT_TRUE(next.undo().ok());
  ASSERT_TRUE(journal.append(session, next.log().back(), nullptr).ok());
  session = std::move(next);
  next = session;
  ASSERT_TRUE(next.redo().ok());
  ASSERT_TRUE(journal.append(session, next.log().back(), nullptr).ok());
  session = std::move(next);

  const Expected<History> read = readJournal(path);
  std::filesystem::remove(path);
  ASSERT_TRUE(read) << read.message();
  EXPECT_TRUE(read->paper == session.paper());
  ASSERT_EQ(read->log.size(), session.log().size());
  const Operation& op = read->log[read->log.size() - 3];
  ASSERT_EQ(op.kind, Operation::Kind::KeepBend);
  EXPECT_EQ(op.bend.points, stripsBentFrom(0.5).points);
  EXPECT_EQ(op.bend.positions, stripsBentFrom(0.5).positions);
  EXPECT_EQ(op.bend.triangles, stripsBentFrom(0.5).triangles);
  // Undo after the restart returns the flat faces.
  Session restored(*read);
  ASSERT_TRUE(restored.undo().ok());
  EXPECT_TRUE(restored.paper() == creasedDownTheMiddle());
}

TEST(KeptBend, AKeptBendSavesToFoldWithItsMeshAndLoadsBackAsFacets)
{
  Paper paper = creasedDownTheMiddle();
  ASSERT_TRUE(keepBend(paper, stripsBentFrom(0.5)));
  const std::string text = formatFold(paper);
  EXPECT_THAT(text, HasSubstr("virtual_origami:edges_facet"));
  const Expected<FoldDocument> back = parseFold(text);
  ASSERT_TRUE(back) << back.message();
  const Paper& read = back->frames.back();  // the folded form: what other FOLD viewers show
  ASSERT_EQ(read.vertices.size(), paper.vertices.size());
  for (size_t v = 0; v < read.vertices.size(); ++v)
  {
    EXPECT_EQ(read.vertices[v].folded, paper.vertices[v].folded) << "vertex " << v;
    EXPECT_EQ(read.vertices[v].crease_pattern, paper.vertices[v].crease_pattern) << "vertex " << v;
  }
  // Every facet that holds the bend is in the file, a facet again, at the angle it keeps;
  // triangles joined by flat facets may be written as the one flat face they make.
  int bends = 0;
  for (size_t e = 0; e < paper.edges.size(); ++e)
  {
    const Edge& edge = paper.edges[e];
    if (!isFacet(edge) || std::abs(*edge.target_angle) < 1e-9)
      continue;
    ++bends;
    const int same = read.findEdge(edge.vertices[0], edge.vertices[1]);
    ASSERT_GE(same, 0) << "the bend's facet " << e << " is not in the file";
    EXPECT_TRUE(isFacet(read.edges[same]));
    EXPECT_NEAR(*read.edges[same].target_angle, *edge.target_angle, 1e-14);  // FOLD writes degrees
    EXPECT_NEAR(read.edges[same].fold_angle, edge.fold_angle, 1e-14);
  }
  EXPECT_EQ(bends, (kCells / 2 - 1) * kCells);
  // Every face of the file is flat: the bent surface is in its faces, not across one.
  for (size_t f = 0; f < read.faces.size(); ++f)
  {
    const Vec3 normal = read.faceNormal(static_cast<int>(f));
    const Vec3 origin = read.vertices[read.faces[f].vertices[0]].folded;
    for (int v : read.faces[f].vertices)
      EXPECT_NEAR(normal.dot(read.vertices[v].folded - origin), 0.0, 1e-12) << "face " << f;
  }
  EXPECT_TRUE(checkValidity(read).ok()) << checkValidity(read).summary();
  // OBJ: one triangle per face of the bent half, the flat half one polygon.
  const std::string obj = formatObj(paper);
  int faces = 0;
  for (size_t at = obj.find("\nf "); at != std::string::npos; at = obj.find("\nf ", at + 1))
    ++faces;
  EXPECT_EQ(faces, static_cast<int>(paper.faces.size()));
}

TEST(KeptBend, ATurnOfTheFlatHalfKeepsTheBendExactly)
{
  Session session = foldingSession(creasedDownTheMiddle());
  ASSERT_TRUE(session.keepBend(stripsBentFrom(0.5)));
  const Paper bent = session.paper();
  // The flat half turned a quarter about one piece of the crease: the crease's pieces are on
  // one line and part the sheet, so the half turns rigidly and the bent half stays.
  int axis = -1;
  for (size_t e = 0; e < bent.edges.size() && axis < 0; ++e)
    if (bent.edges[e].isCrease() && !isFacet(bent.edges[e]))
      axis = static_cast<int>(e);
  ASSERT_GE(axis, 0);
  RotateRequest turn;
  turn.click = p3(0.25, 0.5);
  turn.axis_edge = axis;
  turn.angle = -M_PI / 2;
  const Expected<RotateResult> turned = session.rotate(turn);
  ASSERT_TRUE(turned) << turned.message();
  const Paper& after = session.paper();
  ASSERT_EQ(after.edges.size(), bent.edges.size());
  for (size_t e = 0; e < after.edges.size(); ++e)
    if (isFacet(bent.edges[e]))
    {
      EXPECT_NEAR(after.edges[e].fold_angle, bent.edges[e].fold_angle, 1e-12) << "facet " << e;
      EXPECT_EQ(after.edges[e].assignment, Assignment::Flat) << "facet " << e;
    }
  EXPECT_LE(edgeStrain(after).max, 1e-12);
}

TEST(KeptBend, ACreaseAcrossTheBendIsRefusedAndBesideItIsMade)
{
  Session session = foldingSession(creasedDownTheMiddle());
  ASSERT_TRUE(session.keepBend(stripsBentFrom(0.5)));
  const Paper bent = session.paper();
  const uint64_t revision = session.revision();
  const Expected<CreaseResult> across = session.crease({ p3(-0.1, 0.3), p3(1.1, 0.3), std::nullopt, false });
  ASSERT_FALSE(across);
  EXPECT_THAT(across.message(), HasSubstr("kept bend"));
  EXPECT_TRUE(session.paper() == bent);
  EXPECT_EQ(session.revision(), revision);
  // The flat half takes a crease.
  EXPECT_TRUE(session.crease({ p3(0.25, -0.1), p3(0.25, 1.1), std::nullopt, false }));
}

TEST(KeptBend, ASheetThatDoesNotFitOrStretchesOrDidNotBendIsRefusedAndChangesNothing)
{
  const Paper creased = creasedDownTheMiddle();
  const auto refused = [&](const BentSheet& sheet, const std::string& says) {
    Paper paper = creased;
    const Expected<KeptBend> kept = keepBend(paper, sheet);
    EXPECT_FALSE(kept) << says;
    if (!kept)
    {
      EXPECT_THAT(kept.message(), HasSubstr(says));
    }
    EXPECT_TRUE(paper == creased) << says;
  };
  BentSheet nan = stripsBentFrom(0.5);
  nan.positions[10].y() = NAN;
  refused(nan, "not a finite point");
  BentSheet short_positions = stripsBentFrom(0.5);
  short_positions.positions.pop_back();
  refused(short_positions, "positions");
  BentSheet unknown = stripsBentFrom(0.5);
  unknown.triangles[3][1] = 1000;
  refused(unknown, "does not exist");
  BentSheet clockwise = stripsBentFrom(0.5);
  std::swap(clockwise.triangles[0][1], clockwise.triangles[0][2]);
  refused(clockwise, "counter-clockwise");
  BentSheet gap = stripsBentFrom(0.5);
  gap.triangles.pop_back();
  refused(gap, "cover");
  BentSheet off_paper = stripsBentFrom(0.5);
  for (Vec2& p : off_paper.points)
    p.x() += 0.01;
  refused(off_paper, "no point at vertex");
  BentSheet flat = stripsBentFrom(0.5);
  for (size_t k = 0; k < flat.points.size(); ++k)
    flat.positions[k] = Vec3(flat.points[k].x(), flat.points[k].y(), 0.0);
  refused(flat, "nothing bent");
  BentSheet stretched = stripsBentFrom(0.5);
  for (Vec3& p : stretched.positions)
    p *= 1.05;
  refused(stretched, "stretches");
  BentSheet empty;
  refused(empty, "empty");
  // Through a session: a pin the sheet moves refuses it too.
  Session session = foldingSession(creased);
  int corner = -1;
  for (size_t v = 0; v < creased.vertices.size(); ++v)
    if (creased.vertices[v].crease_pattern == Vec2(1.0, 1.0))
      corner = static_cast<int>(v);
  ASSERT_GE(corner, 0);
  session.setHeldVertices({ corner });
  const Expected<KeptBend> pinned = session.keepBend(stripsBentFrom(0.5));
  ASSERT_FALSE(pinned);
  EXPECT_THAT(pinned.message(), HasSubstr("pinned"));
  EXPECT_TRUE(session.paper() == creased);
}

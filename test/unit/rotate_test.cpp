#include <gtest/gtest.h>

#include <memory>

#include "test_models.h"
#include "virtual_origami/core/fold_io.h"
#include "virtual_origami/core/metrics.h"
#include "virtual_origami/core/reference_patterns.h"
#include "virtual_origami/core/face_orders.h"
#include "virtual_origami/core/rotate.h"
#include "virtual_origami/core/tessellations.h"
#include "virtual_origami/solvers/crease_driver_factory.h"
#include "virtual_origami/solvers/solver_factory.h"
#include "virtual_origami/solvers/newton_solver.h"

using namespace virtual_origami::core;
using namespace virtual_origami::core::test;

namespace
{
void expectRejected(Paper& paper, const RotateRequest& request, const std::string& words)
{
  const Paper before = paper;
  const Expected<RotateResult> result = rotate(paper, request);
  EXPECT_FALSE(result.ok());
  EXPECT_NE(result.message().find(words), std::string::npos) << result.message();
  EXPECT_TRUE(paper == before);
}

constexpr double kDeg = M_PI / 180;
/// A damping floor above the softest modes of a 400-vertex Miura-ori turned 10° from flat.
constexpr double kHeldDamping = 3e-7;

/// Turns `face` about `edge` by `angle` in `calls` equal rotate() calls, the solver moving
/// the faces the turn drags.
void turnInCalls(Paper& paper, int face, int edge, double angle, int calls)
{
  const std::unique_ptr<ShapeSolver> solver = makeSolver("newton");
  RotateRequest request;
  request.face = face;
  request.axis_edge = edge;
  request.angle = angle / calls;
  for (int call = 0; call < calls; ++call)
  {
    const Expected<RotateResult> r = rotate(paper, request, solver.get());
    ASSERT_TRUE(r.ok()) << r.message();
    EXPECT_TRUE(r->used_solver);
  }
}

double largestFoldAngleDifference(const Paper& a, const Paper& b)
{
  double largest = 0.0;
  for (size_t e = 0; e < a.edges.size(); ++e)
    largest = std::max(largest, std::abs(a.edges[e].fold_angle - b.edges[e].fold_angle));
  return largest;
}

int onlyCrease(const Paper& paper)
{
  for (size_t e = 0; e < paper.edges.size(); ++e)
    if (paper.edges[e].isCrease())
      return static_cast<int>(e);
  return -1;
}
}  // namespace

TEST(Rotate, TurnsTheFaceByTheAngle)
{
  for (double angle : { M_PI / 2, -M_PI / 3, M_PI })
  {
    Paper paper = Paper::square(1.0);
    creaseLine(paper, p3(0.5, -1), p3(0.5, 2));
    RotateRequest request;
    request.click = p3(0.8, 0.5);  // the right half; its only crease is the axis
    request.angle = angle;
    const Expected<RotateResult> r = rotate(paper, request);
    ASSERT_TRUE(r.ok()) << r.message();
    EXPECT_EQ(r->axis_edge, onlyCrease(paper));
    EXPECT_EQ(r->moved_faces.size(), 1u);
    EXPECT_NEAR(paper.edges[r->axis_edge].fold_angle, angle, 1e-12);
    // The far edge of the right half turned about x = 0.5 (valley lifts it towards +z).
    for (const Vertex& v : paper.vertices)
      if (v.crease_pattern.x() > 0.75)
      {
        EXPECT_NEAR(v.folded.x(), 0.5 + 0.5 * std::cos(angle), 1e-12);
        EXPECT_NEAR(v.folded.z(), 0.5 * std::sin(angle), 1e-12);
      }
      else
      {
        EXPECT_EQ(v.folded.z(), 0.0);  // the other half stays exactly
      }
    expectValid(paper);
  }
}

TEST(Rotate, FoldedFlatLayersCoincide)
{
  Paper paper = stackOfLayers(1);
  for (const Vertex& v : paper.vertices)
  {
    const Vec2& c = v.crease_pattern;
    const double x = c.x() <= 0.5 ? c.x() : 1.0 - c.x();
    EXPECT_LT((v.folded - p3(x, c.y())).norm(), 1e-15);
  }
  const int hinge = onlyCrease(paper);
  EXPECT_NEAR(paper.edges[hinge].fold_angle, M_PI, 1e-15);
  EXPECT_EQ(paper.edges[hinge].assignment, Assignment::Valley);
  expectValid(paper);
}

TEST(Rotate, AFlapCarriesEveryLayerConnectedToIt)
{
  // Folded in half: two layers over [0, 0.5] × [0, 1], joined along x = 0.5. Folding the top
  // half down carries both layers (joined by the first fold), and nothing else.
  Paper paper = stackOfLayers(1);
  const CreaseResult c = creaseLine(paper, p3(-0.1, 0.5), p3(0.6, 0.5));
  ASSERT_EQ(c.new_edges.size(), 2u);
  RotateRequest request;
  request.click = p3(0.3, 0.8);
  request.face = faceAt(paper, request.click, 1e-9);
  for (int e : c.new_edges)
    if (paper.edges[e].faces[0] == request.face || paper.edges[e].faces[1] == request.face)
      request.axis_edge = e;
  request.angle = M_PI;
  const Paper before = paper;
  const Expected<RotateResult> r = rotate(paper, request);
  ASSERT_TRUE(r.ok()) << r.message();
  EXPECT_EQ(r->moved_faces.size(), 2u);
  for (size_t f = 0; f < paper.faces.size(); ++f)
  {
    const bool moved = std::find(r->moved_faces.begin(), r->moved_faces.end(), f) != r->moved_faces.end();
    const Vec3 was = before.faceCentroid(static_cast<int>(f));
    const Vec3 now = paper.faceCentroid(static_cast<int>(f));
    EXPECT_EQ(moved, was.y() > 0.5) << "face " << f;
    if (moved)
      EXPECT_NEAR(now.y(), 1.0 - was.y(), 1e-12);  // mirrored over y = 0.5
    else
      EXPECT_TRUE(now == was);
  }
  for (int e : c.new_edges)
    EXPECT_NEAR(std::abs(paper.edges[e].fold_angle), M_PI, 1e-12);
  expectValid(paper);
}

TEST(Rotate, LockedFacesNeedASolver)
{
  // A crease across the sheet and one from its midpoint to a corner: turning the lower right
  // face about the diagonal drags the left half, which holds the upper right face too.
  Paper paper = Paper::square(1.0);
  creaseLine(paper, p3(0.5, -1), p3(0.5, 2));
  const CreaseResult diagonal = creaseLine(paper, p3(0.5, 0.5), p3(1, 1));
  ASSERT_EQ(diagonal.new_edges.size(), 1u);
  RotateRequest request;
  request.face = faceAt(paper, p3(0.9, 0.3), 1e-9);
  request.axis_edge = diagonal.new_edges[0];
  request.angle = 0.3;
  EXPECT_TRUE(flapOf(paper, request.face, request.axis_edge).empty());
  expectRejected(paper, request, "solver");
}

TEST(Rotate, PastHalfATurnIsRejected)
{
  Paper paper = stackOfLayers(1);
  RotateRequest request;
  request.face = faceAt(paper, p3(0.25, 0.5, 0.0), 1e-9);
  request.axis_edge = onlyCrease(paper);
  request.angle = 0.1;  // already at 180°
  expectRejected(paper, request, "past 180");
  request.angle = -M_PI;  // unfolding is fine
  EXPECT_TRUE(rotate(paper, request).ok());
  EXPECT_NEAR(paper.edges[request.axis_edge].fold_angle, 0.0, 1e-12);
  expectValid(paper);
}

TEST(Rotate, BadInputChangesNothing)
{
  Paper paper = Paper::square(1.0);
  creaseLine(paper, p3(0.5, -1), p3(0.5, 2));
  RotateRequest request;
  request.click = p3(0.8, 0.5);
  request.angle = NAN;
  expectRejected(paper, request, "not finite");
  request.angle = 1e300;  // finite, but the staged solve would never end
  expectRejected(paper, request, "more than a whole turn");
  request.angle = -2 * M_PI - 1e-6;
  expectRejected(paper, request, "more than a whole turn");
  request.angle = 1.0;
  request.face = 7;
  expectRejected(paper, request, "face 7 does not exist");
  request.face = -1;
  request.axis_edge = 99;
  expectRejected(paper, request, "edge 99 does not exist");
  request.axis_edge = 0;  // a boundary edge
  expectRejected(paper, request, "boundary");
  request.axis_edge = -1;
  request.click = p3(3, 3);
  expectRejected(paper, request, "no face");
  request.click = p3(0.8, INFINITY);
  expectRejected(paper, request, "non-finite");
  Paper flat = Paper::square(1.0);
  request.click = p3(0.5, 0.5);
  expectRejected(flat, request, "no crease");
}

TEST(Rotate, OneLargeTurnFollowsTheMiuraOriLikeSmallTurns)
{
  // Miura-ori 6 × 5 (γ = 70°) started 0.02 rad along its rigid folding; face 0 turns about its
  // zigzag crease to face 1 (held) by 175°, folding it further (valley, then mirrored
  // mountain). Turned at once, the solver used to land on another branch, creases at ±180°
  // off the closed form by 2π, where 30° steps stay on it.
  constexpr int kColumns = 6, kRows = 5;
  constexpr double kGamma = 70 * kDeg;
  for (double sign : { 1.0, -1.0 })
  {
    Paper start = miuraOri(kColumns, kRows, 1.0, 1.3, kGamma);
    ASSERT_TRUE(foldToAngles(start, miuraFoldAngles(start, kColumns, kRows, kGamma, sign * 0.02)).ok());
    const int zigzag = start.findEdge(1, kColumns + 2);  // vertex (1, 0) to (1, 1)
    const double turn = sign * 175 * kDeg;
    Paper once = start, stepped = start;
    turnInCalls(once, 0, zigzag, turn, 1);
    turnInCalls(stepped, 0, zigzag, turn, 6);  // 29.2° each
    const double zigzag_angle = once.edges[zigzag].fold_angle;
    EXPECT_NEAR(zigzag_angle, start.edges[zigzag].fold_angle + turn, 1e-12);
    // Zigzag crease (1, 0)→(1, 1) folds to 2·atan(tan(ρ/2)/cos γ) (reference_patterns.h).
    const double rho = 2 * std::atan(std::tan(zigzag_angle / 2) * std::cos(kGamma));
    const std::vector<double> closed_form = miuraFoldAngles(once, kColumns, kRows, kGamma, rho);
    for (size_t e = 0; e < once.edges.size(); ++e)
      EXPECT_NEAR(once.edges[e].fold_angle, closed_form[e], 1e-6) << "edge " << e << ", sign " << sign;
    EXPECT_LT(largestFoldAngleDifference(once, stepped), 1e-6);
    EXPECT_LT(edgeStrain(once).max, 1e-9);
    expectValid(once);
  }
}

TEST(Rotate, OneLargeTurnFollowsADegree4VertexLikeSmallTurns)
{
  // Sectors 60°, 80°, 120°, 100°, started 10° into mode 1 (ρ3 = ρ1, ρ4 = −ρ2); face 3 turns
  // about crease 1 to face 0 (held) by 185°, through the flat state to −175° (and mirrored).
  // Turned at once, the solver used to leave mode 1 for a shape off it by 2π.
  constexpr double kAlpha = 60 * kDeg, kBeta = 80 * kDeg;
  for (double sign : { 1.0, -1.0 })
  {
    Paper start = degree4Vertex({ kAlpha, kBeta, M_PI - kAlpha, M_PI - kBeta });
    std::array<int, 4> creases{};
    for (int k = 0; k < 4; ++k)
      creases[k] = start.findEdge(0, k + 1);
    const std::array<double, 4> begin = degree4FoldAngles(kAlpha, kBeta, sign * 10 * kDeg, 1);
    std::vector<double> angles(start.edges.size(), 0.0);
    for (int k = 0; k < 4; ++k)
      angles[creases[k]] = begin[k];
    ASSERT_TRUE(foldToAngles(start, angles).ok());
    const double turn = -sign * 185 * kDeg;
    Paper once = start, stepped = start;
    turnInCalls(once, 3, creases[0], turn, 1);
    turnInCalls(stepped, 3, creases[0], turn, 6);  // 30.8° each
    EXPECT_NEAR(once.edges[creases[0]].fold_angle, -sign * 175 * kDeg, 1e-12);
    const std::array<double, 4> closed_form = degree4FoldAngles(kAlpha, kBeta, -sign * 175 * kDeg, 1);
    for (int k = 0; k < 4; ++k)
      EXPECT_NEAR(once.edges[creases[k]].fold_angle, closed_form[k], 1e-6) << "crease " << k + 1 << ", sign " << sign;
    EXPECT_LT(largestFoldAngleDifference(once, stepped), 1e-6);
    EXPECT_LT(edgeStrain(once).max, 1e-9);
    expectValid(once);
  }
}

TEST(Rotate, TurningAboutAnEdgeThatSplitAConcaveFaceMakesItACrease)
{
  // An arrow-shaped face, concave at (1, 0.5): read as two convex pieces joined by a flat edge
  // added only to split it (Edge::split), which a FOLD written from it leaves out. Turned
  // about, that edge is a crease like any other.
  const Expected<FoldDocument> arrow =
      parseFold(R"({"vertices_coords": [[0,0],[1,0.5],[2,0],[1,2]], "faces_vertices": [[0,1,2,3]]})");
  ASSERT_TRUE(arrow.ok()) << arrow.message();
  Paper paper = arrow->frames[0];
  ASSERT_EQ(2u, paper.faces.size());
  const int split = paper.findEdge(1, 3);  // from the inner corner to the tip
  ASSERT_GE(split, 0);
  ASSERT_TRUE(paper.edges[split].split);
  RotateRequest request;
  request.face = 0;
  request.axis_edge = split;
  request.angle = M_PI / 2;
  const Expected<RotateResult> r = rotate(paper, request);
  ASSERT_TRUE(r.ok()) << r.message();
  EXPECT_FALSE(paper.edges[split].split);
  EXPECT_EQ(Assignment::Valley, paper.edges[split].assignment);
  expectValid(paper);
  const Expected<FoldDocument> written = parseFold(formatFold(paper));
  ASSERT_TRUE(written.ok()) << written.message();
  EXPECT_EQ(2u, written->frames[1].faces.size());
  EXPECT_NEAR(M_PI / 2, written->frames[1].edges[written->frames[1].findEdge(1, 3)].fold_angle, 1e-9);
}

TEST(Rotate, ATurnByNothingKeepsTheLayerOrder)
{
  // The quarter fold: four layers. A turn by 0 (a drag back to where it was pressed) must leave
  // every face where it is and the layers in their order; they were dropped, and the preview
  // drew four layers at two heights.
  const Paper quarter = stackOfLayers(2);
  ASSERT_FALSE(quarter.face_orders.empty());
  for (size_t f = 0; f < quarter.faces.size(); ++f)
  {
    Paper turned = quarter;
    RotateRequest request;
    request.face = static_cast<int>(f);
    request.click = quarter.faceCentroid(static_cast<int>(f));
    request.angle = 0.0;
    const Expected<RotateResult> result = rotate(turned, request);
    if (!result)
      continue;  // a face without a crease to turn about
    for (const FaceOrder& order : quarter.face_orders)
      EXPECT_EQ(faceOrder(turned, order.face, order.other), order.above) << "face " << f;
    EXPECT_EQ(turned.face_orders.size(), quarter.face_orders.size()) << "face " << f;
  }
}

namespace virtual_origami::core
{
namespace
{
/// A turn of `sheet`'s corner face (face 0) by `angle` about its slanted crease (axis_edge −1
/// where the face has none).
RotateRequest cornerTurn(const Paper& sheet, double angle)
{
  RotateRequest request;
  request.face = 0;
  request.axis_edge = test::slantedCreaseOf(sheet, 0);
  request.angle = angle;
  return request;
}

/// The corner face of a Miura-ori turned about its slanted crease (one degree of freedom), a
/// quasi-Newton crease driver as the guide whatever the size.
class MiuraCornerTurn : public ::testing::Test
{
protected:
  explicit MiuraCornerTurn(Paper paper) : start(std::move(paper)), axis(test::slantedCreaseOf(start, 0)) {}

  void SetUp() override
  {
    ASSERT_GE(axis, 0);
    guide.driver = driver.get();
    guide.min_vertices = 0;
    request = cornerTurn(start, 0.0);
  }

  const Paper start;
  const int axis;
  NewtonSolver solver;
  const std::unique_ptr<CreaseDriver> driver = makeCreaseDriver("quasi_newton");
  TurnGuide guide;
  RotateRequest request;
};

/// An 8 × 8 Miura-ori's.
class GuidedMiuraTurn : public MiuraCornerTurn
{
protected:
  GuidedMiuraTurn() : MiuraCornerTurn(miuraTessellation(8, 8).value().paper) {}
};

/// A 1,100-vertex Miura-ori's, near its flat sheet's singular balance.
class NearFlatMiuraTurn : public MiuraCornerTurn
{
protected:
  NearFlatMiuraTurn() : MiuraCornerTurn(tessellationWithVertices(TessellationKind::Miura, 1100).value().paper) {}
};

/// A crease driver's start changes how fast a turn is followed, not where it ends: on a
/// Miura-ori (one degree of freedom) three guided 10° turns end where the solver alone ends,
/// with the faces as exact.
TEST_F(GuidedMiuraTurn, AGuidedTurnEndsWhereTheSolverAloneEnds)
{
  Paper alone = start, guided = start;
  request.angle = 10 * M_PI / 180;
  for (int k = 0; k < 3; ++k)
  {
    const Expected<RotateResult> a = rotate(alone, request, &solver);
    const Expected<RotateResult> g = rotate(guided, request, &solver, {}, guide);
    ASSERT_TRUE(a) << a.message();
    ASSERT_TRUE(g) << g.message();
    EXPECT_LE(g->solve.max_strain, 1e-9);
    EXPECT_LE(g->solve.iterations, a->solve.iterations);
  }
  for (size_t v = 0; v < start.vertices.size(); ++v)
    EXPECT_LE((guided.vertices[v].folded - alone.vertices[v].folded).norm(), 1e-8) << "vertex " << v;
  for (size_t e = 0; e < start.edges.size(); ++e)
    EXPECT_NEAR(guided.edges[e].fold_angle, alone.edges[e].fold_angle, 1e-8) << "edge " << e;
  EXPECT_NEAR(guided.edges[axis].fold_angle, 30 * M_PI / 180, 1e-9);
}

/// A guide its step bound stops short of balance (here after 5 steps) is still the solver's start
/// (TurnGuide::max_iterations): the solver needs fewer iterations from it, and the turn ends where
/// the solver alone ends, as exact.
TEST_F(GuidedMiuraTurn, AGuideStoppedShortOfBalanceStillEndsWhereTheSolverAloneEnds)
{
  guide.max_iterations = 5;
  request.angle = 10 * kDeg;
  Paper alone = start, guided = start;
  const Expected<RotateResult> a = rotate(alone, request, &solver);
  const Expected<RotateResult> g = rotate(guided, request, &solver, {}, guide);
  ASSERT_TRUE(a) << a.message();
  ASSERT_TRUE(g) << g.message();
  EXPECT_LT(g->solve.iterations, a->solve.iterations);  // measured 2 against 9
  EXPECT_LE(g->solve.max_strain, solver.limits().tolerance);
  EXPECT_LT(edgeStrain(guided).max, 1e-9);
  for (size_t v = 0; v < start.vertices.size(); ++v)
    EXPECT_LE((guided.vertices[v].folded - alone.vertices[v].folded).norm(), 1e-8) << "vertex " << v;
  EXPECT_LT(largestFoldAngleDifference(guided, alone), 1e-8);
  EXPECT_NEAR(guided.edges[axis].fold_angle, start.edges[axis].fold_angle + 10 * kDeg, 1e-12);
}

/// A drag's preview goes on from its last one (TurnStart) and ends where the same turn from the
/// paper ends (a Miura-ori has one degree of freedom), the faces as exact; a start another turn
/// made, or one on the other side of the paper, is not taken.
TEST_F(GuidedMiuraTurn, APreviewGoingOnFromTheLastEndsWhereTheTurnFromThePaperEnds)
{
  // Balanced to 1e-12: near the flat sheet a strain of 1e-10 leaves the vertices free along the
  // soft mode by some 1e-8, by where the solve started (measured 1.7e-8 between the two starts).
  solver.setLimits(SolveLimits{ 1e-12, 1000, 0.0 });
  request.angle = 6 * kDeg;
  Paper last = start;
  ASSERT_TRUE(rotate(last, request, &solver, {}, guide).ok());
  request.angle = 8 * kDeg;
  Paper fresh = start, went_on = start;
  const Expected<RotateResult> f = rotate(fresh, request, &solver, {}, guide);
  const Expected<RotateResult> w = rotate(went_on, request, &solver, {}, guide, TurnStart{ &last, 6 * kDeg, 0, axis });
  ASSERT_TRUE(f) << f.message();
  ASSERT_TRUE(w) << w.message();
  EXPECT_LE(w->solve.max_strain, 1e-9);
  EXPECT_LT(edgeStrain(went_on).max, 1e-9);
  EXPECT_NEAR(went_on.edges[axis].fold_angle, start.edges[axis].fold_angle + 8 * kDeg, 1e-12);
  for (size_t v = 0; v < start.vertices.size(); ++v)
    EXPECT_LE((went_on.vertices[v].folded - fresh.vertices[v].folded).norm(), 1e-8) << "vertex " << v;
  EXPECT_LT(largestFoldAngleDifference(went_on, fresh), 1e-8);
  expectValid(went_on);

  // Not taken (the solver alone, which ends the same way from the same start): made by another
  // face's turn, or on the other side of the paper.
  Paper alone = start;
  ASSERT_TRUE(rotate(alone, request, &solver).ok());
  Paper other_face = start;
  ASSERT_TRUE(rotate(other_face, request, &solver, {}, {}, TurnStart{ &last, 6 * kDeg, 1, axis }).ok());
  EXPECT_TRUE(other_face == alone);
  Paper other_side = start, alone_back = start;
  request.angle = -8 * kDeg;
  ASSERT_TRUE(rotate(alone_back, request, &solver).ok());
  ASSERT_TRUE(rotate(other_side, request, &solver, {}, {}, TurnStart{ &last, 6 * kDeg, 0, axis }).ok());
  EXPECT_TRUE(other_side == alone_back);
}

/// A drag's preview starts where the parabola through the model (no turn) and the drag's previews
/// before it leads (TurnStart::before): near the flat sheet a Miura-ori's vertices move by the
/// square of the turn, so from there two of Newton's steps reach 1e-8, where from the last preview
/// alone they do not (1,100 vertices; from the line through the model and the last preview:
/// strain 1e-3 at the start against 2e-6, and 1e-7 after the two steps).
/// It ends on the branch the turn from the paper ends on.
TEST_F(NearFlatMiuraTurn, APreviewStartsWhereTheDragsPreviewsBeforeItLead)
{
  Paper at2 = start, at4 = start;
  request.angle = 2 * kDeg;
  ASSERT_TRUE(rotate(at2, request, &solver, {}, guide).ok());
  request.angle = 4 * kDeg;
  ASSERT_TRUE(rotate(at4, request, &solver, {}, guide).ok());
  NewtonSolver two_steps;
  two_steps.setLimits(SolveLimits{ 1e-8, 2, 0.0 });
  request.angle = 6 * kDeg;
  TurnStart going_on{ &at4, 4 * kDeg, 0, axis };
  Paper on_the_line = start;
  EXPECT_FALSE(rotate(on_the_line, request, &two_steps, {}, {}, going_on).ok());
  EXPECT_TRUE(on_the_line == start);  // refused: untouched
  going_on.before = { { &at2, 2 * kDeg } };
  Paper predicted = start;
  const Expected<RotateResult> p = rotate(predicted, request, &two_steps, {}, {}, going_on);
  ASSERT_TRUE(p) << p.message();
  EXPECT_LE(p->solve.iterations, 2);
  Paper fresh = start;
  ASSERT_TRUE(rotate(fresh, request, &solver, {}, guide).ok());
  // On the same branch: balanced to 1e-8 near the flat sheet, whose flexes strain the faces by
  // the square of their motion, the creases are free by some 1e-5 rad (another branch is 0.1 off).
  EXPECT_LT(largestFoldAngleDifference(predicted, fresh), 1e-4);
  EXPECT_NEAR(predicted.edges[axis].fold_angle, start.edges[axis].fold_angle + 6 * kDeg, 1e-12);
  EXPECT_LT(edgeStrain(predicted).max, 1e-8);
}

/// A Newton solve that creeps towards its tolerance stops once the pace of its last steps shows
/// it cannot get there within its iteration limit, and the turn is refused with the paper
/// untouched. Made to creep by holding its damping floor above the soft modes of a Miura-ori near
/// the flat sheet (lowest_damping = min_damping: the floor is never lowered); the default solver,
/// which lowers its floor while whole steps creep, gets there.
TEST(Rotate, ANewtonSolveTooSlowForItsToleranceStopsAndIsRefused)
{
  const Paper start = tessellationWithVertices(TessellationKind::Miura, 400).value().paper;
  const RotateRequest request = cornerTurn(start, 10 * kDeg);
  ASSERT_GE(request.axis_edge, 0);
  NewtonOptions held_damping;
  held_damping.min_damping = kHeldDamping;
  held_damping.lowest_damping = kHeldDamping;
  NewtonSolver creeping(held_damping);
  Paper refused = start;
  const Expected<RotateResult> r = rotate(refused, request, &creeping);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.message().find("too slow to converge"), std::string::npos) << r.message();
  EXPECT_TRUE(refused == start);

  NewtonSolver solver;
  Paper turned = start;
  const Expected<RotateResult> t = rotate(turned, request, &solver);
  ASSERT_TRUE(t) << t.message();
  EXPECT_LE(t->solve.max_strain, solver.limits().tolerance);
  EXPECT_LE(edgeStrain(turned).max, solver.limits().tolerance);
}

/// Turned the other way, a flat sheet moves as its mirror image across its plane (the premise
/// of the second preview's start): the Miura-ori's corner face turned by −2° and by +2° from the
/// flat sheet, every vertex of the one the other's reflected, to the solver's tolerance.
/// So a drag's second preview from the flat sheet starts where its first one, scaled by the turn
/// across the plane and by its square along it, leads: from there one of Newton's steps reaches
/// 1e-8 at 1,100 vertices, on the branch the turn from the flat sheet ends on; from a folded
/// model (no mirror image) the same step is refused.
TEST_F(NearFlatMiuraTurn, ADragsSecondPreviewFromTheFlatSheetStartsOnItsMirrorImage)
{
  const Vec3 normal = start.faceNormal(0);
  const Vec3 origin = start.vertices[0].folded;
  Paper up = start, down = start;
  request.angle = 2 * kDeg;
  ASSERT_TRUE(rotate(up, request, &solver, {}, guide).ok());
  request.angle = -2 * kDeg;
  ASSERT_TRUE(rotate(down, request, &solver, {}, guide).ok());
  double apart = 0.0;
  for (size_t v = 0; v < start.vertices.size(); ++v)
  {
    const Vec3 p = up.vertices[v].folded;
    const Vec3 mirrored = p - 2 * (p - origin).dot(normal) * normal;
    apart = std::max(apart, (mirrored - down.vertices[v].folded).norm());
  }
  EXPECT_LE(apart, 1e-9 * start.scale());

  NewtonSolver one_step;
  one_step.setLimits(SolveLimits{ 1e-8, 1, 0.0 });
  request.angle = 4 * kDeg;
  Paper predicted = start;
  const Expected<RotateResult> p = rotate(predicted, request, &one_step, {}, {}, TurnStart{ &up, 2 * kDeg, 0, axis });
  ASSERT_TRUE(p) << p.message();
  EXPECT_LE(edgeStrain(predicted).max, 1e-8);
  // The branch the turn from the flat sheet ends on (the other one has every crease mirrored,
  // 0.1 rad away); the two balances differ along the near-flat sheet's soft modes.
  Paper turned = start;
  ASSERT_TRUE(rotate(turned, request, &solver, {}, guide).ok());
  EXPECT_LT(largestFoldAngleDifference(predicted, turned), 1e-4);

  // Folded, the model has no mirror image to start on: the same step from there is refused.
  Paper folded = start;
  request.angle = 20 * kDeg;
  ASSERT_TRUE(rotate(folded, request, &solver, {}, guide).ok());
  Paper folded_up = folded;
  request.angle = 2 * kDeg;
  ASSERT_TRUE(rotate(folded_up, request, &solver).ok());
  request.angle = 4 * kDeg;
  Paper unpredicted = folded;
  EXPECT_FALSE(rotate(unpredicted, request, &one_step, {}, {}, TurnStart{ &folded_up, 2 * kDeg, 0, axis }).ok());
}

/// A drag's frame near the flat sheet creeps: Gauss–Newton's whole steps along the soft modes
/// fall short by a near-constant factor. A frame tries such a step longer while the energy falls
/// (NewtonOptions::extend_creeping_frames): the Miura-ori's corner turned 0.5° off the flat sheet
/// at 4,000 vertices, guided, as a preview balanced to 1e-12 (where the creep shows at this size),
/// in 11 steps instead of 31, to the same balance and branch.
TEST(Rotate, ACreepingFrameTriesItsStepLonger)
{
  const Paper start = tessellationWithVertices(TessellationKind::Miura, 4000).value().paper;
  const RotateRequest request = cornerTurn(start, 0.5 * kDeg);
  ASSERT_GE(request.axis_edge, 0);
  constexpr double kBalance = 1e-12;
  Paper turned[2] = { start, start };
  int steps[2] = { 0, 0 };
  for (int extended : { 0, 1 })
  {
    NewtonOptions options;
    options.extend_creeping_frames = extended;
    NewtonSolver solver(options);
    solver.setLimits(SolveLimits{ kBalance, 1000, 0.0 });
    const std::unique_ptr<CreaseDriver> driver = makeCreaseDriver("quasi_newton");  // its own: it keeps frames
    TurnGuide guide;
    guide.driver = driver.get();
    const Expected<RotateResult> preview = rotate(turned[extended], request, &solver, {}, guide, {}, kBalance);
    ASSERT_TRUE(preview) << preview.message();
    EXPECT_LE(edgeStrain(turned[extended]).max, kBalance);
    steps[extended] = preview->solve.iterations;
  }
  EXPECT_LT(steps[1], steps[0] / 2) << steps[1] << " steps against " << steps[0];
  EXPECT_LT(largestFoldAngleDifference(turned[0], turned[1]), 1e-4);
}

/// Each face's rest shape and fit are taken in differences of its own vertices' coordinates,
/// which are exact: a sheet far from the origin is solved as exactly as one at it. (Through the
/// face's mean of absolute coordinates every rest shape was rounded to their ulp, 1.8e-12 at
/// 10⁴, which the near-singular balance of a Miura-ori near the flat sheet amplified into a
/// strain no solver could close.) The same turn, the sheet moved by 10⁴, ends at the same rigid
/// state moved, to 10⁻¹² of strain.
TEST(Rotate, ATurnFarFromTheOriginIsAsExactAsAtIt)
{
  const Paper start = tessellationWithVertices(TessellationKind::Miura, 400).value().paper;
  const RotateRequest request = cornerTurn(start, 10 * kDeg);
  ASSERT_GE(request.axis_edge, 0);
  const Vec3 shift(1e3, -1e3, 0.0);
  Paper far = start;
  for (Vertex& v : far.vertices)
  {
    v.crease_pattern += shift.head<2>();
    v.folded += shift;
  }
  const std::unique_ptr<ShapeSolver> solver = makeSolver("newton");
  SolveLimits limits = solver->limits();
  limits.tolerance = 1e-12;
  solver->setLimits(limits);
  Paper near = start;
  const Expected<RotateResult> n = rotate(near, request, solver.get());
  const Expected<RotateResult> f = rotate(far, request, solver.get());
  ASSERT_TRUE(n) << n.message();
  ASSERT_TRUE(f) << f.message();
  EXPECT_LE(edgeStrain(far).max, 1e-12);
  for (size_t v = 0; v < start.vertices.size(); ++v)
    EXPECT_LE((far.vertices[v].folded - shift - near.vertices[v].folded).norm(), 1e-9) << "vertex " << v;
  EXPECT_LT(largestFoldAngleDifference(far, near), 1e-9);
}
}  // namespace
}  // namespace virtual_origami::core

// Fold by assignment answers honestly (issue: real crease patterns fold right): what it commits
// is right for paper — its strain within the bound, no crease past flat against its target, no
// faces crossing, flat layers stacked — or it is refused with the figures, unless kept; free
// hinges stay free; the opposite assignment folds the mirror image; steps and one call agree.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>

#include "crane_reference.h"
#include "virtual_origami/core/assignment_fold.h"
#include "virtual_origami/core/fold_fraction.h"
#include "virtual_origami/core/layer_order.h"
#include "virtual_origami/core/reference_patterns.h"
#include "virtual_origami/core/session.h"
#include "virtual_origami/core/tessellations.h"
#include "virtual_origami/solvers/crease_driver_factory.h"
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

/// The crease pattern of a folded state, as a designer would draw it: every crease folded one
/// way marked so, creases lying unfolded marked flat (F), the sheet flat.
Paper patternOf(const Paper& folded)
{
  Paper pattern = folded;
  for (Vertex& v : pattern.vertices)
    v.folded = Vec3(v.crease_pattern.x(), v.crease_pattern.y(), 0.0);
  for (Edge& e : pattern.edges)
    if (e.isCrease())
    {
      e.assignment = std::abs(e.fold_angle) < 1e-6 ? Assignment::Flat :
                     e.fold_angle > 0            ? Assignment::Valley :
                                                   Assignment::Mountain;
      e.fold_angle = 0.0;
    }
  pattern.face_orders.clear();
  return pattern;
}

void expectSameAngles(const Paper& a, const Paper& b, double tolerance, const std::string& what)
{
  ASSERT_EQ(a.edges.size(), b.edges.size()) << what;
  for (size_t e = 0; e < a.edges.size(); ++e)
    EXPECT_NEAR(a.edges[e].fold_angle, b.edges[e].fold_angle, tolerance) << what << ", edge " << e;
}

/// Flat, right for paper, and its layers ordered: what a flat base must be.
void expectFlatWithLayerOrder(const AssignmentFoldResult& r, const Paper& paper, const std::string& what)
{
  EXPECT_LE(r.max_strain, 1e-9) << what;
  EXPECT_LE(r.angle_error, 1e-9) << what;
  EXPECT_EQ(r.against_target, 0) << what;
  EXPECT_EQ(r.crossings, 0) << what;
  EXPECT_EQ(r.layer_problem, "") << what;
  EXPECT_GT(r.ordered_pairs, 0) << what;
  EXPECT_EQ(static_cast<int>(paper.face_orders.size()), r.ordered_pairs) << what;
  EXPECT_EQ(layerOrderViolation(paper, paper.face_orders), "") << what;
}

/// The square base and the bird base (the reference crane's states 8 and 13), drawn as crease
/// patterns, fold flat by assignment in one call to the reference's angles, with their layer
/// order; by steps to the same state, where a step whose faces would pass through each other is
/// refused and leaves the paper where it was. (The crane's body before its wings, state 19, does
/// not: its neck, tail and head are inside reverse folds, their spines turned inside out, which
/// every crease folded at once from the flat sheet cannot reach without layers crossing.)
TEST(AssignmentAnswers, TraditionalBasesFoldFlatWithTheirLayerOrderInOneCallAndInSteps)
{
  const Expected<std::vector<Paper>> states = test::craneStates();
  ASSERT_TRUE(states) << states.message();
  for (int step : { 8, 13 })
  {
    const std::string what = "crane state " + std::to_string(step);
    const Paper& reference = (*states)[step];
    const Paper pattern = patternOf(reference);
    Session one = foldingSession(pattern);
    const Expected<AssignmentFoldResult> at_once = one.foldByAssignment(1.0);
    ASSERT_TRUE(at_once) << what << ": " << at_once.message();
    expectFlatWithLayerOrder(*at_once, one.paper(), what);
    expectSameAngles(one.paper(), reference, 1e-6, what);

    Session steps = foldingSession(pattern);
    for (double fraction : { 0.25, 0.5, 0.75, 1.0 })
    {
      const Paper before = steps.paper();
      const uint64_t revision = steps.revision();
      AssignmentFoldResult figures;
      const Expected<Computed<AssignmentFoldResult>> computed =
          computeFoldByAssignment(steps.workspace(), fraction, true, {}, &figures);
      const Expected<AssignmentFoldResult> r = steps.foldByAssignment(fraction);
      ASSERT_EQ(r.ok(), computed.ok()) << what;
      if (!r)
      {
        // Folding every crease in proportion, the body's reverse-folded layers pass through
        // each other on the way (deeply: 4 % of the sheet): refused, with the figures.
        EXPECT_GT(figures.crossings, 0) << what << " at " << fraction << ": " << r.message();
        EXPECT_THAT(r.message(), HasSubstr("pairs of faces would cross"));
        EXPECT_TRUE(steps.paper() == before) << what;
        EXPECT_EQ(steps.revision(), revision) << what;
        continue;
      }
      EXPECT_EQ(r->crossings, 0) << what << " at " << fraction;
      EXPECT_EQ(r->against_target, 0) << what << " at " << fraction;
    }
    ASSERT_NEAR(foldFraction(steps.paper()), 1.0, 1e-9) << what;
    expectSameAngles(steps.paper(), one.paper(), 1e-6, what + ", steps against one call");
    EXPECT_EQ(steps.paper().face_orders, one.paper().face_orders) << what;
  }
  // State 19 at once: refused, the layers crossing, the paper left flat.
  Session body = foldingSession(patternOf((*states)[19]));
  const Paper flat = body.paper();
  const Expected<AssignmentFoldResult> refused = body.foldByAssignment(1.0);
  ASSERT_FALSE(refused.ok());
  EXPECT_THAT(refused.message(), HasSubstr("pairs of faces would cross"));
  EXPECT_TRUE(body.paper() == flat);
}

/// The waterbomb base: both diagonals valley, one midline mountain (Maekawa: 4 − 2 at the
/// centre). Flat at its targets, every layer ordered.
TEST(AssignmentAnswers, WaterbombBaseFoldsFlatWithItsLayerOrder)
{
  // Corners 0–3, the midline's ends 4 (left) and 5 (right), the centre 6.
  const std::vector<Vec2> vertices = { { 0, 0 }, { 1, 0 }, { 1, 1 }, { 0, 1 }, { 0, 0.5 }, { 1, 0.5 }, { 0.5, 0.5 } };
  const std::vector<std::vector<int>> faces = { { 0, 1, 6 }, { 1, 5, 6 }, { 5, 2, 6 },
                                                { 2, 3, 6 }, { 3, 4, 6 }, { 4, 0, 6 } };
  Expected<Paper> pattern = patternPaper(vertices, faces);
  ASSERT_TRUE(pattern) << pattern.message();
  for (Edge& e : pattern->edges)
    if (e.isCrease())
    {
      const bool midline = e.otherVertex(6) == 4 || e.otherVertex(6) == 5;
      e.assignment = midline ? Assignment::Mountain : Assignment::Valley;
    }
  Session session = foldingSession(*pattern);
  const Expected<AssignmentFoldResult> r = session.foldByAssignment(1.0);
  ASSERT_TRUE(r) << r.message();
  expectFlatWithLayerOrder(*r, session.paper(), "waterbomb base");
  for (const Edge& e : session.paper().edges)
  {
    if (e.isCrease())
    {
      EXPECT_NEAR(e.fold_angle, e.assignment == Assignment::Valley ? M_PI : -M_PI, 1e-9);
    }
  }
  // Flat: a triangle of half the sheet's width, every vertex on one plane.
  const Paper& folded = session.paper();
  const Vec3 n = folded.faceNormal(0);
  for (const Vertex& v : folded.vertices)
    EXPECT_NEAR(n.dot(v.folded - folded.vertices[6].folded), 0.0, 1e-9);
}

/// A Miura-ori with only its zigzag creases assigned: the straight ones are free hinges. They
/// stay unassigned after every commit, so a second commit drives only the zigzag creases, and
/// two commits end where one does (the pattern is a mechanism of one degree of freedom).
TEST(AssignmentAnswers, FreeHingesStayFreeAfterEveryCommit)
{
  const Tessellation miura = miuraTessellation(4, 4).value();
  Paper pattern = miura.paper;
  int free_hinges = 0;
  for (Edge& e : pattern.edges)
    if (e.isCrease() && std::abs(pattern.vertices[e.vertices[0]].crease_pattern.y() -
                                 pattern.vertices[e.vertices[1]].crease_pattern.y()) < 1e-12)
    {
      e.assignment = Assignment::Unassigned;
      ++free_hinges;
    }
  ASSERT_GT(free_hinges, 0);
  Session steps = foldingSession(pattern);
  for (double fraction : { 0.5, 0.75 })
  {
    const Expected<AssignmentFoldResult> r = steps.foldByAssignment(fraction);
    ASSERT_TRUE(r) << r.message();
    const std::vector<double> targets = creaseTargets(steps.paper());
    int still_free = 0;
    for (size_t e = 0; e < targets.size(); ++e)
      if (pattern.edges[e].assignment == Assignment::Unassigned)
      {
        EXPECT_EQ(steps.paper().edges[e].assignment, Assignment::Unassigned) << "edge " << e;
        EXPECT_TRUE(std::isnan(targets[e])) << "edge " << e << " is driven after the commit to " << fraction;
        still_free += std::abs(steps.paper().edges[e].fold_angle) > 0.1 ? 1 : 0;
      }
    EXPECT_EQ(still_free, free_hinges) << "the free hinges fold, as the mechanism makes them";
  }
  Session one = foldingSession(pattern);
  ASSERT_TRUE(one.foldByAssignment(0.75));
  expectSameAngles(steps.paper(), one.paper(), 1e-6, "two commits against one");
}

/// −100 % … 0: every driven crease towards the opposite of its target (a mountain folds as a
/// valley). A Miura-ori at −f is the mirror image of itself at f: every fold angle negated.
TEST(AssignmentAnswers, NegativeFractionsFoldTheMirrorImage)
{
  const Paper pattern = miuraTessellation(4, 4).value().paper;
  Session forward = foldingSession(pattern);
  Session backward = foldingSession(pattern);
  const Expected<AssignmentFoldResult> f = forward.foldByAssignment(0.5);
  const Expected<AssignmentFoldResult> b = backward.foldByAssignment(-0.5);
  ASSERT_TRUE(f) << f.message();
  ASSERT_TRUE(b) << b.message();
  int folded = 0;
  for (size_t e = 0; e < pattern.edges.size(); ++e)
    if (pattern.edges[e].isCrease())
    {
      EXPECT_NEAR(backward.paper().edges[e].fold_angle, -forward.paper().edges[e].fold_angle, 1e-6) << "edge " << e;
      EXPECT_EQ(backward.paper().edges[e].assignment, pattern.edges[e].assignment) << "assignments are kept";
      folded += std::abs(forward.paper().edges[e].fold_angle) > 0.1 ? 1 : 0;
    }
  EXPECT_GT(folded, 0);
  EXPECT_EQ(b->against_target, 0) << "measured against −f · target";
  EXPECT_LT(foldFraction(backward.paper()), -0.1);
  // And on to the opposite flat state.
  const Expected<AssignmentFoldResult> flat = backward.foldByAssignment(-1.0);
  ASSERT_TRUE(flat) << flat.message();
  EXPECT_LE(flat->angle_error, 1e-9);
  EXPECT_EQ(flat->layer_problem, "");
  EXPECT_GT(flat->ordered_pairs, 0);
}

/// A square twist cannot fold half way with rigid faces: the strain is over the bound, so the
/// commit is refused with its figures and changes nothing; kept on request, it is committed with
/// the same figures.
TEST(AssignmentAnswers, AStrainedStateIsRefusedWithItsFiguresUnlessKept)
{
  const Paper pattern = squareTwistTessellation(2, 2).value().paper;
  Session session = foldingSession(pattern);
  AssignmentFoldResult figures;
  const Expected<Computed<AssignmentFoldResult>> refused =
      computeFoldByAssignment(session.workspace(), 0.5, true, {}, &figures);
  ASSERT_FALSE(refused);
  EXPECT_GT(figures.max_strain, 1e-3);
  EXPECT_THAT(refused.message(), HasSubstr("the faces would stretch: strain"));
  EXPECT_THAT(refused.message(), HasSubstr("over the bound 0.001"));
  const Expected<AssignmentFoldResult> through_session = session.foldByAssignment(0.5);
  ASSERT_FALSE(through_session);
  EXPECT_TRUE(session.paper() == pattern);
  EXPECT_EQ(session.revision(), 0u);
  EXPECT_TRUE(session.log().empty());
  // A preview is a frame of the slide: shown whatever its strain.
  EXPECT_TRUE(session.foldByAssignment(0.5, false));
  // A looser bound, or keep, commits it.
  AssignmentFoldAcceptance loose;
  loose.max_strain = 2 * figures.max_strain;
  EXPECT_TRUE(computeFoldByAssignment(session.workspace(), 0.5, true, loose));
  AssignmentFoldAcceptance keep;
  keep.keep = true;
  const Expected<AssignmentFoldResult> kept = session.foldByAssignment(0.5, true, keep);
  ASSERT_TRUE(kept) << kept.message();
  EXPECT_NEAR(kept->max_strain, figures.max_strain, 1e-9);
  EXPECT_FALSE(kept->rigid);
  EXPECT_EQ(session.revision(), 1u);
  // Applying the recorded fold again reproduces the kept state: a recorded fold is kept on
  // replay. It went on from the preview before it, so the recording carries where it ended (as
  // `operations` does), and the replay takes that.
  ASSERT_EQ(session.log().size(), 1u);
  Operation recorded = session.log().back();
  for (const Vertex& v : session.paper().vertices)
    recorded.folded.push_back(v.folded);
  Session again = foldingSession(pattern);
  ASSERT_TRUE(again.apply(recorded));
  EXPECT_TRUE(again.paper() == session.paper());
}

/// The verdict names each problem with its figure; a result whose creases did not turn where
/// they were asked to (faces that cannot bend held them), or that ends off its targets at 100 %,
/// is never "folded".
TEST(AssignmentAnswers, TheVerdictNamesEveryProblem)
{
  AssignmentFoldResult right;
  right.fraction = 1.0;
  EXPECT_EQ(assignmentFoldProblems(right, {}), "");
  AssignmentFoldResult wrong = right;
  wrong.max_strain = 0.94;
  wrong.against_target = 22;
  wrong.crossings = 340;
  wrong.layer_problem = "faces 3 and 7 would pass through each other";
  const std::string said = assignmentFoldProblems(wrong, {});
  EXPECT_THAT(said, HasSubstr("strain 0.94"));
  EXPECT_THAT(said, HasSubstr("22 creases would fold against"));
  EXPECT_THAT(said, HasSubstr("340 pairs of faces would cross"));
  EXPECT_THAT(said, HasSubstr("faces 3 and 7"));
  AssignmentFoldAcceptance keep;
  keep.keep = true;
  EXPECT_EQ(assignmentFoldProblems(wrong, keep), "");
  AssignmentFoldResult held = right;
  held.fraction = 0.5;
  held.asked_to_turn = 20;
  held.stuck = 12;
  held.angle_error = 1.5;
  EXPECT_THAT(assignmentFoldProblems(held, {}), HasSubstr("12 of 20 creases could not turn"));
  held.stuck = 2;  // a few waiting for others on a rigid path
  EXPECT_EQ(assignmentFoldProblems(held, {}), "");
  AssignmentFoldResult short_of_it = right;
  short_of_it.angle_error = 3.04;  // all the way asked, the sheet where it was
  EXPECT_THAT(assignmentFoldProblems(short_of_it, {}), HasSubstr("the creases end 3.04 rad (RMS) from their targets"));
  short_of_it.fraction = 0.75;  // part way, creases miss fraction · target by design (a Miura-ori's)
  EXPECT_EQ(assignmentFoldProblems(short_of_it, {}), "");
}

}  // namespace
}  // namespace virtual_origami::core

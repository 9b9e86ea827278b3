// A flat result of fold by assignment carries its layer order (faceOrders) also where its stack
// is large but sparse: Origami Simulator's waterbomb tessellation folds flat with its 330 faces
// in one stack, which at 250 faces was answered `success` without any order recorded.
#include <gtest/gtest.h>

#include <string>

#include "library_patterns.h"
#include "virtual_origami/core/assignment_fold.h"
#include "virtual_origami/core/layer_order.h"
#include "virtual_origami/core/session.h"
#include "virtual_origami/core/tessellations.h"
#include "virtual_origami/solvers/crease_driver_factory.h"
#include "virtual_origami/solvers/solver_factory.h"

namespace virtual_origami::core
{
namespace
{
TEST(AssignmentLayers, ALargeSparseFlatStackCarriesItsLayerOrder)
{
  Session session(test::libraryPattern("Tessellations/waterbomb.svg"));
  session.setSolver(makeSolver("newton"));
  session.setCreaseDrivers(makeCreaseDriver("quasi_newton"));
  const Expected<AssignmentFoldResult> flat = session.foldByAssignment(1.0);
  ASSERT_TRUE(flat) << flat.message();
  EXPECT_TRUE(flat->layer_problem.empty()) << flat->layer_problem;

  // Its 330 faces lie over each other in one stack, more than the 250 a stack is bounded by
  // by default.
  const Paper& paper = session.paper();
  LayerOrderOptions options;
  options.tolerance = 1e-5 * paper.scale();
  const Expected<LayerOrder> bounded = solveLayerOrder(paper, options);
  ASSERT_TRUE(bounded);
  EXPECT_FALSE(bounded->complete);
  EXPECT_NE(bounded->incomplete.find("a stack of 330 faces"), std::string::npos) << bounded->incomplete;

  // Its order is recorded, one entry per overlapping pair, and obeys every rule of paper.
  EXPECT_GT(flat->ordered_pairs, 10000);
  EXPECT_EQ(static_cast<int>(paper.face_orders.size()), flat->ordered_pairs);
  EXPECT_EQ(layerOrderViolation(paper, paper.face_orders, options.tolerance, true), "");
}

/// A flat stack too large to order (a Miura-ori of 28 × 28 parallelograms folds flat into one
/// stack of 31,752 overlapping pairs, more than the 20,000 a stack is bounded by; 24 × 24 makes
/// 19,872) is answered with no order recorded, and the answer says so and why: its layers are
/// unchecked.
TEST(AssignmentLayers, AFlatStackTooLargeToOrderIsSaidToBeUnordered)
{
  Session session(miuraTessellation(28, 28).value().paper);
  session.setSolver(makeSolver("newton"));
  session.setCreaseDrivers(makeCreaseDriver("quasi_newton"));
  const Expected<AssignmentFoldResult> flat = session.foldByAssignment(1.0);
  ASSERT_TRUE(flat) << flat.message();
  EXPECT_LE(flat->angle_error, 1e-3);
  EXPECT_EQ(flat->ordered_pairs, 0);
  EXPECT_TRUE(session.paper().face_orders.empty());
  EXPECT_NE(flat->layers_unordered.find("more than the 20000 overlapping pairs of faces"), std::string::npos)
      << flat->layers_unordered;

  // A smaller one is ordered, and says nothing of it.
  Session small(miuraTessellation(6, 6).value().paper);
  small.setSolver(makeSolver("newton"));
  small.setCreaseDrivers(makeCreaseDriver("quasi_newton"));
  const Expected<AssignmentFoldResult> ordered = small.foldByAssignment(1.0);
  ASSERT_TRUE(ordered) << ordered.message();
  EXPECT_GT(ordered->ordered_pairs, 0);
  EXPECT_EQ(ordered->layers_unordered, "");
}

}  // namespace
}  // namespace virtual_origami::core

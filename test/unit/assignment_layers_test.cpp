// A flat result of fold by assignment carries its layer order (faceOrders) also where its stack
// is large but sparse: Origami Simulator's waterbomb tessellation folds flat with its 330 faces
// in one stack, which at 250 faces was answered `success` without any order recorded.
#include <gtest/gtest.h>

#include <string>

#include "library_patterns.h"
#include "virtual_origami/core/assignment_fold.h"
#include "virtual_origami/core/layer_order.h"
#include "virtual_origami/core/session.h"
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

}  // namespace
}  // namespace virtual_origami::core

// LayerContact's candidate pairs (contact.h) are searched anew only when the nodes have moved
// apart by more than the skin allows: a sheet carried along whole (the frames' pins lifting it,
// a gripper moving it) keeps its candidates, and watches the pairs a fresh search finds.
#include <gtest/gtest.h>

#include "virtual_origami/curved/bubble_mesh.h"
#include "virtual_origami/curved/contact.h"
#include "virtual_origami/curved/seed_scenes.h"

using namespace virtual_origami::core;

namespace
{
struct FoldedFlap
{
  SeedScene scene = *seedScene(3, 1.0, 2e-3);  // a flap folded flat onto the sheet: two layers
  CurvedMesh mesh;
  Positions x;

  FoldedFlap()
  {
    BubbleMeshOptions options;
    options.spacing = 0.1;
    mesh = *bubbleMesh(scene.paper, options);
    x = placeNodes(mesh, scene.paper);
  }
};

TEST(CurvedContactSkin, ASheetCarriedAlongWholeKeepsItsCandidatesAndWatchesTheSamePairs)
{
  const FoldedFlap flap;
  LayerContact contact(flap.mesh, flap.scene.paper, {});
  contact.update(flap.x);
  ASSERT_GT(contact.watchedPairs(), 0) << "the flap lies on the sheet";
  const Positions moved = flap.x.colwise() + Vec3(5.0, -3.0, 2.0) * contact.range();
  EXPECT_LT(contact.skinUsed(moved), 1e-9);
  EXPECT_FALSE(contact.needsSearch(moved));
  contact.update(moved);
  LayerContact fresh(flap.mesh, flap.scene.paper, {});
  fresh.update(moved);
  EXPECT_EQ(contact.pairNodes(), fresh.pairNodes());
  EXPECT_EQ(contact.worstGap(moved), fresh.worstGap(moved));
}

TEST(CurvedContactSkin, NodesMovedApartByMoreThanTheSkinAreSearchedAnew)
{
  const FoldedFlap flap;
  LayerContact contact(flap.mesh, flap.scene.paper, {});
  contact.update(flap.x);
  // One node 1.2 skins (the skin: the range) from the rest, all carried along besides: it may
  // have come 1.2 skins nearer a triangle the search left out, beyond the skin.
  Positions moved = flap.x.colwise() + Vec3(5.0, -3.0, 2.0) * contact.range();
  const int node = static_cast<int>(flap.mesh.nodes.size() / 2);
  moved.col(node) += Vec3(0, 0, 1.2 * contact.range());
  EXPECT_NEAR(contact.skinUsed(moved), 1.2, 1e-9);
  EXPECT_TRUE(contact.needsSearch(moved));
  // 0.8 of the skin: within it (each end of a pair half of it from the common motion).
  moved.col(node) -= Vec3(0, 0, 0.4 * contact.range());
  EXPECT_NEAR(contact.skinUsed(moved), 0.8, 1e-9);
  EXPECT_FALSE(contact.needsSearch(moved));
}
}  // namespace

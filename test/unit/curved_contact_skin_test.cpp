// LayerContact's candidate pairs (contact.h) are searched anew only when the nodes have moved
// apart by more than the skin allows: a sheet carried along whole (the frames' pins lifting it,
// a gripper moving it) keeps its candidates, and watches the pairs a fresh search finds.
#include <gtest/gtest.h>

#include <algorithm>

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

namespace
{
// The search's grid (an array of cells over the sheet's extent) finds the same candidates
// wherever the sheet lies, its cells' keys negative or positive, and the pairs a sheet's
// layers watch are among them.
TEST(CurvedContactSkin, TheSearchFindsTheSameCandidatesWhereverTheSheetLies)
{
  const FoldedFlap flap;
  const LayerContact contact(flap.mesh, flap.scene.paper, {});
  const auto sorted = [](LayerContact::Candidates c) {
    std::sort(c.nodes.begin(), c.nodes.end());
    std::sort(c.edges.begin(), c.edges.end());
    return c;
  };
  const LayerContact::Candidates here = sorted(contact.candidatesAt(flap.x));
  ASSERT_FALSE(here.nodes.empty());
  ASSERT_FALSE(here.edges.empty());
  for (const Vec3& offset : { Vec3(-7.3, 2.1, -0.37), Vec3(1e3, -2e3, 5e2) })
  {
    const LayerContact::Candidates there = sorted(contact.candidatesAt(flap.x.colwise() + offset));
    EXPECT_EQ(there.nodes, here.nodes) << offset.transpose();
    EXPECT_EQ(there.edges, here.edges) << offset.transpose();
  }
  LayerContact watching(flap.mesh, flap.scene.paper, {});
  watching.update(flap.x);
  ASSERT_GT(watching.watchedPairs(), 0);
  for (const auto& pair : watching.pairNodes())
  {
    // A node–triangle pair: the node first, then the triangle's corners.
    bool listed = false;
    for (const auto& [node, triangle] : here.nodes)
      listed = listed || (node == pair[0] && flap.mesh.triangles[triangle].nodes[0] == pair[1] &&
                          flap.mesh.triangles[triangle].nodes[1] == pair[2]);
    for (const auto& [a, b] : here.edges)
      listed = listed || (flap.mesh.edges[a].nodes[0] == pair[0] && flap.mesh.edges[a].nodes[1] == pair[1] &&
                          flap.mesh.edges[b].nodes[0] == pair[2] && flap.mesh.edges[b].nodes[1] == pair[3]);
    EXPECT_TRUE(listed) << pair[0] << " " << pair[1] << " " << pair[2] << " " << pair[3];
  }
}
}  // namespace

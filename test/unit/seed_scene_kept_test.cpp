// Seed 002's scene 3 on a folded model, kept (issue 38 item 3): the triangle ade folded over on
// de, corner b pulled part of the way onto c by the curved model, and the bent sheet kept as the
// paper's state — the flap still folded over, nothing crossing, b where the hand left it — then
// undone to the folded paper exactly and redone.
#include <gtest/gtest.h>

#include <cmath>

#include "virtual_origami/core/face_crossings.h"
#include "virtual_origami/core/kept_bend.h"
#include "virtual_origami/core/session.h"
#include "virtual_origami/curved/bent_sheet.h"
#include "virtual_origami/curved/seed_scenes.h"
#include "virtual_origami/solvers/solver_factory.h"

using namespace virtual_origami::core;

namespace
{
constexpr double kDeg = M_PI / 180.0;

/// Scene 3 pulled to `until` of its half turn (10 steps to half way, each balanced).
SeedSceneRun pullSceneThree(const SeedScene& scene, double until)
{
  SeedSceneOptions options;
  options.until = until;
  options.steps = static_cast<int>(std::lround(20 * until));
  const Expected<SeedSceneRun> run = runSeedScene(scene, options);
  EXPECT_TRUE(run.ok()) << run.message();
  return *run;
}
}  // namespace

TEST(SeedSceneKept, Scene3OnTheFoldedSheetIsKeptWithTheFlapFoldedAndUndoneExactly)
{
  const Expected<SeedScene> scene = seedScene(3, 1.0, 2e-3);
  ASSERT_TRUE(scene.ok()) << scene.message();
  const SeedSceneRun run = pullSceneThree(*scene, 0.5);
  ASSERT_TRUE(run.passed());

  Session session(scene->paper);
  session.setSolver(makeSolver("newton"));
  const Paper folded = session.paper();
  const size_t revisions = session.log().size();
  const Expected<KeptBend> kept = session.keepBend(bentSheetOf(run.mesh, run.positions));
  ASSERT_TRUE(kept.ok()) << kept.message();
  EXPECT_EQ(session.log().size(), revisions + 1);
  const Paper bent = session.paper();

  // The pulled half bent: its faces became triangles, joined by facets that hold a real bend.
  EXPECT_FALSE(kept->bent_faces.empty());
  EXPECT_GT(kept->largest_bend, 10 * kDeg);
  EXPECT_LT(kept->max_strain, kKeptBendMaxStrain);
  // Corner b is where the hand left it, c where it was held.
  const Vec3 pulled = scene->pullAt(0.5);
  EXPECT_LT((bent.vertices[scene->pulled].folded - pulled).norm(), 1e-12);
  EXPECT_LT((bent.vertices[scene->fixed].folded - folded.vertices[scene->fixed].folded).norm(), 1e-12);
  // The flap ade still lies folded over: every piece of the crease de stays past 150°.
  int folded_pieces = 0;
  for (const Edge& e : bent.edges)
    if (e.isCrease() && std::abs(e.fold_angle) > 90 * kDeg)
    {
      ++folded_pieces;
      EXPECT_GT(std::abs(e.fold_angle), 150 * kDeg);
    }
  EXPECT_GT(folded_pieces, 1);  // de split at the nodes of the bent faces beside it
  EXPECT_TRUE(findFaceCrossings(bent).empty());

  ASSERT_TRUE(session.undo().ok());
  EXPECT_TRUE(session.paper() == folded);
  ASSERT_TRUE(session.redo().ok());
  EXPECT_TRUE(session.paper() == bent);
}

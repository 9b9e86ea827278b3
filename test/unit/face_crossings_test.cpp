// Faces passing through each other, against shapes whose crossings are known by construction.
#include <gtest/gtest.h>

#include <cmath>

#include "virtual_origami/core/face_crossings.h"
#include "virtual_origami/core/reference_patterns.h"
#include "virtual_origami/core/tessellations.h"

namespace virtual_origami::core
{
namespace
{
/// A strip of three faces: 0 on x ∈ [0, 1], 1 on [1, 1.2], 2 on [1.2, 2.2], y ∈ [0, 1], its
/// vertices placed by hand (the lengths do not matter to crossings).
Paper strip(const Vec3& v2, const Vec3& v3)
{
  const std::vector<Vec2> cp = { { 0, 0 }, { 1, 0 }, { 1.2, 0 }, { 2.2, 0 }, { 0, 1 }, { 1, 1 }, { 1.2, 1 }, { 2.2, 1 } };
  Paper paper = patternPaper(cp, { { 0, 1, 5, 4 }, { 1, 2, 6, 5 }, { 2, 3, 7, 6 } }).value();
  const Vec3 folded[4] = { { 0, 0, 0 }, { 1, 0, 0 }, v2, v3 };
  for (int i = 0; i < 4; ++i)
  {
    paper.vertices[i].folded = folded[i];
    paper.vertices[i + 4].folded = folded[i] + Vec3(0, 1, 0);
  }
  return paper;
}

const double kTilt = 10.0 * M_PI / 180.0;

TEST(FaceCrossings, AFaceTurnedDownThroughAnotherCrossesIt)
{
  // Face 1 turned back over face 0, rising 10°; face 2 turned down from its far edge, through
  // face 0 at x ≈ 0.81.
  const Vec3 v2(1 - 0.2 * std::cos(kTilt), 0, 0.2 * std::sin(kTilt));
  const Vec3 v3 = v2 + Vec3(std::sin(kTilt), 0, -std::cos(kTilt));
  const std::vector<std::pair<int, int>> crossings = findFaceCrossings(strip(v2, v3));
  ASSERT_EQ(crossings.size(), 1u);
  EXPECT_EQ(crossings[0], std::make_pair(0, 2));
  // Turned up instead, face 2 rises away from face 0: nothing crosses.
  EXPECT_TRUE(findFaceCrossings(strip(v2, v2 + Vec3(std::sin(kTilt), 0, std::cos(kTilt)))).empty());
}

TEST(FaceCrossings, FacesThatOnlyTouchDoNotCross)
{
  // Face 1 flat on face 0, face 2 hanging straight down from it: it meets face 0's plane along
  // a line and never enters the other side.
  EXPECT_TRUE(findFaceCrossings(strip(Vec3(0.8, 0, 0), Vec3(0.8, 0, -1))).empty());
  // Face 2 flat on face 0 as well: three layers, coplanar, the layer order's question.
  EXPECT_TRUE(findFaceCrossings(strip(Vec3(0.8, 0, 0), Vec3(1.8, 0, 0))).empty());
  // Face 2 passing just under face 0's plane, less deep than the tolerance.
  const double scale = std::sqrt(2.2);
  EXPECT_TRUE(findFaceCrossings(strip(Vec3(0.8, 0, 0), Vec3(0.0, 0, -1e-8 * scale))).empty());
  EXPECT_EQ(findFaceCrossings(strip(Vec3(0.8, 0, 1e-3), Vec3(0.0, 0, -1e-3))).size(), 1u);
}

TEST(FaceCrossings, RigidlyFoldedAndFlatMiuraOriHaveNone)
{
  for (double rho : { 0.5, 2.0, 3.0 })
  {
    const Tessellation miura = miuraTessellationFolded(4, 4, 1.0, 1.0, M_PI / 3, rho).value();
    EXPECT_TRUE(findFaceCrossings(miura.paper).empty()) << rho;
  }
  Tessellation flat = miuraTessellation(4, 4).value();
  ASSERT_TRUE(foldToAngles(flat.paper, flat.target_fold_angle));
  EXPECT_TRUE(findFaceCrossings(flat.paper).empty());
}

}  // namespace
}  // namespace virtual_origami::core

// paperMarkers, the markers paper_model draws of every state and preview: each side of every face
// just off the face's plane on its own side, coincident layers a layer gap apart, every crease
// in its assignment's list at its ends.
#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include <ros/ros.h>

#include "virtual_origami/core/crease.h"
#include "virtual_origami/core/flat_fold.h"
#include "virtual_origami/core/tessellations.h"
#include "virtual_origami/ros/conversions.h"
#include "virtual_origami/ros/markers.h"

namespace
{
using namespace virtual_origami;
using visualization_msgs::Marker;

const Marker* find(const visualization_msgs::MarkerArray& array, const std::string& ns)
{
  for (const Marker& m : array.markers)
    if (m.ns == ns)
      return &m;
  return nullptr;
}

size_t fanCorners(const core::Paper& paper)
{
  size_t corners = 0;
  for (const core::Face& f : paper.faces)
    corners += 3 * (f.vertices.size() - 2);
  return corners;
}

TEST(PaperMarkers, EachSideOfAFoldedMiuraOriLiesJustOffItsFacesOnItsOwnSide)
{
  auto miura = core::miuraTessellationFolded(4, 3, 1.0, 1.0, 70.0 * M_PI / 180.0, 1.0);
  ASSERT_TRUE(miura) << miura.message();
  const core::Paper& paper = miura->paper;
  ASSERT_TRUE(paper.face_orders.empty());
  const MarkerStyle style;
  const visualization_msgs::MarkerArray markers = paperMarkers(paper, style, ros::Time(1.0));
  const Marker* front = find(markers, "front");
  const Marker* back = find(markers, "back");
  ASSERT_TRUE(front && back);
  ASSERT_EQ(front->points.size(), fanCorners(paper));
  ASSERT_EQ(back->points.size(), fanCorners(paper));
  size_t k = 0;
  for (size_t f = 0; f < paper.faces.size(); ++f)
  {
    const std::vector<int>& loop = paper.faces[f].vertices;
    const core::Vec3 normal = paper.faceNormal(static_cast<int>(f));
    const core::Vec3 centroid = paper.faceCentroid(static_cast<int>(f));
    for (size_t i = 1; i + 1 < loop.size(); ++i, k += 3)
    {
      const int corners[3] = { loop[0], loop[i], loop[i + 1] };
      for (int j = 0; j < 3; ++j)
      {
        // The front's corner is the face's vertex moved off the plane along its front normal;
        // the back's the same corner moved the other way, the triangle wound the other way.
        const core::Vec3 on_front = toVec3(front->points[k + j]);
        const core::Vec3 on_back = toVec3(back->points[k + (3 - j) % 3]);
        EXPECT_NEAR(normal.dot(on_front - centroid), style.side_offset, 1e-12);
        EXPECT_NEAR(normal.dot(on_back - centroid), -style.side_offset, 1e-12);
        EXPECT_LT((on_front - normal * style.side_offset - paper.vertices[corners[j]].folded).norm(), 1e-12);
        EXPECT_LT((on_back + normal * style.side_offset - paper.vertices[corners[j]].folded).norm(), 1e-12);
      }
      // Wound counter-clockwise about the front normal: seen from the front, front; from behind, back.
      const core::Vec3 a = toVec3(front->points[k]), b = toVec3(front->points[k + 1]), c = toVec3(front->points[k + 2]);
      EXPECT_GT((b - a).cross(c - a).dot(normal), 0.0);
      const core::Vec3 d = toVec3(back->points[k]), e = toVec3(back->points[k + 1]), g = toVec3(back->points[k + 2]);
      EXPECT_LT((e - d).cross(g - d).dot(normal), 0.0);
    }
  }
}

TEST(PaperMarkers, EveryCreaseIsDrawnInItsAssignmentsListAtItsEnds)
{
  auto miura = core::miuraTessellationFolded(3, 3, 1.0, 1.0, 70.0 * M_PI / 180.0, 0.8);
  ASSERT_TRUE(miura) << miura.message();
  const core::Paper& paper = miura->paper;
  const MarkerStyle style;
  const visualization_msgs::MarkerArray markers = paperMarkers(paper, style, ros::Time(1.0));
  std::map<std::string, size_t> drawn;  // points seen so far per list
  std::map<std::string, size_t> expected;
  for (const core::Edge& e : paper.edges)
  {
    const std::string ns = e.assignment == core::Assignment::Mountain ? "mountain" :
                           e.assignment == core::Assignment::Valley   ? "valley" :
                           e.assignment == core::Assignment::Boundary ? "boundary" :
                                                                        "crease";
    const Marker* list = find(markers, ns);
    ASSERT_TRUE(list) << ns;
    ASSERT_EQ(list->type, Marker::LINE_LIST);
    size_t& at = drawn[ns];
    ASSERT_LT(at + 1, list->points.size()) << ns;
    for (int end = 0; end < 2; ++end)
    {
      // Just over the upper side of its first face, by twice a side's offset.
      const core::Vec3 shown = toVec3(list->points[at + end]);
      const core::Vec3 vertex = paper.vertices[e.vertices[end]].folded;
      EXPECT_NEAR((shown - vertex).norm(), 2 * style.side_offset, 1e-12);
      EXPECT_GT((shown - vertex).z(), 0.0);
    }
    at += 2;
    expected[ns] += 2;
  }
  for (const auto& [ns, count] : expected)
    EXPECT_EQ(find(markers, ns)->points.size(), count) << ns;
  EXPECT_GT(expected["mountain"], 0u);
  EXPECT_GT(expected["valley"], 0u);
  // A kind the paper has none of is deleted (rviz refuses an empty list).
  const Marker* unassigned = find(markers, "crease");
  ASSERT_TRUE(unassigned);
  EXPECT_EQ(unassigned->action, expected.count("crease") ? Marker::ADD : Marker::DELETE);
}

TEST(PaperMarkers, TheLayersOfASheetFoldedInHalfAreALayerGapApart)
{
  core::Paper paper = core::Paper::square(1.0);
  core::CreaseRequest crease;
  crease.start = core::Vec3(0, 0, 0);
  crease.end = core::Vec3(1, 1, 0);
  ASSERT_TRUE(core::crease(paper, crease).ok());
  const auto folded = core::flatFold(paper, { { { core::Vec2(0, 0), core::Vec2(1, 1), M_PI } }, core::Vec2(0.9, 0.1) });
  ASSERT_TRUE(folded.ok()) << folded.message();
  ASSERT_EQ(paper.faces.size(), 2u);
  ASSERT_FALSE(paper.face_orders.empty());
  MarkerStyle style;
  style.layer_gap = 0.003;
  const visualization_msgs::MarkerArray markers = paperMarkers(paper, style, ros::Time(1.0));
  const Marker* front = find(markers, "front");
  const Marker* back = find(markers, "back");
  ASSERT_TRUE(front && back);
  ASSERT_EQ(front->points.size(), 6u);
  // Each face's layer: the middle of its two sides (whose offsets cancel), over the table.
  double layers[2];
  for (int f = 0; f < 2; ++f)
  {
    double sum = 0.0;
    for (int j = 0; j < 3; ++j)
      sum += front->points[3 * f + j].z + back->points[3 * f + j].z;
    layers[f] = sum / 6.0;
  }
  EXPECT_NEAR(std::min(layers[0], layers[1]), 0.0, 1e-12);
  EXPECT_NEAR(std::abs(layers[0] - layers[1]), style.layer_gap, 1e-12);
}
}  // namespace

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "markers_rostest");
  ros::Time::init();
  return RUN_ALL_TESTS();
}

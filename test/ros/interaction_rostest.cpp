// rostest: the interaction node driven the way rviz drives it (InteractiveMarkerFeedback on
// the server's feedback topic), checked on the paper's `state`.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <regex>
#include <set>

#include "interaction_fixture.h"

using namespace virtual_origami;
using namespace virtual_origami::test;
using Interaction = InteractionFixture;

TEST_F(Interaction, TheSheetIsADragPlaneWithAMenu)
{
  ASSERT_EQ(marker_.controls.size(), 1u);
  const auto& control = marker_.controls[0];
  EXPECT_EQ(control.interaction_mode, visualization_msgs::InteractiveMarkerControl::MOVE_PLANE);
  ASSERT_EQ(control.markers.size(), 1u);
  EXPECT_EQ(control.markers[0].type, visualization_msgs::Marker::TRIANGLE_LIST);
  EXPECT_EQ(marker_.header.frame_id, "paper");
  for (const char* title : { "Crease mode", "Rotate mode", "Squash", "Undo", "Redo", "Reset", "Pin" })
  {
    bool found = false;
    for (const auto& entry : menu_)
      found |= entry.first.find(title) != std::string::npos;
    EXPECT_TRUE(found) << title;
  }
}

TEST_F(Interaction, EveryFaceIsPickableFromBothSides)
{
  creaseDiagonal();
  const Rotate standing = client_.rotate(-1, -1, 0.8, 0.3, M_PI / 2);
  ASSERT_TRUE(standing.response.success) << standing.response.message;
  const PaperState& state = client_.stateAt(base_ + 1);
  const int corner = vertexAt(state, 1, 0);  // up in the air now
  const core::Vec3 top = folded(state, corner);
  ASSERT_GT(top.z(), 0.6);
  const core::Vec3 n = core::Vec3(1, -1, 0).normalized();  // the standing half's normal, up to sign
  // The sheet's pickable copy holds the standing corner off both sides of its face, as far
  // each way (issue 23: a copy lifted along z lay in the standing face, and rviz picked the
  // drawing: 0 of 25 points on it).
  std::vector<double> offsets;
  ASSERT_TRUE(waitFor(
      [&] {
        offsets.clear();
        if (!loadMenu())
          return false;
        for (const auto& p : marker_.controls[0].markers[0].points)
        {
          const core::Vec3 off = toVec3(p) - top;
          if ((off - off.dot(n) * n).norm() < 1e-9)
            offsets.push_back(off.dot(n));
        }
        return offsets.size() >= 2;
      },
      10));
  const auto [lo, hi] = std::minmax_element(offsets.begin(), offsets.end());
  EXPECT_LT(*lo, -1e-3);
  EXPECT_GT(*hi, 1e-3);
  EXPECT_NEAR(*lo, -*hi, 1e-9);
}

TEST_F(Interaction, DraggingAlongTheDiagonalCreasesCornerToCorner)
{
  menu("Crease mode");
  // Near, not on, the corners: snapping lands on them. Guides show while dragging.
  drag(p3(0.012, 0.018), p3(0.986, 0.991), 10, [&] {
    EXPECT_TRUE(waitFor([&] { return shown_.count("line") && shown_.count("end_snap"); }, 5));
    EXPECT_TRUE(shown_.count("start_snap"));
    EXPECT_EQ(client_.state().revision, base_);  // nothing committed while dragging
  });
  const PaperState& state = client_.stateAt(base_ + 1);
  EXPECT_EQ(guidesShown(), 0u);  // the guides are gone after the release
  const int a = vertexAt(state, 0, 0), b = vertexAt(state, 1, 1);
  ASSERT_GE(a, 0);
  ASSERT_GE(b, 0);
  const int diagonal = creaseBetween(state, a, b);
  ASSERT_GE(diagonal, 0) << "no edge joins the corners";
  EXPECT_EQ(state.edges[diagonal].face_left >= 0 && state.edges[diagonal].face_right >= 0, true);
  EXPECT_EQ(state.faces.size(), 2u);
  EXPECT_EQ(state.vertices_crease_pattern.size(), 4u);  // no new vertex: exactly corner to corner
}

TEST_F(Interaction, AnEdgeDivisionGuideShowsWhileDragging)
{
  menu("Crease mode");
  drag(p3(0.49, 0.01), p3(0.51, 0.99), 8,
       [&] { EXPECT_TRUE(waitFor([&] { return shown_.count("end_guide_points") > 0; }, 5)); });
  const PaperState& state = client_.stateAt(base_ + 1);
  EXPECT_GE(vertexAt(state, 0.5, 0), 0);
  EXPECT_GE(vertexAt(state, 0.5, 1), 0);
}

TEST_F(Interaction, ASnappedDirectionThatEndsInsideTheSheetCreasesAcrossIt)
{
  menu("Crease mode");
  // Issue 23: from a corner towards 22.5°, released inside the sheet: the end snapped to the
  // ray short of the edge, and the crease was refused.
  const double a = M_PI / 8;
  drag(p3(0.008, 0.006), p3(0.85 * std::cos(a) + 0.004, 0.85 * std::sin(a) - 0.004), 10);
  const PaperState& state = client_.stateAt(base_ + 1);
  const int corner = vertexAt(state, 0, 0);
  int end = -1;
  for (size_t v = 0; v < state.vertices_crease_pattern.size(); ++v)
    if ((creasePattern(state, static_cast<int>(v)) - p3(1, std::tan(a))).norm() < 1e-9)
      end = static_cast<int>(v);
  ASSERT_GE(end, 0) << "no vertex where the 22.5° ray leaves the sheet";
  EXPECT_GE(creaseBetween(state, corner, end), 0);
  EXPECT_EQ(state.faces.size(), 2u);
}

TEST_F(Interaction, ARefusalSpeaksToTheUserOverTheSheet)
{
  menu("Crease mode");
  said_ = {};
  drag(p3(0.3, 0.3), p3(0.6, 0.4), 6);  // inside the face: no crease across it
  expectUnchanged();
  expectSaidOverTheSheet("Not creased: a crease runs across a face");
  said_ = {};
  drag(p3(1.06, 0.1), p3(1.08, 0.9), 6);  // on the margin past the right edge, missing the paper
  expectUnchanged();
  expectSaidOverTheSheet("Not creased: the line does not cross the paper");
  menu("Rotate mode");
  said_ = {};
  drag(p3(0.95, 0.05), p3(0.6, 0.4), 6);  // no crease yet
  expectUnchanged();
  expectSaidOverTheSheet("This part has no crease to turn about yet");
}

TEST_F(Interaction, ARefusalIsForgottenOnTheNextSuccess)
{
  menu("Crease mode");
  drag(p3(0.3, 0.3), p3(0.6, 0.4), 6);  // refused: not across a face
  ASSERT_TRUE(waitFor([&] { return !status_.message.empty(); }, 5));
  drag(p3(0.012, 0.018), p3(0.986, 0.991), 10);  // the diagonal, creased
  client_.stateAt(base_ + 1);
  const int seen = statuses_;
  ASSERT_TRUE(waitFor([&] { return statuses_ > seen && status_.revision == base_ + 1; }, 10));
  EXPECT_EQ(status_.message, "");
  EXPECT_FALSE(shown_.count("message"));
}

TEST_F(Interaction, FaceOrdersSayWhichLayerLiesAbove)
{
  // msg/FaceOrder.msg: `above` +1 when `other` lies on the side `face`'s front normal points to.
  ASSERT_TRUE(client_.crease(0.5, 0, 0.5, 1).response.success);
  const Rotate valley = client_.rotate(-1, -1, 0.75, 0.5, M_PI);  // the right half up and over the left
  ASSERT_TRUE(valley.response.success) << valley.response.message;
  const PaperState& state = client_.stateAt(base_ + 2);
  ASSERT_FALSE(state.face_orders.empty());
  const auto moved = [&](int f) {
    double x = 0;
    for (int v : state.faces[f].vertices)
      x += creasePattern(state, v).x() / static_cast<double>(state.faces[f].vertices.size());
    return x > 0.5;
  };
  const auto normalZ = [&](int f) {
    const auto& vs = state.faces[f].vertices;
    return (folded(state, vs[1]) - folded(state, vs[0])).cross(folded(state, vs[2]) - folded(state, vs[0])).z();
  };
  for (const FaceOrder& o : state.face_orders)
  {
    ASSERT_NE(moved(o.face), moved(o.other));
    const double other_higher = moved(o.other) ? 1.0 : -1.0;  // the turned half lies on top
    EXPECT_EQ(o.above, normalZ(o.face) * other_higher > 0 ? 1 : -1) << o.face << " " << o.other;
  }
}

TEST_F(Interaction, DraggingAHalfTurnsItAboutTheCrease)
{
  creaseDiagonal();
  menu("Rotate mode");
  const PaperState before = client_.state();
  const int moving = vertexAt(before, 1, 0), staying = vertexAt(before, 0, 1);
  const int previews_before = paper_markers_;
  // From the lower-right half onto the diagonal: from above, a quarter turn.
  drag(p3(0.8, 0.3), p3(0.55, 0.55), 10, [&] {
    EXPECT_TRUE(waitFor([&] { return shown_.count("axis") && shown_.count("ring"); }, 5));
    EXPECT_TRUE(waitFor([&] { return paper_markers_ > previews_before; }, 5));  // previews drawn
    EXPECT_EQ(client_.state().revision, base_);                                 // not committed
  });
  const PaperState& after = client_.stateAt(base_ + 1);
  const int axis = creaseBetween(after, vertexAt(after, 0, 0), vertexAt(after, 1, 1));
  ASSERT_GE(axis, 0);
  EXPECT_NEAR(after.edges[axis].fold_angle, M_PI / 2, 1e-6);
  EXPECT_EQ(after.edges[axis].assignment, "V");  // towards the eye above: a valley
  EXPECT_GT(folded(after, moving).z(), 0.6);
  EXPECT_TRUE(folded(after, staying).isApprox(folded(before, staying)));
  EXPECT_EQ(guidesShown(), 0u);
}

TEST_F(Interaction, EveryPressOnAHalfStartsATurn)
{
  creaseDiagonal();
  menu("Rotate mode");
  const PaperState before = client_.state();
  // Issue 23: 7 of 10 such presses were refused ("no crease on the line through the click
  // and its centre"). Each press is dragged half way to the crease: from above, 45°.
  const std::vector<core::Vec3> presses = {
    p3(0.95, 0.05), p3(0.5, 0.04), p3(0.96, 0.5),  p3(0.3, 0.1), p3(0.9, 0.7),
    p3(0.6, 0.3),   p3(0.2, 0.04), p3(0.97, 0.88), p3(0.7, 0.1), p3(0.8, 0.45)
  };
  for (const core::Vec3& press : presses)
  {
    const core::Vec3 foot = p3(0.5 * (press.x() + press.y()), 0.5 * (press.x() + press.y()));
    drag(press, press + 0.5 * (foot - press), 6);
    const PaperState& turned = client_.stateAt(base_ + 1);
    ASSERT_EQ(turned.revision, base_ + 1)
        << "the press at (" << press.x() << ", " << press.y() << ") turned nothing: " << status_.message;
    const int axis = creaseBetween(turned, vertexAt(turned, 0, 0), vertexAt(turned, 1, 1));
    ASSERT_GE(axis, 0);
    EXPECT_NEAR(turned.edges[axis].fold_angle, M_PI / 4, 1e-6) << press.transpose();
    ASSERT_TRUE(client_.trigger("undo").response.success);
    base_ += 2;
    EXPECT_EQ(client_.stateAt(base_).vertices_folded, before.vertices_folded);
    ASSERT_TRUE(waitFor([&] { return status_.revision == base_; }, 10));
  }
}

TEST_F(Interaction, AClickOnACreaseNamesTheAxis)
{
  creaseDiagonal();
  ASSERT_TRUE(client_.crease(0.5, 0, 0.5, 1).response.success);
  ++base_;
  ASSERT_TRUE(waitFor([&] { return status_.revision == base_; }, 10));
  menu("Rotate mode");
  const auto creaseThrough = [&](const PaperState& s, double x0, double y0, double x1, double y1) {
    return creaseBetween(s, vertexAt(s, x0, y0), vertexAt(s, x1, y1));
  };
  // A click on the vertical crease names it: the drag from the lower right, whose automatic
  // axis is the diagonal, turns the right half about the vertical crease instead.
  drag(p3(0.505, 0.8), p3(0.505, 0.8), 1);
  EXPECT_EQ(client_.state().revision, base_);
  EXPECT_TRUE(shown_.count("named_axis"));
  EXPECT_NE(status_.message.find("axis"), std::string::npos) << status_.message;
  drag(p3(0.9, 0.2), p3(0.7, 0.2), 6);  // from 0.4 to 0.2 off the axis: 45°
  const PaperState turned = client_.stateAt(base_ + 1);
  EXPECT_NEAR(std::abs(turned.edges[creaseThrough(turned, 0.5, 0, 0.5, 0.5)].fold_angle), M_PI / 4, 1e-6);
  EXPECT_NEAR(std::abs(turned.edges[creaseThrough(turned, 0.5, 0.5, 0.5, 1)].fold_angle), M_PI / 4, 1e-6);
  EXPECT_NEAR(turned.edges[creaseThrough(turned, 0, 0, 0.5, 0.5)].fold_angle, 0.0, 1e-9);
  EXPECT_NEAR(turned.edges[creaseThrough(turned, 0.5, 0.5, 1, 1)].fold_angle, 0.0, 1e-9);
  ASSERT_TRUE(client_.trigger("undo").response.success);
  base_ += 2;
  client_.stateAt(base_);
  ASSERT_TRUE(waitFor([&] { return status_.revision == base_; }, 10));
  EXPECT_TRUE(shown_.count("named_axis"));  // named until released
  // A click off the creases goes back to the automatic axis: the same drag turns the diagonal.
  drag(p3(0.8, 0.4), p3(0.8, 0.4), 1);
  EXPECT_FALSE(shown_.count("named_axis"));
  drag(p3(0.9, 0.2), p3(0.7, 0.2), 6);
  const PaperState& automatic = client_.stateAt(base_ + 1);
  EXPECT_GT(std::abs(automatic.edges[creaseThrough(automatic, 0.5, 0.5, 1, 1)].fold_angle), 0.1);
  EXPECT_NEAR(automatic.edges[creaseThrough(automatic, 0.5, 0, 0.5, 0.5)].fold_angle, 0.0, 1e-9);
}

TEST_F(Interaction, AClickOnAStackDrawsNothingNew)
{
  quarterFold();
  ASSERT_TRUE(waitFor([&] { return frontHeights().size() == 4; }, 10)) << frontHeights().size() << " heights";
  menu("Rotate mode");
  const int drawn = paper_markers_;
  const auto heights = frontHeights();
  // Issue 23: a click in rotate mode redrew the four layers at two heights (a preview of no
  // turn), the revision unchanged.
  drag(p3(0.2, 0.3), p3(0.2, 0.3), 1);
  expectUnchanged();
  EXPECT_EQ(paper_markers_, drawn) << "the paper was drawn anew without a change";
  EXPECT_EQ(frontHeights(), heights);
}

TEST_F(Interaction, APreviewIsDrawnAsItsCommitIs)
{
  quarterFold();
  menu("Rotate mode");
  visualization_msgs::Marker previewed;
  const int drawn = paper_markers_;
  // The flap over the crease y = .5 lifted by 45° and released there.
  drag(p3(0.25, 0.1), p3(0.25, 0.3), 8, [&] {
    EXPECT_TRUE(waitFor([&] { return paper_markers_ > drawn; }, 5));  // previews drawn
    ros::WallDuration(0.3).sleep();                                   // the last pose's too
    ros::spinOnce();
    previewed = front_;
  });
  client_.stateAt(base_ + 1);
  ASSERT_TRUE(waitFor([&] { return front_.header.stamp > previewed.header.stamp; }, 10));
  EXPECT_EQ(front_.points, previewed.points);
  EXPECT_GT(frontHeights().size(), 4u);  // the flap stands off the table
}

TEST_F(Interaction, MenuUndoRestoresThePreviousState)
{
  creaseDiagonal();
  menu("Rotate mode");
  const PaperState before = client_.state();
  drag(p3(0.2, 0.7), p3(0.8, 0.2), 12);  // across the diagonal: a half turn, folded flat
  const PaperState turned = client_.stateAt(base_ + 1);
  EXPECT_NE(turned.vertices_folded, before.vertices_folded);
  menu("Undo");
  const PaperState& undone = client_.stateAt(base_ + 2);
  EXPECT_EQ(undone.vertices_folded, before.vertices_folded);
  EXPECT_EQ(undone.edges, before.edges);
  menu("Redo");
  EXPECT_EQ(client_.stateAt(base_ + 3).vertices_folded, turned.vertices_folded);
}

TEST_F(Interaction, PressesThatChangeNothingCommitNothing)
{
  menu("Crease mode");
  drag(p3(0.3, 0.3), p3(0.3, 0.3), 1);  // a click
  expectUnchanged();
  menu("Rotate mode");
  drag(p3(0.3, 0.6), p3(0.5, 0.5), 4);  // an uncreased sheet has no axis
  expectUnchanged();
  EXPECT_FALSE(status_.message.empty());
  creaseDiagonal();
  drag(p3(0.8, 0.3), p3(0.9, 0.4), 4);  // along the axis: no turn
  expectUnchanged();
  drag(p3(1.05, 0.5), p3(0.5, 0.5), 4);  // on the margin, off the sheet
  expectUnchanged();
}

TEST_F(Interaction, MenuPinsAndReleasesTheNearestVertex)
{
  menu("Pin the nearest vertex", p3(0.97, 0.98));
  ASSERT_TRUE(waitFor([&] { return client_.state().pins.size() == 1; }));
  const PaperState& pinned = client_.state();
  EXPECT_EQ(creasePattern(pinned, pinned.pins[0].vertex), p3(1, 1));
  menu("Release the nearest pin", p3(0.95, 0.96));
  EXPECT_TRUE(waitFor([&] { return client_.state().pins.empty(); }));
}

/// The mark the interaction reports for a crease: π valley, −π mountain, 0 unfold; none unmarked.
std::optional<double> markOf(const InteractionStatus& status, int edge)
{
  for (size_t i = 0; i < status.marked_edges.size(); ++i)
    if (status.marked_edges[i] == edge)
      return status.marked_angles[i];
  return std::nullopt;
}

TEST_F(Interaction, FoldModeClicksCycleACreasesMarkAndFoldFlatFoldsOnIt)
{
  creaseDiagonal();
  menu("Fold mode");
  EXPECT_EQ(status_.mode, "fold");
  const PaperState before = client_.state();
  const int diagonal = creaseBetween(before, vertexAt(before, 0, 0), vertexAt(before, 1, 1));
  const std::vector<std::optional<double>> cycle{ M_PI, -M_PI, 0.0, std::nullopt, M_PI };
  for (const std::optional<double>& expected : cycle)
  {
    drag(p3(0.5, 0.5), p3(0.5, 0.5), 1);  // a click on the crease
    EXPECT_EQ(status_.picked_edge, diagonal);
    EXPECT_EQ(markOf(status_, diagonal), expected);
  }
  EXPECT_TRUE(shown_.count("marks"));
  // A click away from the creases picks the face that stays; the other half folds over it.
  drag(p3(0.8, 0.2), p3(0.8, 0.2), 1);
  ASSERT_GE(status_.picked_face, 0);
  expectUnchanged();
  menu("Fold flat");
  const PaperState& after = client_.stateAt(base_ + 1);
  EXPECT_NEAR(after.edges[diagonal].fold_angle, M_PI, 1e-9);
  for (size_t v = 0; v < after.vertices_folded.size(); ++v)
  {
    EXPECT_GE(after.vertices_folded[v].x - after.vertices_folded[v].y, -1e-9) << "vertex " << v;  // over the lower half
    EXPECT_NEAR(after.vertices_folded[v].z, 0.0, 1e-9);
  }
  EXPECT_TRUE(folded(after, vertexAt(after, 1, 0)).isApprox(p3(1, 0)));  // the face that stays
  EXPECT_TRUE(folded(after, vertexAt(after, 0, 1)).isApprox(p3(1, 0)));  // folded onto it
  ASSERT_TRUE(waitFor([&] { return status_.marked_edges.empty(); }, 5));  // the marks are used up
}

TEST_F(Interaction, CreasesThatDoNotFoldFlatAreRefusedAndNothingChanges)
{
  ASSERT_TRUE(client_.crease(0.5, 0, 0.5, 1).response.success);
  ASSERT_TRUE(client_.crease(0, 0.5, 1, 0.5).response.success);
  base_ += 2;
  client_.stateAt(base_);
  ASSERT_TRUE(waitFor([&] { return status_.revision == base_; }, 10));
  menu("Fold mode");
  drag(p3(0.75, 0.5), p3(0.75, 0.5), 1);  // one half of one line: the sheet would tear
  ASSERT_GE(status_.picked_edge, 0);
  drag(p3(0.2, 0.2), p3(0.2, 0.2), 1);
  ASSERT_GE(status_.picked_face, 0);
  said_ = {};
  menu("Fold flat");
  expectUnchanged();
  ASSERT_TRUE(waitFor([&] { return !said_.text.empty(); }, 5));
  EXPECT_NE(status_.message.find("fold"), std::string::npos) << status_.message;
  EXPECT_EQ(status_.marked_edges.size(), 1u);  // the marks stay, to be put right
  // Nothing marked: said so.
  menu("Clear the marks");
  EXPECT_TRUE(status_.marked_edges.empty());
  menu("Fold flat");
  expectUnchanged();
  EXPECT_NE(status_.message.find("No crease marked"), std::string::npos) << status_.message;
}

namespace
{
/// Whether the folded point `p` lies inside face `f` of a flat state (seen from above), by more
/// than `margin`.
bool insideFolded(const PaperState& s, int f, const core::Vec3& p, double margin = 1e-6)
{
  const auto& vs = s.faces[f].vertices;
  double area = 0.0;
  for (size_t i = 0; i < vs.size(); ++i)
  {
    const core::Vec3 a = folded(s, vs[i]), b = folded(s, vs[(i + 1) % vs.size()]);
    area += a.x() * b.y() - b.x() * a.y();
  }
  for (size_t i = 0; i < vs.size(); ++i)
  {
    const core::Vec3 a = folded(s, vs[i]), b = folded(s, vs[(i + 1) % vs.size()]);
    const double side = ((b - a).x() * (p - a).y() - (b - a).y() * (p - a).x()) / (b - a).norm();
    if ((area > 0 ? side : -side) <= margin)
      return false;
  }
  return true;
}

core::Vec3 foldedCentroid(const PaperState& s, int f)
{
  core::Vec3 c = core::Vec3::Zero();
  for (int v : s.faces[f].vertices)
    c += folded(s, v) / static_cast<double>(s.faces[f].vertices.size());
  return c;
}

/// Every two faces of a flat state that lie on each other have their order recorded; how many
/// such pairs there are.
int expectEveryStackedPairOrdered(const PaperState& s)
{
  std::set<std::pair<int, int>> ordered;
  for (const FaceOrder& o : s.face_orders)
    ordered.insert({ std::min(o.face, o.other), std::max(o.face, o.other) });
  int stacked = 0;
  for (size_t f = 0; f < s.faces.size(); ++f)
    for (size_t g = 0; g < s.faces.size(); ++g)
      if (f != g && insideFolded(s, static_cast<int>(g), foldedCentroid(s, static_cast<int>(f))))
      {
        ++stacked;
        EXPECT_TRUE(ordered.count({ std::min(f, g), std::max(f, g) })) << "faces " << f << " and " << g;
      }
  return stacked;
}
}  // namespace

TEST_F(Interaction, FoldFlatRefusesMarksNoPaperFoldsNamingTheVertexAndTheCreasesToChangeAndFollowedTheyFold)
{
  // Issue 42, finding 1: the creased square's midline halves and one diagonal marked valley
  // (six valleys, no mountain at the centre: Maekawa broken) folded "like" a square base.
  for (const auto& [x0, y0, x1, y1] :
       std::vector<std::array<double, 4>>{ { 0, 0, 1, 1 }, { 1, 0, 0, 1 }, { 0.5, 0, 0.5, 1 }, { 0, 0.5, 1, 0.5 } })
    ASSERT_TRUE(client_.crease(x0, y0, x1, y1).response.success);
  base_ += 4;
  const PaperState creased = client_.stateAt(base_);
  ASSERT_TRUE(waitFor([&] { return status_.revision == base_; }, 10));
  const int centre = vertexAt(creased, 0.5, 0.5);
  ASSERT_GE(centre, 0);
  menu("Fold mode");
  menu("Clear the marks");  // marks are kept by their place in the crease pattern, across resets
  const auto midpoint = [&](int e) -> core::Vec3 {
    return 0.5 * (creasePattern(creased, creased.edges[e].v0) + creasePattern(creased, creased.edges[e].v1));
  };
  std::set<int> marked;
  for (const core::Vec3& on :
       { p3(0.5, 0.25), p3(0.5, 0.75), p3(0.25, 0.5), p3(0.75, 0.5), p3(0.25, 0.25), p3(0.75, 0.75) })
  {
    drag(on, on, 1);  // one click: valley
    ASSERT_GE(status_.picked_edge, 0);
    EXPECT_EQ(markOf(status_, status_.picked_edge), M_PI);
    marked.insert(status_.picked_edge);
  }
  ASSERT_EQ(marked.size(), 6u);
  drag(p3(0.9, 0.6), p3(0.9, 0.6), 1);  // the face that stays
  ASSERT_GE(status_.picked_face, 0);
  said_ = {};
  menu("Fold flat");
  expectUnchanged();
  ASSERT_TRUE(waitFor([&] { return !said_.text.empty(); }, 5));
  // The refusal names the vertex and the creases to change by their places on the sheet (the
  // user sees no ids).
  const std::string refusal = status_.message;
  EXPECT_NE(refusal.find("the vertex at (0.5, 0.5)"), std::string::npos) << refusal;
  EXPECT_NE(refusal.find("Maekawa"), std::string::npos) << refusal;
  EXPECT_FALSE(std::regex_search(refusal, std::regex("(face|edge|vertex|crease) [0-9]"))) << refusal;
  EXPECT_EQ(status_.marked_edges.size(), 6u);  // the marks stay, to be put right
  // The creases it names, marked as it says, fold.
  const std::string number = "(-?[0-9.e-]+)";
  const std::regex named("the crease \\(" + number + ", " + number + "\\)–\\(" + number + ", " + number +
                         "\\) (mountain|valley)");
  const auto edgeBetween = [&](const core::Vec3& a, const core::Vec3& b) {
    for (int e : marked)
    {
      const core::Vec3 p = creasePattern(creased, creased.edges[e].v0), q = creasePattern(creased, creased.edges[e].v1);
      if (((p - a).norm() < 1e-3 && (q - b).norm() < 1e-3) || ((p - b).norm() < 1e-3 && (q - a).norm() < 1e-3))
        return e;
    }
    return -1;
  };
  std::map<int, double> told;
  for (auto it = std::sregex_iterator(refusal.begin(), refusal.end(), named); it != std::sregex_iterator(); ++it)
  {
    const int edge =
        edgeBetween(p3(std::stod((*it)[1]), std::stod((*it)[2])), p3(std::stod((*it)[3]), std::stod((*it)[4])));
    ASSERT_GE(edge, 0) << "the crease " << (*it)[0] << " is not one of the marked";
    told[edge] = (*it)[5] == "mountain" ? -M_PI : M_PI;
  }
  ASSERT_FALSE(told.empty()) << "no crease named to change: " << refusal;
  for (const auto& [edge, angle] : told)
  {
    for (int click = 0; click < 4 && markOf(status_, edge) != angle; ++click)
      drag(midpoint(edge), midpoint(edge), 1);
    ASSERT_EQ(markOf(status_, edge), angle);
  }
  drag(p3(0.9, 0.6), p3(0.9, 0.6), 1);
  menu("Fold flat");
  // Finding 2: the fold records the order of the layers it stacks.
  const PaperState& after = client_.stateAt(base_ + 1);
  for (int e : marked)
    EXPECT_NEAR(after.edges[e].fold_angle, told.count(e) ? told[e] : M_PI, 1e-9) << "crease " << e;
  for (const auto& v : after.vertices_folded)
    EXPECT_NEAR(v.z, 0.0, 1e-9);
  EXPECT_FALSE(after.face_orders.empty());
  EXPECT_GT(expectEveryStackedPairOrdered(after), 0);
}

TEST_F(Interaction, ReMarkingAFoldedCreaseAndFoldingFlatSwingsItsFlapToTheOtherSide)
{
  ASSERT_TRUE(client_.crease(0.5, 0, 0.5, 1).response.success);
  ++base_;
  client_.stateAt(base_);
  ASSERT_TRUE(waitFor([&] { return status_.revision == base_; }, 10));
  menu("Fold mode");
  menu("Clear the marks");
  drag(p3(0.5, 0.5), p3(0.5, 0.5), 1);  // valley
  const int crease = status_.picked_edge;
  ASSERT_GE(crease, 0);
  drag(p3(0.5, 0.5), p3(0.5, 0.5), 1);  // mountain
  ASSERT_EQ(markOf(status_, crease), -M_PI);
  drag(p3(0.2, 0.5), p3(0.2, 0.5), 1);  // the left half stays: the right one folds under it
  menu("Fold flat");
  const PaperState mountain = client_.stateAt(base_ + 1);
  ASSERT_NEAR(mountain.edges[crease].fold_angle, -M_PI, 1e-9);
  ASSERT_EQ(mountain.face_orders.size(), 1u);
  ASSERT_TRUE(waitFor([&] { return status_.revision == base_ + 1 && status_.marked_edges.empty(); }, 10));
  // Issue 42, finding 1: the folded crease re-marked valley was refused ("moves nothing").
  drag(p3(0.5, 0.5), p3(0.5, 0.5), 1);
  ASSERT_EQ(status_.picked_edge, crease);
  ASSERT_EQ(markOf(status_, crease), M_PI);
  drag(p3(0.25, 0.5), p3(0.25, 0.5), 1);  // the top layer stays: the other swings round it
  ASSERT_GE(status_.picked_face, 0);
  menu("Fold flat");
  const PaperState& valley = client_.stateAt(base_ + 2);
  EXPECT_NEAR(valley.edges[crease].fold_angle, M_PI, 1e-9);
  for (size_t v = 0; v < valley.vertices_folded.size(); ++v)  // the same place, the other side
    EXPECT_LT((folded(valley, static_cast<int>(v)) - folded(mountain, static_cast<int>(v))).norm(), 1e-9);
  ASSERT_EQ(valley.face_orders.size(), 1u);
  const FaceOrder &was = mountain.face_orders[0], &now = valley.face_orders[0];
  EXPECT_EQ(now.face == was.face ? now.above : -now.above, -was.above) << "the layers did not swap";
}

TEST_F(Interaction, NextLayerDownPicksTheLayersOfAStackInTurnAndSaysWhenThereIsNoneBelow)
{
  menu("Rotate mode");
  menu("Next layer down", p3(0.3, 0.3));  // one sheet: no layer below
  EXPECT_NE(status_.message.find("No layer below this one"), std::string::npos) << status_.message;
  quarterFold();
  std::set<int> faces;
  std::map<uint32_t, int> face_of_layer;
  for (uint32_t layer = 2; layer <= 4; ++layer)
  {
    menu("Next layer down", p3(0.25, 0.2));
    EXPECT_EQ(status_.layers, 4u);
    EXPECT_EQ(status_.picked_layer, layer);
    faces.insert(status_.picked_face);
    face_of_layer[layer] = status_.picked_face;
  }
  EXPECT_EQ(faces.size(), 3u);
  EXPECT_TRUE(shown_.count("pick"));
  menu("Next layer down", p3(0.25, 0.2));
  EXPECT_NE(status_.message.find("No layer below this one"), std::string::npos) << status_.message;
  EXPECT_EQ(status_.picked_layer, 4u);
  // And back up through the same faces to the top one (none of them), which has none above it.
  for (uint32_t layer = 3; layer >= 2; --layer)
  {
    menu("Next layer up", p3(0.25, 0.2));
    EXPECT_EQ(status_.picked_layer, layer);
    EXPECT_EQ(status_.picked_face, face_of_layer[layer]);
  }
  menu("Next layer up", p3(0.25, 0.2));
  EXPECT_EQ(status_.picked_layer, 1u);
  EXPECT_EQ(faces.count(status_.picked_face), 0u);
  menu("Next layer up", p3(0.25, 0.2));
  EXPECT_NE(status_.message.find("No layer above this one"), std::string::npos) << status_.message;
  EXPECT_EQ(status_.picked_layer, 1u);
  expectUnchanged();
}

TEST_F(Interaction, APressOnAPickedLayerTurnsThatLayerAndTheToggleTurnsItAlone)
{
  quarterFold();
  ros::Subscriber ops = client_.nh().subscribe<Operation>(
      "operations", 10, [&](const Operation::ConstPtr& op) { operations_.push_back(*op); });
  ASSERT_TRUE(waitFor([&] { return ops.getNumPublishers() > 0; }, 10));
  menu("Rotate mode");
  menu("Turn the picked layers only");
  menu("Next layer down", p3(0.25, 0.1));
  const int picked = status_.picked_face;
  ASSERT_GE(picked, 0);
  drag(p3(0.25, 0.1), p3(0.25, 0.3), 8);  // lifted about the crease y = .5
  client_.stateAt(base_ + 1);
  ASSERT_TRUE(waitFor([&] { return !operations_.empty(); }, 10));
  EXPECT_EQ(operations_.back().type, "rotate");
  EXPECT_EQ(operations_.back().face, picked);
  EXPECT_TRUE(operations_.back().picked_layers_only);
}

TEST_F(Interaction, DragModeDragsAVertexThePinHoldsAndADragNoShapeFollowsIsRefused)
{
  ASSERT_TRUE(client_.call<PinVertex>("pin", [] {
                       PinVertex::Request r;
                       r.vertex = 0;
                       return r;
                     }())
                  .response.success);
  ASSERT_TRUE(waitFor([&] { return client_.state().pins.size() == 1; }));
  const PaperState before = client_.state();
  const int pinned = before.pins[0].vertex;
  const core::Vec3 anchor = folded(before, pinned);
  // The corner across the sheet from the pin, turned 10° about it in the sheet's plane.
  int corner = -1;
  for (size_t v = 0; v < before.vertices_folded.size(); ++v)
    if ((folded(before, static_cast<int>(v)) - anchor).norm() > 1.4)
      corner = static_cast<int>(v);
  ASSERT_GE(corner, 0);
  const core::Vec3 from = folded(before, corner);
  const Eigen::AngleAxisd turn(10 * M_PI / 180, core::Vec3::UnitZ());
  const core::Vec3 to = anchor + turn * (from - anchor);
  menu("Drag mode");
  EXPECT_EQ(status_.mode, "drag");
  const uint64_t pinned_revision = client_.state().revision;
  base_ = pinned_revision;
  drag(from, to, 10);
  const PaperState& after = client_.stateAt(base_ + 1);
  EXPECT_LT((folded(after, corner) - to).norm(), 1e-6);
  EXPECT_LT((folded(after, pinned) - anchor).norm(), 1e-9);
  for (const Edge& e : after.edges)  // the sheet keeps its shape
    EXPECT_NEAR((folded(after, e.v0) - folded(after, e.v1)).norm(),
                (creasePattern(after, e.v0) - creasePattern(after, e.v1)).norm(), 1e-6);
  // Towards the pin: no flat sheet of this shape reaches there.
  ++base_;
  said_ = {};
  drag(to, anchor + 0.8 * (to - anchor), 6);
  expectUnchanged();
  ASSERT_TRUE(waitFor([&] { return !said_.text.empty(); }, 5));
  // A press on nothing: said, nothing changed.
  drag(p3(0.5, 0.5), p3(0.6, 0.6), 4);
  expectUnchanged();
  EXPECT_NE(status_.message.find("No vertex here"), std::string::npos) << status_.message;
}

TEST_F(Interaction, AHalfTurnDraggedToOneDegreeShortIsExactlyAHalfTurnAndTheNextFoldsFlat)
{
  creaseDiagonal();
  menu("Rotate mode");
  // Issue 42, finding 4: dragged exactly to the mirror image it stopped at 179°. From above the
  // angle follows the pointer's distance from the axis: at 179°, 1/90 of the press's distance
  // short of the mirror image.
  const core::Vec3 press = p3(0.8, 0.3), foot = p3(0.55, 0.55);
  drag(press, foot + (1.0 - 2.0 * 179.0 / 180.0) * (press - foot), 12);
  const PaperState& turned = client_.stateAt(base_ + 1);
  const int diagonal = creaseBetween(turned, vertexAt(turned, 0, 0), vertexAt(turned, 1, 1));
  ASSERT_GE(diagonal, 0);
  EXPECT_NEAR(std::abs(turned.edges[diagonal].fold_angle), M_PI, 1e-9);
  for (const auto& v : turned.vertices_folded)
    EXPECT_NEAR(v.z, 0.0, 1e-9);
  ++base_;
  ASSERT_TRUE(waitFor([&] { return status_.revision == base_; }, 10));
  // The next half turn, of the triangle's two layers about the other diagonal, folds flat (at
  // 179° it crumpled the model).
  ASSERT_TRUE(client_.crease(1, 0, 0, 1).response.success);
  ++base_;
  const PaperState creased = client_.stateAt(base_);
  ASSERT_TRUE(waitFor([&] { return status_.revision == base_; }, 10));
  drag(p3(0.25, 0.75), p3(0.25, 0.75), 1);  // a click on the new crease names it the axis
  ASSERT_NE(status_.message.find("axis"), std::string::npos) << status_.message;
  const core::Vec3 second = p3(0.15, 0.6), over = p3(0.275, 0.725);  // its foot on x + y = 1
  drag(second, over + 1.2 * (over - second), 12);
  ASSERT_TRUE(waitFor([&] { return client_.state().revision == base_ + 1; }, 10)) << status_.message;
  const PaperState& quarter = client_.stateAt(base_ + 1);
  for (const auto& v : quarter.vertices_folded)
    EXPECT_NEAR(v.z, 0.0, 1e-9);
  for (const Edge& e : quarter.edges)  // the sheet keeps its shape
    EXPECT_NEAR((folded(quarter, e.v0) - folded(quarter, e.v1)).norm(),
                (creasePattern(quarter, e.v0) - creasePattern(quarter, e.v1)).norm(), 1e-9);
  EXPECT_FALSE(quarter.face_orders.empty());
  EXPECT_GT(expectEveryStackedPairOrdered(quarter), 0);
  EXPECT_NE(quarter.vertices_folded, creased.vertices_folded);
}

TEST_F(Interaction, AFloodOfPosesIsCoalescedAndTheLatestApplied)
{
  creaseDiagonal();
  menu("Rotate mode");
  max_pending_ = 0;
  gesture_.press = p3(0.8, 0.3);
  send(gesture_.down(ros::Time::now()));
  ASSERT_TRUE(waitFor([&] { return status_.dragging; }, 5));
  // 1000 poses as fast as they go, ending over the axis.
  const int n = 1000;
  ros::Time last;
  for (int i = 1; i <= n; ++i)
  {
    last = ros::Time::now();
    const double t = static_cast<double>(i) / n;
    send(gesture_.moveTo(p3(0.8 - 0.25 * t, 0.3 + 0.25 * t), last));
  }
  ASSERT_TRUE(waitFor([&] { return status_.applied_stamp == last; }, 10)) << "the latest pose was not applied";
  EXPECT_GT(status_.feedback_coalesced, 0u);
  EXPECT_LT(status_.updates_applied, static_cast<uint64_t>(n));
  EXPECT_LE(max_pending_, 2u);  // one press and one pose at most: poses replace each other
  EXPECT_EQ(client_.state().revision, base_);
  send(gesture_.upAt(p3(0.55, 0.55), ros::Time::now()));
  settle();
  const PaperState& after = client_.stateAt(base_ + 1);
  const int axis = creaseBetween(after, vertexAt(after, 0, 0), vertexAt(after, 1, 1));
  EXPECT_NEAR(after.edges[axis].fold_angle, M_PI / 2, 1e-6);
}

namespace
{
/// Where the sight line through `point` meets the table (z = 0).
core::Vec3 onTable(const ViewCamera& c, const core::Vec3& point)
{
  const core::Vec3 ray = point - c.eye;
  return c.eye + (-c.eye.z() / ray.z()) * ray;
}
}  // namespace

TEST(ViewTurn, KeepsThePressInItsPlaceLevelAndSeesTheAxisFromTheSide)
{
  const ViewCamera view = defaultView();
  const core::Vec3 press(0.8, 0.8, 0), centre(2.0 / 3, 2.0 / 3, 0);
  const core::Vec3 across = core::Vec3(-1, 1, 0).normalized();  // the anti-diagonal: seen edge-on from here
  ASSERT_LT(std::abs(view.rayTo(press).dot(across)), 0.5);
  const std::optional<ViewCamera> turned = turnedView(view, press, centre, across);
  ASSERT_TRUE(turned.has_value());
  EXPECT_GE(std::abs(turned->rayTo(press).dot(across)), 0.6);
  EXPECT_NEAR(turned->axes.col(0).z(), 0.0, 1e-12);  // level: an orbit view has no roll
  EXPECT_TRUE((turned->axes.transpose() * turned->axes).isIdentity(1e-12));
  EXPECT_NEAR(turned->axes.determinant(), 1.0, 1e-12);
  const core::Vec3 before = view.axes.transpose() * (press - view.eye);
  const core::Vec3 after = turned->axes.transpose() * (press - turned->eye);
  EXPECT_TRUE(after.isApprox(before, 1e-12)) << after.transpose() << " / " << before.transpose();
  EXPECT_GT(turned->eye.z(), 0.0);
  // Seen from the side already: no turn.
  EXPECT_FALSE(turnedView(view, press, centre, core::Vec3(1, 1, 0).normalized()).has_value());
}

TEST(ViewTurn, SightLinesOntoAPlane)
{
  const ViewCamera view = defaultView();
  const std::optional<core::Vec3> hit =
      alongSightOnto(view, core::Vec3(0.3, 0.2, 0.5), core::Vec3(0, 0, 0), core::Vec3::UnitZ());
  ASSERT_TRUE(hit.has_value());
  EXPECT_NEAR(hit->z(), 0.0, 1e-12);
  EXPECT_NEAR((*hit - view.eye).normalized().dot(view.rayTo(core::Vec3(0.3, 0.2, 0.5))), 1.0, 1e-12);
  // A plane behind the eye is not seen.
  EXPECT_FALSE(alongSightOnto(view, view.eye + view.forward(), view.eye - view.forward(), view.forward()).has_value());
}

TEST_F(InteractionSeen, TheTurningFaceFollowsThePointersSightLine)
{
  creaseDiagonal();
  menu("Rotate mode");
  // Issue 23: in this view the pointer was 237 px from the point it turned (a view from above
  // assumed). The press (0.8, 0.3) turned 60° about the diagonal lies on the sight line
  // through the pointer: drag to where that line meets the table.
  const core::Vec3 press = p3(0.8, 0.3), centre = p3(0.55, 0.55);
  const core::Vec3 out = (press - centre).normalized();
  const core::Vec3 turned =
      centre + (press - centre).norm() * (std::cos(M_PI / 3) * out + std::sin(M_PI / 3) * core::Vec3::UnitZ());
  drag(press, onTable(view_, turned), 10);
  const PaperState& after = client_.stateAt(base_ + 1);
  const int axis = creaseBetween(after, vertexAt(after, 0, 0), vertexAt(after, 1, 1));
  ASSERT_GE(axis, 0);
  EXPECT_NEAR(after.edges[axis].fold_angle, M_PI / 3, 1e-6);
  EXPECT_TRUE(turns_.empty());  // seen from the side: no view turn
}

TEST_F(InteractionSeen, ACreaseTakesTheEyePoint)
{
  menu("Crease mode");
  drag(p3(0.012, 0.018), p3(0.986, 0.991), 10);
  client_.stateAt(base_ + 1);
  ASSERT_TRUE(waitFor([&] { return !operations_.empty() && operations_.back().type == "crease"; }, 5));
  const Operation& op = operations_.back();
  EXPECT_TRUE(op.has_eye);
  EXPECT_NEAR((toVec3(op.eye) - view_.eye).norm(), 0.0, 1e-6);
  EXPECT_NEAR((toVec3(op.start) - p3(0, 0)).norm(), 0.0, 1e-12);  // snapped to the corners
  EXPECT_NEAR((toVec3(op.end) - p3(1, 1)).norm(), 0.0, 1e-12);
}

TEST_F(InteractionSeen, ALineFromTheMarginIsDrawnOnTheTable)
{
  menu("Crease mode");
  // Pressed just off the corner (on the margin) and released near the opposite corner: both
  // ends snap to the corners on the table, not to points on the drag plane in the air.
  drag(p3(-0.02, -0.015), p3(0.985, 0.99), 10);
  const PaperState& state = client_.stateAt(base_ + 1);
  ASSERT_GE(creaseBetween(state, vertexAt(state, 0, 0), vertexAt(state, 1, 1)), 0);
  EXPECT_EQ(state.vertices_crease_pattern.size(), 4u);
  EXPECT_EQ(state.faces.size(), 2u);
}

TEST_F(InteractionSeen, SeenEdgeOnTheViewTurnsForTheDragAndBack)
{
  ASSERT_TRUE(client_.crease(1, 0, 0, 1).response.success);  // across this view's line of sight
  ++base_;
  ASSERT_TRUE(waitFor([&] { return status_.revision == base_; }, 10));
  menu("Rotate mode");
  turns_.clear();
  const core::Vec3 press = p3(0.8, 0.8);
  drag(press, p3(0.78, 0.75), 4, [&] {
    ASSERT_TRUE(waitFor([&] { return !turns_.empty(); }, 5)) << "no view turn";
    const geometry_msgs::PoseStamped& goal = turns_.front();
    EXPECT_EQ(goal.header.frame_id, "paper");
    ViewCamera turned;
    turned.eye = toVec3(goal.pose.position);
    turned.axes = Eigen::Quaterniond(goal.pose.orientation.w, goal.pose.orientation.x, goal.pose.orientation.y,
                                     goal.pose.orientation.z)
                      .toRotationMatrix();
    const core::Vec3 across = core::Vec3(-1, 1, 0).normalized();
    EXPECT_GE(std::abs(turned.rayTo(press).dot(across)), 0.6);  // the axis seen from the side
    // The press stays under the mouse: its place in the camera's coordinates is kept.
    EXPECT_TRUE(
        (turned.axes.transpose() * (press - turned.eye)).isApprox(view_.axes.transpose() * (press - view_.eye), 1e-4));
  });
  ASSERT_TRUE(waitFor([&] { return turns_.size() >= 2; }, 5));
  EXPECT_EQ(turns_.back().header.frame_id, "");  // back to the view before the turn on release
}

TEST_F(InteractionSeen, SeenEdgeOnFromALowObliqueViewTheViewTurnsToo)
{
  ASSERT_TRUE(client_.crease(0.5, 0, 0.5, 1).response.success);
  ++base_;
  ASSERT_TRUE(waitFor([&] { return status_.revision == base_; }, 10));
  menu("Rotate mode");
  // Issue 42, finding 4: low and oblique, the face's centre straight behind the press along the
  // sight line, the edge-on ring got no view turn (a drag meant for 90° turned 114°).
  const core::Vec3 press = p3(0.4, 0.5), across = core::Vec3::UnitY();
  const core::Vec3 eye(-3.0, 0.5, 0.6);
  const core::Vec3 forward = (press - eye).normalized();
  const core::Vec3 right = forward.cross(core::Vec3::UnitZ()).normalized();
  view_.eye = eye;
  view_.axes.col(0) = right;
  view_.axes.col(1) = forward.cross(right);
  view_.axes.col(2) = forward;
  gesture_.eye = eye;
  ASSERT_LT(std::abs(view_.rayTo(press).dot(across)), 0.6);  // edge-on from here
  ros::WallDuration(0.5).sleep();                            // the node knows the new view
  ros::spinOnce();
  turns_.clear();
  drag(press, p3(0.38, 0.5), 4, [&] {
    ASSERT_TRUE(waitFor([&] { return !turns_.empty(); }, 5)) << "no view turn";
    const geometry_msgs::PoseStamped& goal = turns_.front();
    EXPECT_EQ(goal.header.frame_id, "paper");
    ViewCamera turned;
    turned.eye = toVec3(goal.pose.position);
    turned.axes = Eigen::Quaterniond(goal.pose.orientation.w, goal.pose.orientation.x, goal.pose.orientation.y,
                                     goal.pose.orientation.z)
                      .toRotationMatrix();
    EXPECT_GE(std::abs(turned.rayTo(press).dot(across)), 0.6);  // the axis seen from the side
    EXPECT_NEAR(turned.axes.col(0).z(), 0.0, 1e-6);             // level
    EXPECT_GT(turned.eye.z(), 0.0);
    EXPECT_TRUE(
        (turned.axes.transpose() * (press - turned.eye)).isApprox(view_.axes.transpose() * (press - view_.eye), 1e-4));
  });
  ASSERT_TRUE(waitFor([&] { return turns_.size() >= 2; }, 5));
  EXPECT_EQ(turns_.back().header.frame_id, "");  // back to the view before the turn
}

int main(int argc, char** argv)
{
  ::testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "interaction_rostest");
  ros::NodeHandle nh;
  return RUN_ALL_TESTS();
}

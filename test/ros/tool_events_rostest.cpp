// rostest: the interaction node driven through the Fold tool's interface, as the rviz tool
// virtual_origami/Fold drives it (ToolEvent on `tool_events`, each with the line of sight through
// the mouse), checked on `state` and `interaction_status`: the wheel, Tab and Shift+Tab walk the
// layers of a square base down and up, clicks mark creases and Enter or a double click folds on
// them, Ctrl+Z and Ctrl+Y undo and redo, Esc cancels a drag, number keys choose the mode.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include <nlohmann/json.hpp>
#include <virtual_origami/FlatFold.h>
#include <virtual_origami/Load.h>
#include <virtual_origami/ToolEvent.h>

#include "interaction_fixture.h"
#include "virtual_origami/core/data_folder.h"
#include "virtual_origami/core/fold_sequence.h"
#include "virtual_origami/core/layer_pick.h"

using namespace virtual_origami;
using namespace virtual_origami::test;

namespace
{
/// Looking straight down from 2 m over the sheet's centre (x right, y down, z along the sight).
ViewCamera fromAbove()
{
  ViewCamera c;
  c.eye = p3(0.5, 0.5, 2.0);
  c.axes.col(0) = p3(1, 0, 0);
  c.axes.col(1) = p3(0, -1, 0);
  c.axes.col(2) = p3(0, 0, -1);
  return c;
}

std::optional<double> markOf(const InteractionStatus& status, int edge)
{
  for (size_t i = 0; i < status.marked_edges.size(); ++i)
    if (status.marked_edges[i] == edge)
      return status.marked_angles[i];
  return std::nullopt;
}

class ToolEvents : public InteractionFixture
{
protected:
  void SetUp() override
  {
    tool_pub_ = client_.nh().advertise<ToolEvent>("tool_events", 100);
    InteractionFixture::SetUp();
    ASSERT_TRUE(waitFor([&] { return tool_pub_.getNumSubscribers() > 0; }, 30));
  }

  /// An event with the line of sight from the camera through `at` (in the world frame, which
  /// tf relates to the paper's).
  ToolEvent event(uint8_t kind, const core::Vec3& at) const
  {
    ToolEvent e;
    e.header.stamp = ros::Time::now();
    e.header.frame_id = "world";
    e.kind = kind;
    e.eye = toPoint(camera_.eye);
    const Eigen::Quaterniond q(camera_.axes);
    e.camera.w = q.w();
    e.camera.x = q.x();
    e.camera.y = q.y();
    e.camera.z = q.z();
    const core::Vec3 ray = at - camera_.eye;
    e.ray.x = ray.x();
    e.ray.y = ray.y();
    e.ray.z = ray.z();
    return e;
  }

  void send(const ToolEvent& e)
  {
    tool_pub_.publish(e);
    ros::spinOnce();
  }
  void sendAndSettle(const ToolEvent& e)
  {
    send(e);
    settle();
  }

  void key(const std::string& name, uint8_t modifiers = 0, bool auto_repeat = false,
           const core::Vec3& at = p3(0.5, 0.5))
  {
    ToolEvent e = event(ToolEvent::KEY, at);
    e.key = name;
    e.modifiers = modifiers;
    e.auto_repeat = auto_repeat;
    sendAndSettle(e);
  }

  void wheel(const core::Vec3& at, int delta = -120)
  {
    ToolEvent e = event(ToolEvent::WHEEL, at);
    e.wheel_delta = delta;
    sendAndSettle(e);
  }

  /// Press at `from`, move through `steps` points to `to`; `release`: let go there.
  void drag(const core::Vec3& from, const core::Vec3& to, int steps, bool release = true)
  {
    send(event(ToolEvent::PRESS, from));
    for (int i = 1; i <= steps; ++i)
    {
      ros::WallDuration(0.02).sleep();
      send(event(ToolEvent::MOVE, from + (to - from) * (static_cast<double>(i) / steps)));
    }
    if (release)
    {
      send(event(ToolEvent::RELEASE, to));
      settle();
    }
  }
  void click(const core::Vec3& at)
  {
    drag(at, at, 0);
  }

  /// The square base (sequences/crane.json's first eight steps) through the services.
  void squareBase()
  {
    std::string path;
    ASSERT_TRUE(ros::param::get("~crane", path));
    std::ifstream file(path);
    std::stringstream text;
    text << file.rdbuf();
    const core::Expected<core::FoldSequence> crane = core::parseFoldSequence(text.str());
    ASSERT_TRUE(crane.ok()) << crane.message();
    for (size_t i = 0; i < 8; ++i)
    {
      const core::Operation& op = crane->steps[i].operation;
      bool done = false;
      std::string said;
      if (op.kind == core::Operation::Kind::Crease)
      {
        const Crease c = client_.crease(op.crease.start.x(), op.crease.start.y(), op.crease.end.x(), op.crease.end.y());
        done = c.response.success;
        said = c.response.message;
      }
      else if (op.kind == core::Operation::Kind::Rotate)
      {
        const Rotate r = client_.rotate(op.rotate.face, op.rotate.axis_edge, op.rotate.click.x(), op.rotate.click.y(),
                                        op.rotate.angle);
        done = r.response.success;
        said = r.response.message;
      }
      else
      {
        FlatFold::Request r;
        for (const core::CreaseLineAngle& line : op.flat_fold.creases)
        {
          r.starts.push_back(toPoint(p3(line.start.x(), line.start.y())));
          r.ends.push_back(toPoint(p3(line.end.x(), line.end.y())));
          r.angles.push_back(line.angle);
        }
        r.fixed = toPoint(p3(op.flat_fold.fixed_point.x(), op.flat_fold.fixed_point.y()));
        r.commit = true;
        const FlatFold f = client_.call<FlatFold>("flat_fold", r);
        done = f.response.success;
        said = f.response.message;
      }
      ASSERT_TRUE(done) << "step " << i << ": " << said;
    }
    base_ += 8;
    client_.stateAt(base_);
    ASSERT_TRUE(waitFor([&] { return status_.revision == base_; }, 10));
  }

  ros::Publisher tool_pub_;
  ViewCamera camera_ = fromAbove();
};
}  // namespace

TEST_F(ToolEvents, NumberKeysChooseTheModeAndTheHintSaysWhatAClickDoes)
{
  const std::vector<std::pair<std::string, std::string>> modes{
    { "3", "fold" }, { "4", "drag" }, { "5", "flap" }, { "2", "rotate" }, { "1", "crease" }
  };
  for (const auto& [k, mode] : modes)
  {
    key(k);
    EXPECT_EQ(status_.mode, mode) << "key " << k;
    std::string title = mode;
    title[0] = static_cast<char>(std::toupper(title[0]));
    EXPECT_EQ(status_.hint.rfind(title + " mode: ", 0), 0u) << status_.hint;
  }
  EXPECT_NE(status_.hint.find("drag a line"), std::string::npos) << status_.hint;
  EXPECT_NE(status_.hint.find("Ctrl+Z undo"), std::string::npos) << status_.hint;
  key("3", ToolEvent::ALT);  // not a mode key
  key("A");
  EXPECT_EQ(status_.mode, "crease");
  expectUnchanged();
}

TEST_F(ToolEvents, TheWheelAndTabWalkTheLayersOfASquareBaseDownAndShiftTabAndTheWheelBackUp)
{
  squareBase();
  const core::Expected<core::Paper> paper = fromMessage(client_.state());
  ASSERT_TRUE(paper.ok()) << paper.message();
  // The most layers under a point of a 4×4 grid over the base, seen from above, away from the creases.
  core::Vec3 at = p3(0, 0);
  size_t most = 0;
  for (double x = 0.03; x < 1.0; x += 0.0625)
    for (double y = 0.03; y < 1.0; y += 0.0625)
    {
      const size_t n = core::facesUnder(*paper, p3(x, y, 1.0), p3(0, 0, -1)).size();
      if (n > most)
      {
        most = n;
        at = p3(x, y);
      }
    }
  ASSERT_GE(most, 4u) << "no stack in the square base";
  key("2");  // rotate mode picks faces
  // Above the top layer nothing: a click there picks the top one.
  wheel(at, -120);
  EXPECT_NE(status_.message.find("No layer above this one"), std::string::npos) << status_.message;
  EXPECT_EQ(status_.picked_layer, 0u);
  std::map<uint32_t, int> face_of;
  for (uint32_t layer = 2; layer <= most; ++layer)
  {
    if (layer % 2)
      key("Tab", 0, layer > 3, at);  // a held Tab repeats
    else
      wheel(at, 120);  // turned away from the user: down
    EXPECT_EQ(status_.layers, most);
    EXPECT_EQ(status_.picked_layer, layer);
    face_of[layer] = status_.picked_face;
  }
  std::set<int> below;
  for (const auto& [layer, face] : face_of)
    below.insert(face);
  EXPECT_EQ(below.size(), most - 1) << "a face of its own in each layer";
  wheel(at, 120);
  EXPECT_NE(status_.message.find("No layer below this one"), std::string::npos) << status_.message;
  EXPECT_EQ(status_.picked_layer, most);
  EXPECT_NE(status_.hint.find("Layer " + std::to_string(most) + " of " + std::to_string(most)), std::string::npos)
      << status_.hint;
  // Back up: the wheel towards the user, Shift+Tab (Qt names it Backtab, Shift held; a Tab with
  // Shift is the same), through the same faces to the top.
  for (uint32_t layer = most - 1; layer >= 1; --layer)
  {
    if (layer % 3 == 0)
      wheel(at, -120);
    else
      key(layer % 3 == 1 ? "Backtab" : "Tab", ToolEvent::SHIFT, layer < most - 1, at);  // held, it repeats
    EXPECT_EQ(status_.picked_layer, layer);
    if (layer > 1)
      EXPECT_EQ(status_.picked_face, face_of[layer]) << "layer " << layer;
  }
  EXPECT_NE(status_.hint.find("Layer 1 of " + std::to_string(most)), std::string::npos) << status_.hint;
  EXPECT_NE(status_.message.find("Picked layer 1 of"), std::string::npos) << status_.message;
  const int top = status_.picked_face;
  EXPECT_GE(top, 0);
  EXPECT_EQ(below.count(top), 0u) << "the top layer is none of those below";
  wheel(at, -120);
  EXPECT_NE(status_.message.find("No layer above this one"), std::string::npos) << status_.message;
  EXPECT_EQ(status_.picked_layer, 1u);
  EXPECT_EQ(status_.picked_face, top);
  // Off the paper and its margin the wheel picks nothing and lets go of nothing.
  wheel(p3(3, 3));
  EXPECT_NE(status_.message.find("Nothing under the pointer"), std::string::npos) << status_.message;
  EXPECT_EQ(status_.picked_layer, 1u);
  expectUnchanged();
}

TEST_F(ToolEvents, ClicksMarkEnterFoldsCtrlZUndoesCtrlYRedoes)
{
  creaseDiagonal();
  key("3");
  const PaperState before = client_.state();
  const int diagonal = creaseBetween(before, vertexAt(before, 0, 0), vertexAt(before, 1, 1));
  click(p3(0.5, 0.5));
  EXPECT_EQ(status_.picked_edge, diagonal);
  EXPECT_EQ(markOf(status_, diagonal), M_PI);
  EXPECT_NE(status_.hint.find("1 crease marked"), std::string::npos) << status_.hint;
  click(p3(0.8, 0.2));  // the face that stays
  ASSERT_GE(status_.picked_face, 0);
  EXPECT_NE(status_.hint.find("Enter or a double click folds"), std::string::npos) << status_.hint;
  key("Return", 0, true);  // a held Enter's repeat folds nothing
  expectUnchanged();
  key("Return");
  const PaperState folded_once = client_.stateAt(base_ + 1);
  EXPECT_NEAR(folded_once.edges[diagonal].fold_angle, M_PI, 1e-9);
  EXPECT_TRUE(folded(folded_once, vertexAt(folded_once, 0, 1)).isApprox(p3(1, 0)));
  ASSERT_TRUE(waitFor([&] { return status_.revision == base_ + 1; }, 10));
  key("Z", ToolEvent::CONTROL, true);  // a held Ctrl+Z's repeat undoes nothing
  ros::WallDuration(0.5).sleep();
  EXPECT_EQ(client_.state().revision, base_ + 1);
  key("Z", ToolEvent::CONTROL);
  const PaperState& undone = client_.stateAt(base_ + 2);
  EXPECT_NEAR(undone.edges[diagonal].fold_angle, 0.0, 1e-9);
  EXPECT_TRUE(folded(undone, vertexAt(undone, 0, 1)).isApprox(p3(0, 1)));
  key("Y", ToolEvent::CONTROL);
  const PaperState& redone = client_.stateAt(base_ + 3);
  EXPECT_NEAR(redone.edges[diagonal].fold_angle, M_PI, 1e-9);
  key("Z", ToolEvent::CONTROL);
  client_.stateAt(base_ + 4);
  key("Z", ToolEvent::CONTROL | ToolEvent::SHIFT);  // Ctrl+Shift+Z redoes too
  EXPECT_NEAR(client_.stateAt(base_ + 5).edges[diagonal].fold_angle, M_PI, 1e-9);
}

TEST_F(ToolEvents, ADoubleClickOnTheFaceThatStaysFoldsTheMarkedCreases)
{
  creaseDiagonal();
  key("3");
  const PaperState before = client_.state();
  const int diagonal = creaseBetween(before, vertexAt(before, 0, 0), vertexAt(before, 1, 1));
  click(p3(0.5, 0.5));
  ASSERT_EQ(markOf(status_, diagonal), M_PI);
  click(p3(0.2, 0.8));  // the double click's first click picks the face that stays
  sendAndSettle(event(ToolEvent::DOUBLE_CLICK, p3(0.2, 0.8)));
  const PaperState& after = client_.stateAt(base_ + 1);
  EXPECT_NEAR(after.edges[diagonal].fold_angle, M_PI, 1e-9);
  EXPECT_TRUE(folded(after, vertexAt(after, 0, 1)).isApprox(p3(0, 1)));  // the face that stays
  EXPECT_TRUE(folded(after, vertexAt(after, 1, 0)).isApprox(p3(0, 1)));  // folded onto it
}

TEST_F(ToolEvents, ADragCreasesAsTheSheetMarkersDragDoesFromAnObliqueView)
{
  camera_ = defaultView();
  key("1");
  // Near, not on, the corners: snapping lands on them. Guides show while dragging.
  drag(p3(0.012, 0.018), p3(0.986, 0.991), 10, false);
  EXPECT_TRUE(waitFor([&] { return status_.dragging && shown_.count("line") && shown_.count("end_snap"); }, 5));
  EXPECT_NE(status_.hint.find("Esc cancels"), std::string::npos) << status_.hint;
  EXPECT_EQ(client_.state().revision, base_);  // nothing committed while dragging
  sendAndSettle(event(ToolEvent::RELEASE, p3(0.986, 0.991)));
  const PaperState& state = client_.stateAt(base_ + 1);
  const int a = vertexAt(state, 0, 0), b = vertexAt(state, 1, 1);
  ASSERT_GE(a, 0);
  ASSERT_GE(b, 0);
  EXPECT_GE(creaseBetween(state, a, b), 0);
  EXPECT_EQ(guidesShown(), 0u);
}

TEST_F(ToolEvents, EscCancelsADragAndNothingIsCommitted)
{
  key("1");
  drag(p3(0.1, 0.1), p3(0.9, 0.8), 8, false);
  ASSERT_TRUE(waitFor([&] { return status_.dragging && shown_.count("line"); }, 5));
  key("Esc");
  EXPECT_FALSE(status_.dragging);
  EXPECT_EQ(guidesShown(), 0u);
  EXPECT_NE(status_.message.find("Cancelled"), std::string::npos) << status_.message;
  sendAndSettle(event(ToolEvent::RELEASE, p3(0.9, 0.8)));  // the release after it is nothing
  expectUnchanged();
  // A turn let go by the tool (put away mid-drag): the preview goes, nothing is committed.
  creaseDiagonal();
  key("2");
  drag(p3(0.2, 0.7), p3(0.2, 0.7) + p3(0.0, 0.0, 0.3), 8, false);
  ASSERT_TRUE(waitFor([&] { return status_.dragging && status_.updates_applied > 0; }, 5));
  sendAndSettle(event(ToolEvent::CANCEL, p3(0.2, 0.7)));
  EXPECT_FALSE(status_.dragging);
  EXPECT_EQ(status_.mode, "rotate");
  expectUnchanged();
  // The next click works as ever.
  click(p3(0.5, 0.5));
  EXPECT_NE(status_.message.find("axis"), std::string::npos) << status_.message;
}

TEST_F(ToolEvents, APressOffThePaperHoldsNothing)
{
  key("1");
  drag(p3(4, 4), p3(0.5, 0.5), 5, false);
  settle();
  EXPECT_FALSE(status_.dragging);
  sendAndSettle(event(ToolEvent::RELEASE, p3(0.5, 0.5)));
  expectUnchanged();
  // On the margin beside the paper a line starts on the table: it creases the sheet it crosses.
  drag(p3(-0.03, 0.5), p3(1.03, 0.5), 8);
  const PaperState& state = client_.stateAt(base_ + 1);
  EXPECT_GE(creaseBetween(state, vertexAt(state, 0, 0.5), vertexAt(state, 1, 0.5)), 0);
}

TEST_F(ToolEvents, TheSlidersHandleFoldsByAssignmentAndEscPutsItBack)
{
  // A square with a valley diagonal as a designer's FOLD file: a driven crease, so a slider.
  nlohmann::json fold;
  fold["file_spec"] = 1.1;
  fold["frame_classes"] = { "creasePattern" };
  fold["vertices_coords"] = { { 0, 0 }, { 1, 0 }, { 1, 1 }, { 0, 1 } };
  fold["edges_vertices"] = { { 0, 1 }, { 1, 2 }, { 2, 3 }, { 3, 0 }, { 0, 2 } };
  fold["edges_assignment"] = { "B", "B", "B", "B", "V" };
  fold["faces_vertices"] = { { 0, 1, 2 }, { 0, 2, 3 } };
  const std::string name = "tool_slider_" + std::to_string(::getpid()) + ".fold";
  const std::string path = core::defaultDataFolder() + "/" + name;
  std::ofstream(path) << fold.dump();
  Load::Request load;
  load.path = name;
  const Load loaded = client_.call<Load>("load", load);
  std::filesystem::remove(path);
  ASSERT_TRUE(loaded.response.success) << loaded.response.message;
  std::map<std::string, visualization_msgs::Marker> slider;
  ros::Subscriber slider_sub = client_.nh().subscribe<visualization_msgs::MarkerArray>(
      "fold_slider_markers", 100, [&](const visualization_msgs::MarkerArray::ConstPtr& array) {
        for (const auto& m : array->markers)
          slider[m.ns] = m;
      });
  ASSERT_TRUE(waitFor(
      [&] {
        return slider.count("fold_slider_track") && slider["fold_slider_track"].points.size() >= 2 &&
               slider.count("fold_slider_percent") && status_.revision > base_;
      },
      10))
      << "no fold slider";
  base_ = status_.revision;
  const PaperState flat = client_.stateAt(base_);
  const int diagonal = creaseBetween(flat, vertexAt(flat, 0, 0), vertexAt(flat, 1, 1));
  ASSERT_GE(diagonal, 0);
  const core::Vec3 minus = toVec3(slider["fold_slider_track"].points[0]);
  const core::Vec3 plus = toVec3(slider["fold_slider_track"].points[1]);
  const core::Vec3 zero = 0.5 * (minus + plus);  // a flat pattern: the handle at 0 %
  // Esc while the handle is held at 75 %: nothing committed, the handle back at 0 %.
  drag(zero, zero + 0.75 * (plus - zero), 8, false);
  ASSERT_TRUE(waitFor([&] { return slider["fold_slider_percent"].text == "fold 75 %"; }, 10))
      << slider["fold_slider_percent"].text;
  EXPECT_TRUE(status_.dragging);
  key("Esc");
  EXPECT_FALSE(status_.dragging);
  EXPECT_TRUE(waitFor([&] { return slider["fold_slider_percent"].text == "fold 0 %"; }, 10))
      << slider["fold_slider_percent"].text;
  sendAndSettle(event(ToolEvent::RELEASE, zero + 0.75 * (plus - zero)));
  expectUnchanged();
  // A press beside the handle takes nothing; a drag of the handle to 50 % folds half way.
  drag(zero + 0.3 * (plus - zero), zero + 0.9 * (plus - zero), 4);
  expectUnchanged();
  drag(zero, zero + 0.5 * (plus - zero), 8);
  const PaperState& half = client_.stateAt(base_ + 1);
  EXPECT_NEAR(half.edges[diagonal].fold_angle, M_PI / 2, 1e-3);
  EXPECT_EQ(slider["fold_slider_percent"].text, "fold 50 %");
}

int main(int argc, char** argv)
{
  ::testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "tool_events_rostest");
  ros::NodeHandle nh;
  return RUN_ALL_TESTS();
}

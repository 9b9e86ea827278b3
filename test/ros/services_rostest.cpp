// rostest: the paper_model services against their contract (SPEC §8).
#include <gtest/gtest.h>

#include <filesystem>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <optional>

#include <tf2_ros/buffer.h>
#include <tf2_ros/transform_listener.h>
#include <virtual_origami/DragVertex.h>
#include <virtual_origami/FlatFold.h>
#include <virtual_origami/Load.h>
#include <virtual_origami/Operation.h>
#include <virtual_origami/PinVertex.h>
#include <virtual_origami/Save.h>
#include <visualization_msgs/MarkerArray.h>

#include "ros_test_client.h"
#include "virtual_origami/core/data_folder.h"
#include "virtual_origami/core/session.h"
#include "virtual_origami/ros/conversions.h"

using namespace virtual_origami;
using virtual_origami::test::PaperClient;
using virtual_origami::test::point;
using virtual_origami::test::vertexAt;
using virtual_origami::test::waitFor;

namespace
{
/// The state must be exactly what it was: a refused request changes nothing.
void expectSameState(const PaperState& a, const PaperState& b)
{
  EXPECT_EQ(a.revision, b.revision);
  EXPECT_EQ(a.vertices_folded, b.vertices_folded);
  EXPECT_EQ(a.vertices_crease_pattern, b.vertices_crease_pattern);
  EXPECT_EQ(a.edges, b.edges);
  EXPECT_EQ(a.faces, b.faces);
  EXPECT_EQ(a.pins, b.pins);
}

class Services : public ::testing::Test
{
protected:
  void SetUp() override
  {
    ops_sub_ = client_.nh().subscribe<Operation>("operations", 100, [this](const Operation::ConstPtr& op) {
      operations_.push_back(*op);
    });
    markers_sub_ = client_.nh().subscribe<visualization_msgs::MarkerArray>(
        "markers", 10, [this](const visualization_msgs::MarkerArray::ConstPtr& m) { markers_ = *m; });
    ASSERT_TRUE(waitFor([&] { return ops_sub_.getNumPublishers() > 0 && markers_sub_.getNumPublishers() > 0; }));
    const uint64_t latched = client_.state().revision;  // nothing else changes the model meanwhile
    ASSERT_TRUE(client_.trigger("reset").response.success);
    base_ = latched + 1;
    ASSERT_EQ(client_.stateAt(base_).faces.size(), 1u);
  }

  /// A refused request: success false, a message, nothing changed.
  template <class Response>
  void expectRefused(const Response& response, const PaperState& before)
  {
    EXPECT_FALSE(response.success);
    EXPECT_FALSE(response.message.empty());
    ros::WallDuration(0.2).sleep();
    ros::spinOnce();
    expectSameState(client_.state(), before);
  }

  /// The highest point the markers draw of the faces (ns "front").
  double markerTop()
  {
    double top = -INFINITY;
    for (const auto& m : markers_.markers)
      if (m.ns == "front" && m.action == visualization_msgs::Marker::ADD)
        for (const auto& p : m.points)
          top = std::max(top, p.z);
    return top;
  }

  /// The operation announced with this revision, once it came (none if it did not).
  std::optional<Operation> announced(uint64_t revision)
  {
    std::optional<Operation> found;
    waitFor([&] {
      for (const Operation& op : operations_)
        if (op.revision == revision && op.type != "pin")
          found = op;
      return found.has_value();
    });
    return found;
  }

  int markerPoints(const std::string& ns)
  {
    for (const auto& m : markers_.markers)
      if (m.ns == ns && m.action == visualization_msgs::Marker::ADD)
        return static_cast<int>(m.points.size());
    return 0;
  }

  PaperClient client_;
  ros::Subscriber ops_sub_, markers_sub_;
  std::vector<Operation> operations_;
  visualization_msgs::MarkerArray markers_;
  uint64_t base_ = 0;
};
}  // namespace

TEST_F(Services, CreaseSucceedsOrChangesNothing)
{
  const Crease ok = client_.crease(0.5, -0.1, 0.5, 1.1);
  ASSERT_TRUE(ok.response.success) << ok.response.message;
  EXPECT_EQ(ok.response.revision, base_ + 1);
  EXPECT_EQ(ok.response.new_edges.size(), 1u);
  const PaperState state = client_.stateAt(base_ + 1);
  EXPECT_EQ(state.faces.size(), 2u);
  EXPECT_EQ(state.edges[ok.response.new_edges[0]].assignment, "U");

  const Crease miss = client_.crease(3, 3, 4, 4);
  EXPECT_EQ(miss.response.revision, base_ + 1);
  expectRefused(miss.response, state);
  expectRefused(client_.crease(0.2, 0.2, 0.2, 0.2).response, state);  // zero length
  expectRefused(client_.crease(NAN, 0, 1, 1).response, state);
  expectRefused(client_.crease(0.5, -0.1, 0.5, 1.1).response, state);  // along the crease made
}

TEST_F(Services, RotateSucceedsOrChangesNothing)
{
  ASSERT_TRUE(client_.crease(0.5, -0.1, 0.5, 1.1).response.success);
  const PaperState creased = client_.stateAt(base_ + 1);
  // A preview is not committed.
  const Rotate preview = client_.rotate(-1, -1, 0.8, 0.5, 0.7, false);
  ASSERT_TRUE(preview.response.success) << preview.response.message;
  EXPECT_EQ(preview.response.revision, base_ + 1);
  const Rotate turned = client_.rotate(-1, -1, 0.8, 0.5, M_PI / 2);
  ASSERT_TRUE(turned.response.success) << turned.response.message;
  EXPECT_EQ(turned.response.revision, base_ + 2);
  const PaperState state = client_.stateAt(base_ + 2);
  EXPECT_NEAR(state.edges[turned.response.axis_edge].fold_angle, M_PI / 2, 1e-12);
  EXPECT_EQ(state.edges[turned.response.axis_edge].assignment, "V");
  (void)creased;

  expectRefused(client_.rotate(99, -1, 0.8, 0.5, 0.1).response, state);
  expectRefused(client_.rotate(-1, 99, 0.8, 0.5, 0.1).response, state);
  expectRefused(client_.rotate(-1, 0, 0.8, 0.5, 0.1).response, state);  // a boundary edge
  expectRefused(client_.rotate(-1, -1, 0.8, 0.5, NAN).response, state);
  expectRefused(client_.rotate(-1, -1, 5.0, 5.0, 0.1).response, state);  // no face there

  // Recorded positions (a replay's) are a commit's, one per vertex.
  Rotate::Request recorded;
  recorded.face = turned.response.face;
  recorded.axis_edge = turned.response.axis_edge;
  recorded.angle = 0.1;
  recorded.positions = state.vertices_folded;
  recorded.commit = false;
  expectRefused(client_.call<Rotate>("rotate", recorded).response, state);
  recorded.commit = true;
  recorded.positions.pop_back();
  const Rotate short_of_one = client_.call<Rotate>("rotate", recorded);
  expectRefused(short_of_one.response, state);
  EXPECT_NE(short_of_one.response.message.find("positions for"), std::string::npos) << short_of_one.response.message;
}

TEST_F(Services, SquashUndoRedoReset)
{
  EXPECT_FALSE(client_.trigger("redo").response.success);
  ASSERT_TRUE(client_.crease(0.5, -0.1, 0.5, 1.1).response.success);
  ASSERT_TRUE(client_.rotate(-1, -1, 0.8, 0.5, 2.0).response.success);
  const PaperState turned = client_.stateAt(base_ + 2);
  const std_srvs::Trigger squashed = client_.trigger("squash");
  ASSERT_TRUE(squashed.response.success) << squashed.response.message;
  const PaperState flat = client_.stateAt(base_ + 3);
  for (const auto& p : flat.vertices_folded)
    EXPECT_NEAR(p.z, 0.0, 1e-12);
  ASSERT_TRUE(client_.trigger("undo").response.success);
  const PaperState undone = client_.stateAt(base_ + 4);
  EXPECT_EQ(undone.vertices_folded, turned.vertices_folded);
  ASSERT_TRUE(client_.trigger("redo").response.success);
  EXPECT_EQ(client_.stateAt(base_ + 5).vertices_folded, flat.vertices_folded);
  expectRefused(client_.trigger("redo").response, client_.stateAt(base_ + 5));
  ASSERT_TRUE(client_.trigger("reset").response.success);
  EXPECT_EQ(client_.stateAt(base_ + 6).faces.size(), 1u);
  // Every committed operation was announced, in order, with its revision.
  const auto since_reset = [&] {
    std::vector<Operation> ops;
    for (const Operation& op : operations_)
      if (op.revision > base_)
        ops.push_back(op);
    return ops;
  };
  ASSERT_TRUE(waitFor([&] { return since_reset().size() >= 6; }));
  const std::vector<Operation> announced = since_reset();
  const std::vector<std::string> types{ "crease", "rotate", "squash", "undo", "redo", "reset" };
  for (size_t i = 0; i < types.size(); ++i)
  {
    EXPECT_EQ(announced[i].type, types[i]);
    EXPECT_EQ(announced[i].revision, base_ + 1 + i);
  }
  EXPECT_EQ(announced[1].axis_edge, 6);  // resolved, not -1
}

TEST_F(Services, PinAndRelease)
{
  const PaperState start = client_.state();
  PinVertex::Request pin;
  pin.vertex = 2;
  ASSERT_TRUE(client_.call<PinVertex>("pin", pin).response.success);
  ASSERT_TRUE(waitFor([&] { return client_.state().pins.size() == 1; }));
  EXPECT_EQ(client_.state().pins[0].vertex, 2);
  // A pinned vertex is in tf as pin_2, at its position in the paper frame.
  tf2_ros::Buffer buffer;
  tf2_ros::TransformListener listener(buffer);
  EXPECT_TRUE(buffer.canTransform("paper", "pin_2", ros::Time(0), ros::Duration(5.0)));
  EXPECT_TRUE(buffer.canTransform("world", "paper", ros::Time(0), ros::Duration(5.0)));
  const auto t = buffer.lookupTransform("paper", "pin_2", ros::Time(0));
  EXPECT_NEAR(t.transform.translation.x, 1.0, 1e-9);
  EXPECT_NEAR(t.transform.translation.y, 1.0, 1e-9);
  // A rotation that would carry the pin away is refused.
  ASSERT_TRUE(client_.crease(0.5, -0.1, 0.5, 1.1).response.success);
  const PaperState creased = client_.stateAt(base_ + 1);
  expectRefused(client_.rotate(-1, -1, 0.8, 0.5, 1.0).response, creased);

  const PaperState pinned = client_.state();
  PinVertex::Request bad;
  bad.vertex = -5;
  expectRefused(client_.call<PinVertex>("pin", bad).response, pinned);
  bad.vertex = 3;
  bad.release = true;  // not pinned
  expectRefused(client_.call<PinVertex>("pin", bad).response, pinned);
  pin.release = true;
  ASSERT_TRUE(client_.call<PinVertex>("pin", pin).response.success);
  ASSERT_TRUE(waitFor([&] { return client_.state().pins.empty(); }));
  EXPECT_TRUE(client_.rotate(-1, -1, 0.8, 0.5, 1.0).response.success);
  (void)start;
}

TEST_F(Services, SaveAndLoad)
{
  ASSERT_TRUE(client_.crease(0, 0, 1, 1).response.success);
  ASSERT_TRUE(client_.rotate(-1, -1, 0.2, 0.8, M_PI).response.success);
  const PaperState folded = client_.stateAt(base_ + 2);
  // Relative paths resolve in the node's data folder (ROS_HOME is the suite's own folder).
  const std::string data = core::defaultDataFolder();
  const std::string name = "rostest_" + std::to_string(::getpid());
  Save::Request save;
  save.path = name + ".fold";
  const Save saved = client_.call<Save>("save", save);
  ASSERT_TRUE(saved.response.success) << saved.response.message;
  EXPECT_TRUE(std::ifstream(data + "/" + name + ".fold").good()) << saved.response.message;
  save.path = data + "/" + name + ".obj";  // absolute, inside
  ASSERT_TRUE(client_.call<Save>("save", save).response.success);
  save.path = "no/such/folder/x.fold";
  EXPECT_FALSE(client_.call<Save>("save", save).response.success);
  save.path = "x.png";
  EXPECT_FALSE(client_.call<Save>("save", save).response.success);

  ASSERT_TRUE(client_.trigger("reset").response.success);
  Load::Request load;
  load.path = name + ".fold";
  const Load loaded = client_.call<Load>("load", load);
  ASSERT_TRUE(loaded.response.success) << loaded.response.message;
  const PaperState back = client_.stateAt(base_ + 4);
  ASSERT_EQ(back.vertices_folded.size(), folded.vertices_folded.size());
  for (size_t i = 0; i < back.vertices_folded.size(); ++i)
  {
    EXPECT_NEAR(back.vertices_folded[i].x, folded.vertices_folded[i].x, 1e-12);
    EXPECT_NEAR(back.vertices_folded[i].y, folded.vertices_folded[i].y, 1e-12);
    EXPECT_NEAR(back.vertices_folded[i].z, folded.vertices_folded[i].z, 1e-12);
  }
  // A broken file and a missing one are refused.
  std::ofstream(data + "/" + name + "_broken.fold") << "{\"vertices_coords\": [[0,0],[1,0]], \"faces_vertices\": [[0,1,7]]}";
  load.path = name + "_broken.fold";
  expectRefused(client_.call<Load>("load", load).response, back);
  load.path = "no/such/file.fold";
  expectRefused(client_.call<Load>("load", load).response, back);
}

TEST_F(Services, LoadsOripaCreasePatterns)
{
  const std::string data = core::defaultDataFolder();
  // A preliminary base as ORIPA writes it: the square's outline (1), the diagonals valley (3),
  // the horizontal mountain (2), the vertical in a mountain half and a valley half.
  std::ofstream(data + "/preliminary.cp") << "1 -200 -200 200 -200\n1 200 -200 200 200\n1 200 200 -200 200\n"
                                             "1 -200 200 -200 -200\n3 -200 -200 200 200\n3 -200 200 200 -200\n"
                                             "2 -200 0 200 0\n2 0 -200 0 0\n3 0 0 0 200\n";
  Load::Request load;
  load.path = "preliminary.cp";
  const Load loaded = client_.call<Load>("load", load);
  ASSERT_TRUE(loaded.response.success) << loaded.response.message;
  const PaperState& state = client_.stateAt(base_ + 1);
  EXPECT_EQ(state.faces.size(), 8u);
  int mountains = 0, valleys = 0;
  for (const Edge& e : state.edges)
  {
    mountains += e.assignment == "M";
    valleys += e.assignment == "V";
  }
  EXPECT_EQ(mountains, 3);
  EXPECT_EQ(valleys, 5);
  for (const geometry_msgs::Point& p : state.vertices_crease_pattern)  // the sheet's 1 × 1 square
  {
    EXPECT_GE(p.x, -1e-12);
    EXPECT_LE(p.x, 1 + 1e-12);
  }
  // A malformed line is refused by its number, and nothing changes.
  std::ofstream(data + "/bad.cp") << "1 -200 -200 200 -200\n7 200 -200 200 200\n";
  load.path = "bad.cp";
  const Load bad = client_.call<Load>("load", load);
  EXPECT_FALSE(bad.response.success);
  EXPECT_NE(bad.response.message.find("line 2"), std::string::npos) << bad.response.message;
  EXPECT_EQ(client_.state().revision, base_ + 1);
}

TEST_F(Services, LoadsSvgPatternsInOrigamiSimulatorsConvention)
{
  const std::string data = core::defaultDataFolder();
  // A 30 × 30 square with a 10 × 10 hole, red mountains from its corners to the hole's.
  std::ofstream(data + "/hole.svg") << R"(<svg xmlns="http://www.w3.org/2000/svg">
    <rect x="0" y="0" width="30" height="30" stroke="#000" fill="none"/>
    <rect x="10" y="10" width="10" height="10" stroke="#000" fill="none"/>
    <path stroke="#f00" d="M0 0L10 10M30 0L20 10M30 30L20 20M0 30L10 20"/></svg>)";
  Load::Request load;
  load.path = "hole.svg";
  const Load loaded = client_.call<Load>("load", load);
  ASSERT_TRUE(loaded.response.success) << loaded.response.message;
  const PaperState& state = client_.stateAt(base_ + 1);
  EXPECT_EQ(state.faces.size(), 4u);  // round the hole, none over it
  int mountains = 0, boundaries = 0;
  for (const Edge& e : state.edges)
  {
    mountains += e.assignment == "M";
    boundaries += e.assignment == "B";
  }
  EXPECT_EQ(mountains, 4);
  EXPECT_EQ(boundaries, 8);
  // A stroke of another colour is refused naming its element, and nothing changes.
  std::ofstream(data + "/grey.svg") << "<svg>\n<line x2='1' stroke='#888'/></svg>";
  load.path = "grey.svg";
  const Load grey = client_.call<Load>("load", load);
  EXPECT_FALSE(grey.response.success);
  EXPECT_NE(grey.response.message.find("<line> on line 2"), std::string::npos) << grey.response.message;
  EXPECT_EQ(client_.state().revision, base_ + 1);
}

TEST_F(Services, FilesStayInTheDataFolder)
{
  namespace fs = std::filesystem;
  const PaperState before = client_.state();
  const fs::path data = core::defaultDataFolder();
  // A folder beside the data folder stands for the rest of the user's files.
  const fs::path outside = data.parent_path() / "outside";
  fs::create_directories(outside);
  const fs::path victim = outside / "victim.fold";
  std::ofstream(victim) << "the user's own file";
  const fs::path secret = outside / "secret.fold";
  std::ofstream(secret) << "SECRET-BYTES";

  std::vector<std::string> refused_saves{ "/etc/vo_probe.fold", "/etc/vo_probe.obj", "../outside/x.fold",
                                          "../../x.fold", victim.string() };
  fs::create_symlink(victim, data / "link.fold");  // a link leaving the folder
  refused_saves.push_back("link.fold");
  std::ofstream(data / "readonly.fold") << "kept";
  fs::permissions(data / "readonly.fold", fs::perms::owner_read | fs::perms::group_read | fs::perms::others_read);
  refused_saves.push_back("readonly.fold");
  for (const std::string& path : refused_saves)
  {
    Save::Request save;
    save.path = path;
    const Save res = client_.call<Save>("save", save);
    EXPECT_FALSE(res.response.success) << "save " << path;
    EXPECT_FALSE(res.response.message.empty()) << "save " << path;
  }
  EXPECT_FALSE(fs::exists("/etc/vo_probe.fold"));
  EXPECT_FALSE(fs::exists("/etc/vo_probe.obj"));
  const auto content = [](const fs::path& p) {
    std::ifstream in(p);
    return std::string(std::istreambuf_iterator<char>(in), {});
  };
  EXPECT_EQ(content(victim), "the user's own file");
  EXPECT_EQ(content(data / "readonly.fold"), "kept");

  // A link planted at the temporary name the save of an earlier version used.
  fs::create_symlink(victim, data / "planted.fold.tmp");
  Save::Request save;
  save.path = "planted.fold";
  const Save planted = client_.call<Save>("save", save);
  EXPECT_TRUE(planted.response.success) << planted.response.message;
  EXPECT_EQ(content(victim), "the user's own file");
  EXPECT_TRUE(fs::is_symlink(data / "planted.fold.tmp"));

  for (const std::string& path : { std::string("/etc/shadow"), std::string("/etc/passwd"), secret.string(),
                                   std::string("../outside/secret.fold") })
  {
    Load::Request load;
    load.path = path;
    const Load res = client_.call<Load>("load", load);
    EXPECT_FALSE(res.response.success) << "load " << path;
    EXPECT_EQ(res.response.message.find("SECRET"), std::string::npos) << res.response.message;
  }
  // Inside, a file that is not FOLD is refused without quoting it.
  std::ofstream(data / "not_fold.fold") << "SECRET-BYTES and more";
  Load::Request load;
  load.path = "not_fold.fold";
  const Load res = client_.call<Load>("load", load);
  EXPECT_FALSE(res.response.success);
  EXPECT_EQ(res.response.message.find("SECRET"), std::string::npos) << res.response.message;
  EXPECT_EQ(res.response.message.find("S\'"), std::string::npos) << res.response.message;

  ros::WallDuration(0.2).sleep();
  ros::spinOnce();
  EXPECT_EQ(client_.state().revision, before.revision);
  fs::remove_all(outside);
}

TEST_F(Services, ASequenceEndsWhereTheCoreAloneEnds)
{
  core::Session session;
  const auto crease = [&](double x0, double y0, double x1, double y1) {
    ASSERT_TRUE(client_.crease(x0, y0, x1, y1).response.success);
    core::CreaseRequest r;
    r.start = core::Vec3(x0, y0, 0);
    r.end = core::Vec3(x1, y1, 0);
    ASSERT_TRUE(session.crease(r).ok());
  };
  const auto rotate = [&](double x, double y, double angle) {
    ASSERT_TRUE(client_.rotate(-1, -1, x, y, angle).response.success);
    core::RotateRequest r;
    r.click = core::Vec3(x, y, 0);
    r.angle = angle;
    ASSERT_TRUE(session.rotate(r).ok());
  };
  crease(0, 0, 1, 1);
  rotate(0.2, 0.8, M_PI);
  crease(1.1, -0.1, 0.4, 0.6);
  rotate(0.3, 0.1, M_PI);
  ASSERT_TRUE(client_.trigger("undo").response.success);
  ASSERT_TRUE(session.undo().ok());
  rotate(0.3, 0.1, 2.0);
  ASSERT_TRUE(client_.trigger("squash").response.success);
  ASSERT_TRUE(session.squash().ok());
  const PaperState expected = toMessage(session.paper(), base_ + session.revision(), {});
  const PaperState& got = client_.stateAt(base_ + session.revision());
  EXPECT_EQ(got.vertices_folded, expected.vertices_folded);  // bit for bit
  EXPECT_EQ(got.vertices_crease_pattern, expected.vertices_crease_pattern);
  EXPECT_EQ(got.edges, expected.edges);
  EXPECT_EQ(got.faces, expected.faces);
}

TEST_F(Services, MarkersFollowEveryOperation)
{
  ASSERT_TRUE(waitFor([&] { return markerPoints("front") == 6; }));  // one square: two triangles
  EXPECT_EQ(markerPoints("boundary"), 8);
  ASSERT_TRUE(client_.crease(0.5, -0.1, 0.5, 1.1).response.success);
  ASSERT_TRUE(waitFor([&] { return markerPoints("crease") == 2; }));
  EXPECT_EQ(markerPoints("front"), 12);
  EXPECT_EQ(markerPoints("back"), 12);
  ASSERT_TRUE(client_.rotate(-1, -1, 0.8, 0.5, -1.0).response.success);
  ASSERT_TRUE(waitFor([&] { return markerPoints("mountain") == 2; }));
  EXPECT_EQ(markerPoints("crease"), 0);
  for (const auto& m : markers_.markers)
    EXPECT_EQ(m.header.frame_id, "paper");
}

namespace
{
/// The diagonal (0, 0)–(1, 1) folded to `angle`, the lower-right half staying.
FlatFold::Request diagonalFold(double angle, bool commit, double fraction = 1.0)
{
  FlatFold::Request r;
  r.starts = { point(0, 0) };
  r.ends = { point(1, 1) };
  r.angles = { angle };
  r.fixed = point(0.9, 0.1);
  r.commit = commit;
  r.fraction = fraction;
  return r;
}

}  // namespace

TEST_F(Services, FlatFoldPreviewsCommitsAndRefuses)
{
  ASSERT_TRUE(client_.crease(0, 0, 1, 1).response.success);
  const PaperState creased = client_.stateAt(base_ + 1);
  // A preview half way: drawn (the corner (0, 1) straight above the diagonal), not recorded.
  const FlatFold preview = client_.call<FlatFold>("flat_fold", diagonalFold(M_PI, false, 0.5));
  ASSERT_TRUE(preview.response.success) << preview.response.message;
  EXPECT_EQ(preview.response.revision, base_ + 1);
  EXPECT_EQ(preview.response.moved_faces.size(), 1u);
  EXPECT_TRUE(waitFor([&] { return markerTop() > 0.7; })) << markerTop();
  ros::WallDuration(0.2).sleep();
  ros::spinOnce();
  expectSameState(client_.state(), creased);

  const FlatFold folded = client_.call<FlatFold>("flat_fold", diagonalFold(M_PI, true));
  ASSERT_TRUE(folded.response.success) << folded.response.message;
  EXPECT_EQ(folded.response.revision, base_ + 2);
  EXPECT_EQ(folded.response.changed_edges.size(), 1u);
  EXPECT_EQ(folded.response.moved_faces.size(), 1u);
  const PaperState state = client_.stateAt(base_ + 2);
  const geometry_msgs::Point corner = state.vertices_folded[vertexAt(state, 0, 1)];
  EXPECT_NEAR(corner.x, 1.0, 1e-12);
  EXPECT_NEAR(corner.y, 0.0, 1e-12);
  EXPECT_NEAR(corner.z, 0.0, 1e-12);
  EXPECT_NEAR(state.edges[folded.response.changed_edges[0]].fold_angle, M_PI, 1e-12);
  EXPECT_EQ(state.edges[folded.response.changed_edges[0]].assignment, "V");
  EXPECT_TRUE(waitFor([&] { return markerTop() < 0.1; })) << markerTop();
  // Announced on `operations` with every parameter (the preview was not: nothing else came).
  const std::optional<Operation> announced_fold = announced(base_ + 2);
  ASSERT_TRUE(announced_fold.has_value());
  const Operation op = *announced_fold;
  for (const Operation& o : operations_)
    EXPECT_TRUE(o.revision != base_ + 1 || o.type == "crease") << o.type;
  EXPECT_EQ(op.type, "flat_fold");
  EXPECT_EQ(op.revision, base_ + 2);
  ASSERT_EQ(op.crease_starts.size(), 1u);
  ASSERT_EQ(op.crease_ends.size(), 1u);
  ASSERT_EQ(op.crease_angles.size(), 1u);
  EXPECT_EQ(op.crease_ends[0].x, 1.0);
  EXPECT_EQ(op.crease_ends[0].y, 1.0);
  EXPECT_EQ(op.crease_angles[0], M_PI);
  EXPECT_EQ(op.fixed.x, 0.9);
  EXPECT_EQ(op.fixed.y, 0.1);
  const core::Expected<core::Operation> back = fromMessage(op);
  ASSERT_TRUE(back.ok()) << back.message();
  EXPECT_EQ(back->kind, core::Operation::Kind::FlatFold);
  EXPECT_EQ(back->flat_fold.fixed_point, core::Vec2(0.9, 0.1));

  // Refusals: success false, a message that says why, the revision and the paper as they were.
  const auto refused = [&](FlatFold::Request r, const std::string& words) {
    for (bool commit : { true, false })
    {
      r.commit = commit;
      const FlatFold answer = client_.call<FlatFold>("flat_fold", r);
      EXPECT_EQ(answer.response.revision, base_ + 2);
      EXPECT_NE(answer.response.message.find(words), std::string::npos) << answer.response.message;
      expectRefused(answer.response, state);
    }
  };
  FlatFold::Request r = diagonalFold(0.0, true, 0.5);
  r.ends.clear();
  refused(r, "one end and one angle per start");
  r = diagonalFold(0.0, true, 0.5);
  r.angles.push_back(0.0);
  refused(r, "one end and one angle per start");
  r = diagonalFold(0.0, true, 0.5);
  r.starts.clear();
  r.ends.clear();
  r.angles.clear();
  refused(r, "no creases");
  refused(diagonalFold(NAN, true, 0.5), "non-finite");
  r = diagonalFold(0.0, true, 0.5);
  r.fixed = point(3, 3);
  refused(r, "off the sheet");
  refused(diagonalFold(M_PI, true, 0.5), "moves nothing");
  // Half the diagonal alone cannot fold: the other half would tear from it.
  ASSERT_TRUE(client_.crease(0, 1, 1, 0).response.success);
  const PaperState crossed = client_.stateAt(base_ + 3);
  r = diagonalFold(0.0, true, 0.5);
  r.ends = { point(0.5, 0.5) };
  for (bool commit : { true, false })
  {
    r.commit = commit;
    const FlatFold answer = client_.call<FlatFold>("flat_fold", r);
    EXPECT_NE(answer.response.message.find("the chosen creases do not fold flat"), std::string::npos)
        << answer.response.message;
    expectRefused(answer.response, crossed);
  }
  // A preview fraction beyond the fold.
  const FlatFold beyond = client_.call<FlatFold>("flat_fold", diagonalFold(0.0, false, 1.5));
  EXPECT_NE(beyond.response.message.find("from 0 to 1"), std::string::npos) << beyond.response.message;
  expectRefused(beyond.response, crossed);

  // Undone like any other operation.
  ASSERT_TRUE(client_.trigger("undo").response.success);
  ASSERT_TRUE(client_.trigger("undo").response.success);
  EXPECT_EQ(client_.stateAt(base_ + 5).vertices_folded, creased.vertices_folded);
}

TEST_F(Services, DragVertexRefusesWhatItCannotDo)
{
  // paper_model runs here without a solver: only what is refused before a solve is asked.
  ASSERT_TRUE(client_.crease(0.5, -0.1, 0.5, 1.1).response.success);
  const PaperState state = client_.stateAt(base_ + 1);
  ASSERT_TRUE(announced(base_ + 1).has_value());
  const size_t published = operations_.size();
  DragVertex::Request r;
  r.vertex = 99;
  r.position = point(0.5, 0.5, 0.5);
  for (bool commit : { true, false })
  {
    r.commit = commit;
    r.vertex = 99;
    r.position = point(0.5, 0.5, 0.5);
    DragVertex answer = client_.call<DragVertex>("drag_vertex", r);
    EXPECT_NE(answer.response.message.find("vertex 99 does not exist"), std::string::npos) << answer.response.message;
    EXPECT_EQ(answer.response.revision, base_ + 1);
    expectRefused(answer.response, state);
    r.vertex = -1;
    expectRefused(client_.call<DragVertex>("drag_vertex", r).response, state);
    r.vertex = vertexAt(state, 1, 0);
    r.position = point(NAN, 0, 0);
    answer = client_.call<DragVertex>("drag_vertex", r);
    EXPECT_NE(answer.response.message.find("not a finite point"), std::string::npos) << answer.response.message;
    expectRefused(answer.response, state);
  }
  // A pinned vertex stays where its pin holds it.
  PinVertex::Request pin;
  pin.vertex = vertexAt(state, 1, 0);
  ASSERT_TRUE(client_.call<PinVertex>("pin", pin).response.success);
  ASSERT_TRUE(waitFor([&] { return client_.state().pins.size() == 1u; }));
  const PaperState with_pin = client_.state();
  r.vertex = pin.vertex;
  r.position = point(0.9, 0.0, 0.3);
  r.commit = true;
  const DragVertex held = client_.call<DragVertex>("drag_vertex", r);
  EXPECT_NE(held.response.message.find("pinned"), std::string::npos) << held.response.message;
  expectRefused(held.response, with_pin);
  pin.release = true;
  ASSERT_TRUE(client_.call<PinVertex>("pin", pin).response.success);
  // Nothing refused was announced (the pin and its release were).
  ros::WallDuration(0.2).sleep();
  ros::spinOnce();
  for (size_t i = published; i < operations_.size(); ++i)
    EXPECT_EQ(operations_[i].type, "pin");
}

TEST_F(Services, RotateCarriesPickedLayersOnlyToItsOperation)
{
  ASSERT_TRUE(client_.crease(0.5, -0.1, 0.5, 1.1).response.success);
  Rotate::Request r;
  r.face = -1;
  r.axis_edge = -1;
  r.click = point(0.8, 0.5);
  r.angle = 0.5;
  r.commit = true;
  r.picked_layers_only = true;
  const Rotate turned = client_.call<Rotate>("rotate", r);
  ASSERT_TRUE(turned.response.success) << turned.response.message;
  r.picked_layers_only = false;
  r.face = turned.response.face;  // the click is off the face once it turned
  r.axis_edge = turned.response.axis_edge;
  const Rotate again = client_.call<Rotate>("rotate", r);
  ASSERT_TRUE(again.response.success) << again.response.message;
  const std::optional<Operation> first = announced(base_ + 2);
  const std::optional<Operation> second = announced(base_ + 3);
  ASSERT_TRUE(first.has_value());
  ASSERT_TRUE(second.has_value());
  EXPECT_EQ(first->type, "rotate");
  EXPECT_TRUE(first->picked_layers_only);
  EXPECT_FALSE(second->picked_layers_only);
  const core::Expected<core::Operation> back = fromMessage(*first);
  ASSERT_TRUE(back.ok()) << back.message();
  EXPECT_FALSE(back->rotate.carry_stack);
  EXPECT_NEAR(client_.stateAt(base_ + 3).edges[turned.response.axis_edge].fold_angle, 1.0, 1e-12);
}

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "services_rostest");
  ros::NodeHandle keep_alive;
  return RUN_ALL_TESTS();
}

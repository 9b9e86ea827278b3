// The interaction node driven the way rviz drives it (InteractiveMarkerFeedback on the server's
// feedback topic), watched on `state`, `interaction_status` and `interaction_markers`: the
// fixture of the rostests that drive it.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <regex>
#include <set>

#include <virtual_origami/InteractionStatus.h>
#include <visualization_msgs/InteractiveMarkerInit.h>
#include <visualization_msgs/InteractiveMarkerControl.h>
#include <visualization_msgs/MarkerArray.h>
#include <geometry_msgs/PoseStamped.h>
#include <tf2_ros/transform_broadcaster.h>
#include <virtual_origami/Operation.h>
#include <virtual_origami/PinVertex.h>

#include "ros_test_client.h"
#include "virtual_origami/ros/conversions.h"
#include "virtual_origami/ros/interaction_view.h"
#include "virtual_origami/ros/mouse_feedback.h"

namespace virtual_origami::test
{
using visualization_msgs::InteractiveMarkerFeedback;

inline core::Vec3 p3(double x, double y, double z = 0.0)
{
  return { x, y, z };
}

/// The crease-pattern position of a vertex of a state.
inline core::Vec3 creasePattern(const PaperState& s, int v)
{
  return p3(s.vertices_crease_pattern[v].x, s.vertices_crease_pattern[v].y);
}
inline core::Vec3 folded(const PaperState& s, int v)
{
  return p3(s.vertices_folded[v].x, s.vertices_folded[v].y, s.vertices_folded[v].z);
}
inline int creaseBetween(const PaperState& s, int a, int b)
{
  for (size_t e = 0; e < s.edges.size(); ++e)
    if ((s.edges[e].v0 == a && s.edges[e].v1 == b) || (s.edges[e].v0 == b && s.edges[e].v1 == a))
      return static_cast<int>(e);
  return -1;
}

class InteractionFixture : public ::testing::Test
{
protected:
  void SetUp() override
  {
    feedback_pub_ = client_.nh().advertise<InteractiveMarkerFeedback>("interaction/feedback", 1000);
    status_sub_ = client_.nh().subscribe<InteractionStatus>(
        "interaction_status", 100, [this](const InteractionStatus::ConstPtr& s) {
          status_ = *s;
          ++statuses_;
          max_pending_ = std::max<uint32_t>(max_pending_, s->pending);
        });
    guides_sub_ = client_.nh().subscribe<visualization_msgs::MarkerArray>(
        "interaction_markers", 100, [this](const visualization_msgs::MarkerArray::ConstPtr& array) {
          for (const auto& m : array->markers)
            if (m.action == visualization_msgs::Marker::DELETEALL)
              shown_.clear();
            else if (m.action == visualization_msgs::Marker::ADD)
            {
              shown_.insert(m.ns);
              if (m.ns == "message")
                said_ = m;
            }
        });
    init_sub_ = client_.nh().subscribe<visualization_msgs::InteractiveMarkerInit>(
        "interaction/update_full", 10,
        [this](const visualization_msgs::InteractiveMarkerInit::ConstPtr& init) { init_ = *init; });
    paper_markers_sub_ = client_.nh().subscribe<visualization_msgs::MarkerArray>(
        "markers", 100, [this](const visualization_msgs::MarkerArray::ConstPtr& array) {
          ++paper_markers_;
          for (const auto& m : array->markers)
            if (m.ns == "front")
              front_ = m;
        });
    const ros::Time reset_at = ros::Time::now();
    ASSERT_TRUE(client_.trigger("reset").response.success);
    base_ = client_.stateSince(reset_at).revision;
    ASSERT_TRUE(waitFor([&] { return feedback_pub_.getNumSubscribers() > 0; }, 30));
    ASSERT_TRUE(waitFor([&] { return loadMenu(); }, 30)) << "no interactive marker `paper` with a menu";
    // A wait for the node to have taken the reset, as the two above: once, with ctest's other
    // tests on the same two cores, it took more than 10 s after the test before it.
    ASSERT_TRUE(waitFor([&] { return statuses_ > 0 && status_.revision == base_; }, 30));
  }

  /// The sheet's marker and its menu entries by title, from the server's full update.
  bool loadMenu()
  {
    for (const auto& m : init_.markers)
      if (m.name == "paper")
      {
        marker_ = m;
        if (!m.controls.empty() && !m.controls[0].markers.empty() && !m.controls[0].markers[0].points.empty())
          gesture_.lift = m.controls[0].markers[0].points[0].z;  // the sheet lies flat in these tests
        for (const auto& entry : m.menu_entries)
          menu_[entry.title] = entry.id;
        return !menu_.empty();
      }
    return false;
  }

  /// Markers of the drag on show (the message to the user aside).
  size_t guidesShown()
  {
    return shown_.size() - shown_.count("message");
  }

  void send(const InteractiveMarkerFeedback& f)
  {
    feedback_pub_.publish(f);
    ros::spinOnce();
  }

  /// The node handled everything sent so far.
  void settle()
  {
    const int seen = statuses_;
    ASSERT_TRUE(waitFor([&] { return statuses_ > seen + 1 && status_.pending == 0 && !status_.dragging; }, 10));
  }

  /// Press at `from`, move through `steps` points to `to`, release there.
  void drag(const core::Vec3& from, const core::Vec3& to, int steps = 10,
            const std::function<void()>& before_release = {})
  {
    gesture_.press = from;
    send(gesture_.down(ros::Time::now()));
    for (int i = 1; i <= steps; ++i)
    {
      ros::WallDuration(0.02).sleep();
      send(gesture_.moveTo(from + (to - from) * (static_cast<double>(i) / steps), ros::Time::now()));
    }
    if (before_release)
      before_release();
    send(gesture_.upAt(to, ros::Time::now()));
    settle();
  }

  /// The menu entry with that title (rviz shows check marks as a prefix).
  void menu(const std::string& title, const core::Vec3& at = p3(0.5, 0.5))
  {
    int id = -1;
    for (const auto& [t, i] : menu_)
      if (t.find(title) != std::string::npos)
        id = i;
    ASSERT_GE(id, 0) << "no menu entry " << title;
    send(gesture_.menu(id, at, ros::Time::now()));
    settle();
  }

  void creaseDiagonal()
  {
    ASSERT_TRUE(client_.crease(0, 0, 1, 1).response.success);
    ++base_;
    client_.stateAt(base_);
    ASSERT_TRUE(waitFor([&] { return status_.revision == base_; }, 10));  // the node shows it
  }

  /// Nothing was committed: the revision stays.
  void expectUnchanged()
  {
    ros::WallDuration(0.5).sleep();
    ros::spinOnce();
    EXPECT_EQ(client_.state().revision, base_);
  }

  /// Square → half → quarter (seed Fig. 15's case): four layers over [0, .5]², folded flat
  /// through the services.
  void quarterFold()
  {
    ASSERT_TRUE(client_.crease(0.5, 0, 0.5, 1).response.success);
    const Rotate half = client_.rotate(-1, -1, 0.75, 0.5, M_PI);
    ASSERT_TRUE(half.response.success) << half.response.message;
    ASSERT_TRUE(client_.crease(0, 0.5, 0.5, 0.5).response.success);
    const Rotate quarter = client_.rotate(-1, -1, 0.25, 0.9, M_PI);
    ASSERT_TRUE(quarter.response.success) << quarter.response.message;
    base_ += 4;
    client_.stateAt(base_);
    ASSERT_TRUE(waitFor([&] { return status_.revision == base_; }, 10));
  }

  /// The heights the paper's front sides are drawn at (in 0.1 mm).
  std::set<long> frontHeights()
  {
    std::set<long> heights;
    for (const auto& p : front_.points)
      heights.insert(std::lround(p.z * 1e4));
    return heights;
  }

  /// The last text said to the user refuses the drag in the user's words, in short lines,
  /// over the sheet.
  void expectSaidOverTheSheet(const std::string& starting)
  {
    ASSERT_TRUE(waitFor([&] { return !said_.text.empty(); }, 5));
    std::string unwrapped = said_.text;
    std::replace(unwrapped.begin(), unwrapped.end(), '\n', ' ');
    EXPECT_EQ(unwrapped.rfind(starting, 0), 0u) << unwrapped;
    EXPECT_EQ(status_.message, unwrapped);
    EXPECT_EQ(unwrapped.find("seed"), std::string::npos) << unwrapped;
    EXPECT_FALSE(std::regex_search(unwrapped, std::regex("(face|edge) [0-9]"))) << unwrapped;  // no numbers
    size_t line = 0, longest = 0;
    for (char c : said_.text)
    {
      line = c == '\n' ? 0 : line + 1;
      longest = std::max(longest, line);
    }
    EXPECT_LE(longest, 32u) << said_.text;
    // Centred over the sheet far enough for the longest line, whichever way the view turns it.
    const double half = 0.3 * said_.scale.z * static_cast<double>(longest);
    for (double c : { said_.pose.position.x, said_.pose.position.y })
    {
      EXPECT_GE(c, half - 1e-9);
      EXPECT_LE(c, 1.0 - half + 1e-9);
    }
    EXPECT_GT(said_.pose.position.z, 0.0);
  }

  PaperClient client_;
  visualization_msgs::Marker said_;   // the last message marker shown
  visualization_msgs::Marker front_;  // the paper's front sides as paper_model last drew them
  ros::Publisher feedback_pub_;
  ros::Subscriber status_sub_, guides_sub_, paper_markers_sub_, init_sub_;
  visualization_msgs::InteractiveMarkerInit init_;
  InteractionStatus status_;
  int statuses_ = 0;
  uint32_t max_pending_ = 0;
  std::set<std::string> shown_;
  int paper_markers_ = 0;
  visualization_msgs::InteractiveMarker marker_;
  std::map<std::string, int> menu_;
  MouseGesture gesture_;
  uint64_t base_ = 0;
  std::vector<Operation> operations_;
};

/// rviz's default view (rviz/origami.rviz): an orbit about (0.5, 0.45, 0.1), 1.7 m away, yaw
/// 4.2, pitch 0.75, as the ViewCamera display broadcasts it (x right, y down, z along the sight).
inline ViewCamera defaultView()
{
  const double yaw = 4.2, pitch = 0.75, distance = 1.7;
  const core::Vec3 focal(0.5, 0.45, 0.1);
  ViewCamera c;
  c.eye =
      focal + distance * core::Vec3(std::cos(yaw) * std::cos(pitch), std::sin(yaw) * std::cos(pitch), std::sin(pitch));
  const core::Vec3 forward = (focal - c.eye).normalized();
  const core::Vec3 right = forward.cross(core::Vec3::UnitZ()).normalized();
  c.axes.col(0) = right;
  c.axes.col(1) = forward.cross(right);
  c.axes.col(2) = forward;
  return c;
}

/// The interaction with rviz's camera broadcast as the ViewCamera display does, from the default view.
class InteractionSeen : public InteractionFixture
{
protected:
  void SetUp() override
  {
    view_ = defaultView();
    camera_timer_ = client_.nh().createWallTimer(ros::WallDuration(1.0 / 30), [this](const ros::WallTimerEvent&) {
      geometry_msgs::TransformStamped t;
      t.header.stamp = ros::Time::now();
      t.header.frame_id = "world";
      t.child_frame_id = "rviz_camera";
      t.transform.translation.x = view_.eye.x();
      t.transform.translation.y = view_.eye.y();
      t.transform.translation.z = view_.eye.z();
      const Eigen::Quaterniond q(view_.axes);
      t.transform.rotation.w = q.w();
      t.transform.rotation.x = q.x();
      t.transform.rotation.y = q.y();
      t.transform.rotation.z = q.z();
      broadcaster_.sendTransform(t);
    });
    turns_sub_ = client_.nh().subscribe<geometry_msgs::PoseStamped>(
        "view_turn", 10, [this](const geometry_msgs::PoseStamped::ConstPtr& p) { turns_.push_back(*p); });
    operations_sub_ = client_.nh().subscribe<Operation>(
        "operations", 100, [this](const Operation::ConstPtr& op) { operations_.push_back(*op); });
    InteractionFixture::SetUp();
    gesture_.eye = view_.eye;
    // With the camera known the drag plane faces the view.
    ASSERT_TRUE(waitFor([&] { return loadMenu() && viewFacing(); }, 10)) << "the drag plane does not face the view";
  }

  void TearDown() override
  {
    camera_timer_.stop();
    // Without the camera (gone after camera_timeout) the sheet's drag plane lies along it again.
    EXPECT_TRUE(waitFor([&] { return loadMenu() && !viewFacing(); }, 10));
  }

  bool viewFacing()
  {
    return !marker_.controls.empty() &&
           marker_.controls[0].orientation_mode == visualization_msgs::InteractiveMarkerControl::VIEW_FACING &&
           marker_.controls[0].independent_marker_orientation;
  }

  ViewCamera view_;
  tf2_ros::TransformBroadcaster broadcaster_;
  ros::WallTimer camera_timer_;
  ros::Subscriber turns_sub_, operations_sub_;
  std::vector<geometry_msgs::PoseStamped> turns_;
};

}  // namespace virtual_origami::test

// rostest: what paper_model answered `success` survives a crash, with `resume: false` as
// `make run` launches it; a journal that cannot be written refuses operations instead of
// answering them; a damaged journal keeps every line before the damage; a stopped solver holds
// up no other client.
#include <gtest/gtest.h>

#include <atomic>
#include <csignal>
#include <cstdlib>
#include <fstream>
#include <string>
#include <thread>

#include "ros_test_client.h"
#include "virtual_origami/core/data_folder.h"

using namespace virtual_origami;
using virtual_origami::test::PaperClient;
using virtual_origami::test::pidOf;
using virtual_origami::test::waitFor;

namespace
{
const std::string kJournal = core::defaultDataFolder() + "/session_origami.jsonl";

void crashOnly(const std::function<void()>& meanwhile)
{
  const int pid = pidOf("paper_model");
  ASSERT_GT(pid, 0);
  ASSERT_EQ(::kill(pid, SIGKILL), 0);
  if (meanwhile)
    meanwhile();
  ASSERT_TRUE(waitFor(
      [&] {
        const int now = pidOf("paper_model");
        return now > 0 && now != pid;
      },
      30.0));
  ASSERT_TRUE(ros::service::waitForService("/origami/crease", ros::Duration(30)));
}

/// Kills paper_model as a crash would and returns the first state its successor publishes;
/// `meanwhile` runs while no process has the journal open (launch's respawn_delay is 2 s).
PaperState crashModel(PaperClient& client, const std::function<void()>& meanwhile = {})
{
  const int received = client.received();
  crashOnly(meanwhile);
  return client.stateAfter(received);
}

/// Creases n vertical lines; returns the last acknowledged revision.
uint64_t creaseLines(PaperClient& client, int n, double from)
{
  uint64_t revision = 0;
  for (int i = 0; i < n; ++i)
  {
    const double x = from + 0.01 * i;
    const Crease c = client.crease(x, -0.1, x, 1.1);
    EXPECT_TRUE(c.response.success) << c.response.message;
    revision = c.response.revision;
  }
  return revision;
}

/// A stopped process continues when this goes out of scope, whatever the test did.
struct Stopped
{
  explicit Stopped(int pid) : pid_(pid)
  {
    ok = ::kill(pid_, SIGSTOP) == 0;
  }
  ~Stopped()
  {
    ::kill(pid_, SIGCONT);
  }
  int pid_;
  bool ok = false;
};
}  // namespace

TEST(Durability, ResumeFalseMeansANewSessionPerLaunchNotPerProcess)
{
  PaperClient client;
  ASSERT_TRUE(client.trigger("reset").response.success);
  const uint64_t acknowledged = creaseLines(client, 6, 0.1);
  const PaperState last = client.stateAt(acknowledged);
  // The respawned process is of the same launch: it resumes although resume is false.
  const PaperState back = crashModel(client);
  EXPECT_EQ(back.revision, acknowledged);
  EXPECT_EQ(back.vertices_folded, last.vertices_folded);
  EXPECT_EQ(back.edges, last.edges);
  const std_srvs::Trigger undone = client.trigger("undo");
  ASSERT_TRUE(undone.response.success) << undone.response.message;
  EXPECT_EQ(client.stateAt(acknowledged + 1).faces.size(), last.faces.size() - 1);
}

TEST(Durability, AnOperationThatCannotBeJournaledIsRefused)
{
  PaperClient client;
  const uint64_t before = creaseLines(client, 1, 0.3);
  const PaperState state = client.stateAt(before);
  if (std::system(("chattr +i " + kJournal + " 2>/dev/null").c_str()) != 0)
    GTEST_SKIP() << "chattr +i is not possible here (needs root on ext2/3/4): no way to make the journal unwritable";
  const Crease refused = client.crease(0.71, -0.1, 0.71, 1.1);
  EXPECT_FALSE(refused.response.success);
  EXPECT_NE(refused.response.message.find("disk"), std::string::npos) << refused.response.message;
  EXPECT_EQ(refused.response.revision, before);
  EXPECT_FALSE(client.trigger("undo").response.success);
  ros::WallDuration(0.3).sleep();
  ros::spinOnce();
  EXPECT_EQ(client.state().revision, before);
  EXPECT_EQ(client.state().edges, state.edges);
  // Writable again: journaling resumes by itself, and what it acknowledges survives a crash.
  ASSERT_EQ(std::system(("chattr -i " + kJournal).c_str()), 0);
  const uint64_t after = creaseLines(client, 2, 0.72);
  EXPECT_EQ(after, before + 2);
  const PaperState last = client.stateAt(after);
  const PaperState back = crashModel(client);
  EXPECT_EQ(back.revision, after);
  EXPECT_EQ(back.edges, last.edges);
  EXPECT_EQ(back.vertices_folded, last.vertices_folded);
}

TEST(Durability, ADamagedJournalKeepsEverythingBeforeTheDamage)
{
  PaperClient client;
  const uint64_t acknowledged = creaseLines(client, 2, 0.2);
  const PaperState last = client.stateAt(acknowledged);
  const PaperState back = crashModel(client, [&] {
    // Well-formed JSON that cannot be applied: a revision no history reaches, then a good-looking line.
    std::ofstream journal(kJournal, std::ios::app);
    journal << R"({"operation": {"kind": "undo", "revision": 1e308}})" << '\n'
            << R"({"operation": {"kind": "undo", "revision": )" << acknowledged + 2 << "}}\n";
  });
  EXPECT_EQ(back.revision, acknowledged);
  EXPECT_EQ(back.edges, last.edges);
  EXPECT_FALSE(back.notice.empty());
  EXPECT_NE(back.notice.find("line"), std::string::npos) << back.notice;
  // Folding goes on from there, and the notice goes with the next change.
  const uint64_t next = creaseLines(client, 1, 0.6);
  EXPECT_EQ(next, acknowledged + 1);
  EXPECT_TRUE(client.stateAt(next).notice.empty());
}

TEST(Durability, AStoppedSolverHoldsUpNoOtherClient)
{
  PaperClient client;
  ASSERT_TRUE(client.trigger("reset").response.success);
  // A degree-4 vertex: turning a face about a half crease drags the others through the solver.
  ASSERT_TRUE(client.crease(0.5, -0.1, 0.5, 1.1).response.success);
  const Crease half = client.crease(0.5, 0.5, 1.0, 0.8);
  ASSERT_TRUE(half.response.success);
  ASSERT_EQ(half.response.new_edges.size(), 1u);
  const int axis = half.response.new_edges[0];
  const Crease third = client.crease(0.5, 0.5, 0.0, 0.9);
  ASSERT_TRUE(third.response.success);
  const int solver = pidOf("spring_solver");
  ASSERT_GT(solver, 0);
  Rotate stalled;
  std::atomic<bool> returned{ false };
  std::thread rotating;
  {
    Stopped stop(solver);
    ASSERT_TRUE(stop.ok);
    rotating = std::thread([&] {
      PaperClient other;
      stalled = other.rotate(-1, axis, 0.9, 0.9, 0.3);
      returned = true;
    });
    ros::WallDuration(1.0).sleep();  // the rotation is waiting on the solver by now
    // Another client's crease is served meanwhile.
    const Crease crease = client.crease(0.25, -0.1, 0.25, 1.1);
    EXPECT_TRUE(crease.response.success) << crease.response.message;
    EXPECT_EQ(crease.response.revision, third.response.revision + 1);
    EXPECT_FALSE(returned) << "the rotation returned before the crease was served";
    // The rotation is refused once solver_timeout has passed, with the solver still stopped.
    rotating.join();
    EXPECT_FALSE(stalled.response.success);
    EXPECT_NE(stalled.response.message.find("answer"), std::string::npos) << stalled.response.message;
    EXPECT_EQ(stalled.response.revision, crease.response.revision);
  }
  // The solver goes on: so does folding.
  bool rotated = false;
  waitFor(
      [&] {
        rotated = client.rotate(-1, axis, 0.9, 0.9, 0.3).response.success;
        return rotated;
      },
      30.0);
  EXPECT_TRUE(rotated);
}

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "durability_rostest");
  ros::NodeHandle keep_alive;
  return RUN_ALL_TESTS();
}

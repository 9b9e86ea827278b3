// The paper_model node: owns the session, offers the services of SPEC §8, publishes the
// state, markers, operations and tf frames, and journals every change to disk.
#pragma once

#include <atomic>
#include <condition_variable>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include <dynamic_reconfigure/server.h>
#include <ros/ros.h>
#include <std_srvs/Trigger.h>
#include <tf2_ros/buffer.h>
#include <tf2_ros/static_transform_broadcaster.h>
#include <tf2_ros/transform_broadcaster.h>
#include <tf2_ros/transform_listener.h>
#include <virtual_origami/Crease.h>
#include <virtual_origami/DragVertex.h>
#include <virtual_origami/KeepBend.h>
#include <virtual_origami/FlatFold.h>
#include <virtual_origami/FoldByAssignment.h>
#include <virtual_origami/Load.h>
#include <virtual_origami/PaperModelConfig.h>
#include <virtual_origami/PinVertex.h>
#include <virtual_origami/Pull.h>
#include <virtual_origami/Rotate.h>
#include <virtual_origami/Save.h>
#include <virtual_origami/VertexTarget.h>

#include "virtual_origami/core/answer_budget.h"
#include "virtual_origami/core/data_folder.h"
#include "virtual_origami/core/model_file.h"
#include "virtual_origami/core/session.h"
#include "virtual_origami/core/session_journal.h"
#include "virtual_origami/ros/conversions.h"
#include "virtual_origami/ros/markers.h"

namespace virtual_origami
{
/// Services are served concurrently (run it under an AsyncSpinner): the model is locked only
/// while an operation is applied, and solver-bound operations are computed outside the lock, so a
/// crease never waits for another client's solve. Every change is journaled (and synced) before
/// it is committed and answered.
class PaperModelNode
{
public:
  /// Advertises the services at once; the session is read back from the journal on a thread
  /// of its own, and until then every service answers a "resuming" refusal.
  PaperModelNode(ros::NodeHandle nh, ros::NodeHandle private_nh);
  ~PaperModelNode();

private:
  bool crease(Crease::Request& req, Crease::Response& res);
  bool rotate(Rotate::Request& req, Rotate::Response& res);
  bool squash(std_srvs::Trigger::Request& req, std_srvs::Trigger::Response& res);
  bool undo(std_srvs::Trigger::Request& req, std_srvs::Trigger::Response& res);
  bool redo(std_srvs::Trigger::Request& req, std_srvs::Trigger::Response& res);
  bool reset(std_srvs::Trigger::Request& req, std_srvs::Trigger::Response& res);
  bool pin(PinVertex::Request& req, PinVertex::Response& res);
  bool pull(Pull::Request& req, Pull::Response& res);
  bool foldByAssignment(FoldByAssignment::Request& req, FoldByAssignment::Response& res);
  /// Fold on chosen creases (SPEC §3.7); a preview (commit false) shows the fold `fraction` of
  /// the way from the paper now (core::flatFoldFrame).
  bool flatFold(FlatFold::Request& req, FlatFold::Response& res);
  /// Drag a vertex (SPEC §3.6): the faces follow through the solver, the pins hold.
  bool dragVertex(DragVertex::Request& req, DragVertex::Response& res);
  bool keepBend(KeepBend::Request& req, KeepBend::Response& res);
  /// Strain colours and the preview budget, live (cfg/PaperModel.cfg).
  void reconfigure(PaperModelConfig& config, uint32_t level);
  bool load(Load::Request& req, Load::Response& res);
  bool save(Save::Request& req, Save::Response& res);

  /// Journals a change and commits it, then announces it on `operations` and publishes the
  /// state; refused (nothing changed) when the journal cannot record it. Holds `mutex_`.
  /// `event`: its journal line when it was serialised ahead, outside the lock.
  core::Status commit(core::Change change, const std::string& what, const ros::Time& stamp = ros::Time(0),
                      const core::JournalEvent* event = nullptr);
  /// Computes an operation on a copy of the model outside the lock, then commits it (or shows it
  /// as the preview) if nobody changed the model meanwhile; computed again when somebody did,
  /// the last of `solve_attempts_` tries under the lock, so that it lands.
  /// `revision`: the one the commit made, or the model's when nothing was committed. Pins that
  /// change meanwhile make it compute again with them held, or, `for_these_pins` (a cycle of
  /// pins following their frames), refuse.
  template <class Result>
  core::Expected<core::Computed<Result>>
  computeAndCommit(const std::function<core::Expected<core::Computed<Result>>(core::Workspace)>& compute, bool commit_it,
                   const std::string& what, uint64_t& revision, const ros::Time& stamp = ros::Time(0),
                   bool for_these_pins = false);
  /// `stamp` zero: now (a pull is stamped with the tf data it followed).
  void publishState(const ros::Time& stamp = ros::Time(0));
  /// When the committed paper is one the preview driver has not seen (another pattern, new
  /// creases, other pins), has warmUpPreviews prepare the driver for it (mutex_ held).
  void scheduleWarmUp();
  /// The warm-up thread: a preview frame of the last paper scheduled, 1 % on from where its
  /// creases are, by a clone of the preview driver on a copy, dropped, so that what the driver's
  /// clones share of a pattern (the Gauss-Newton matrix's analysis and assembly plan) is ready
  /// before the user's first preview asks for a frame. Skipped once a preview came first.
  void warmUpPreviews();
  void publishMarkers(const core::Paper& paper);
  /// The pinned points and, unless switched off, a frame per face (broadcastFaces).
  void broadcastFrames(const ros::TimerEvent&);
  void broadcastFaces(const ros::Time& stamp);
  /// Each cycle: the vertices pinned to tf frames are pulled to their frames' origins and
  /// the solver re-solves the paper around every pin.
  void followPins(const ros::TimerEvent&);
  std::vector<int> pinnedVertices() const;
  /// Reads the journal back (or starts a new one), then swaps the session in and ends resuming.
  void restoreOrStart(const std::string& journal, const std::string& run_id, bool resume);
  /// The solver, snap settings, history limit and drivers, on the session as it is.
  void configureSession();
  /// Whether the session is still being resumed, after a short wait for it (so that a small
  /// journal never makes a client try again).
  bool stillResuming();
  /// True, with the refusal in `res`, while the session is being resumed.
  template <class Response>
  bool refuseWhileResuming(Response& res)
  {
    if (!stillResuming())
      return false;
    res.success = false;
    res.message = "resuming: the session is being read back from its journal; nothing was done, try again shortly";
    return true;
  }
  bool answer(const core::Status& status, const std::string& done, std_srvs::Trigger::Response& res);

  ros::NodeHandle nh_;
  std::mutex mutex_;  // the session, journal, pins and what follows them
  std::optional<core::DataFolder> folder_;
  core::Session session_;
  std::string notice_;  // said on `state` until the next change
  int solve_attempts_ = 3;
  /// A fold-by-assignment commit straining the faces more than this is refused unless kept.
  double max_assignment_strain_ = 1e-3;
  core::SessionJournal journal_;
  Pins pins_;
  uint64_t pins_changes_ = 0;  // counts every pin, release and clearing of the pins
  std::map<int, core::Vec3> pulled_to_;  // where each followed pin last pulled its vertex (paper frame)
  /// The last cycle the faces could not follow: the same targets with the same held vertices on
  /// the same revision are not solved again (a frame standing still where it cannot be reached).
  struct RefusedPull
  {
    uint64_t revision = 0;
    std::vector<core::PullTarget> targets;
    std::vector<int> held;
  };
  std::optional<RefusedPull> refused_;
  MarkerStyle style_;
  std::string world_frame_;
  double size_ = 1.0;
  ros::Publisher state_pub_, markers_pub_, operations_pub_;
  /// While the curved model bends the sheet after a dragged vertex (`curved_drag`), the flat
  /// paper is drawn faded: the bent sheet is what the user holds.
  ros::Subscriber curved_drag_sub_;
  std::atomic<bool> faded_{ false };
  uint64_t faded_revision_ = 0;  // the revision the paper was faded on
  std::vector<ros::ServiceServer> services_;
  tf2_ros::StaticTransformBroadcaster static_tf_;
  tf2_ros::TransformBroadcaster tf_;
  tf2_ros::Buffer tf_buffer_;
  tf2_ros::TransformListener tf_listener_{ tf_buffer_ };  // its own thread: lookups may wait in a service
  double pin_frame_timeout_ = 1.0;                        // how long `pin` waits for an unknown frame to appear
  bool face_frames_ = true;
  int face_frames_max_ = 1000;  // larger models broadcast no face frames
  std::string face_frame_prefix_;
  ros::Timer pin_timer_, follow_timer_;
  /// Folding by assignment: a driver that converges for commits, one with a time budget for
  /// previews. A driver keeps what it learnt of a pattern between calls, so one call at a time.
  std::shared_ptr<core::CreaseDriver> crease_driver_, preview_driver_;
  /// A preview's whole answer keeps to fold_preview_seconds: its frame's solve gets what the
  /// rest of the answer leaves (guarded by drivers_mutex_).
  core::AnswerBudget preview_budget_;
  std::atomic<uint64_t> preview_frames_{ 0 };  // preview frames computed so far
  std::mutex drivers_mutex_;
  /// The preview driver's warm-up (warmUpPreviews): the paper it waits for and the preview
  /// frames there had been when it was scheduled, guarded by warm_mutex_; the signature of the
  /// last paper scheduled (mutex_).
  std::mutex warm_mutex_;
  std::condition_variable warm_wanted_;
  std::optional<core::Paper> warm_paper_;
  std::vector<int> warm_held_;
  uint64_t warm_after_frames_ = 0;
  bool warm_stop_ = false;
  uint64_t warmed_signature_ = 0;
  std::thread warm_thread_;
  std::unique_ptr<dynamic_reconfigure::Server<PaperModelConfig>> reconfigure_server_;
  // What configureSession puts on a resumed session.
  core::SnapSettings snap_;
  std::shared_ptr<core::ShapeSolver> solver_;
  size_t history_limit_ = 0;
  double turn_preview_tolerance_ = 1e-8;  // Session::setTurnPreviewTolerance
  /// Load refuses files over these before the expensive work (parameters max_load_vertices,
  /// max_face_vertices, max_load_mb).
  core::ModelLimits load_limits_;
  size_t max_load_bytes_ = size_t{ 64 } << 20;
  /// Events after the journal's header, in bytes, that make a snapshot once they outweigh it too.
  uint64_t journal_snapshot_bytes_ = uint64_t{ 64 } << 20;
  std::mutex resume_mutex_;
  std::condition_variable resumed_;
  bool resuming_ = true;  // guarded by resume_mutex_
  std::thread resume_thread_;
};

}  // namespace virtual_origami

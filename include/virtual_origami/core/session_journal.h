// A session's history on disk, so that nothing a user did is lost when a node restarts or
// crashes: one JSON line per event, written and synced to disk before it is acknowledged.
#pragma once

#include <algorithm>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "virtual_origami/core/result.h"
#include "virtual_origami/core/session.h"

namespace virtual_origami::core
{
/// Bit-exact JSON of a paper (doubles printed to round-trip).
std::string formatPaperJson(const Paper& paper);
Expected<Paper> parsePaperJson(const std::string& text);

/// One operation's journal event. A commit's line holds what it changed in the state before it
/// (paper_delta.h): made here, ahead of the append, when `state_before` is given (for a large
/// model serialising is most of an append's cost, and a node does it outside its lock); else
/// the state is kept (copied) and the line made at `append(session, event)`, from the session's
/// paper. A load or reset (a new paper) is always written whole, made here.
struct JournalEvent
{
  Operation operation;
  bool has_state = false;  // a commit carries the state it makes; an undo or redo none
  std::string line;        // empty when it is made at the append, from `state`
  std::optional<Paper> state;  // a commit's state, kept for the append to write
  /// The fingerprints (paperFingerprint) of the state a delta line applies to, and of the state
  /// a commit makes.
  std::optional<uint64_t> base_fingerprint;
  uint64_t fingerprint = 0;
};
JournalEvent journalEvent(const Operation& op, const Paper* state_after, const Paper* state_before = nullptr);

/// Appends a session's events to a file: a header line with the whole history so far (a
/// snapshot: the paper whole, each undo and redo state as a delta from its neighbour nearer the
/// paper), then for each operation logged after it a commit (with what it changed, or the whole
/// state it made) or an undo/redo. Restoring reads the snapshot and applies the events in order.
///
/// A failed write leaves the journal unhealthy: it appends nothing more to that file (a torn
/// line must stay the last one) until it is started again, which the appends taking the
/// session do by themselves.
class SessionJournal
{
public:
  /// Starts a new journal for `session` at `path`, writing its whole history so far. The
  /// header is written to a new file beside `path`, synced and renamed over it, so `path`
  /// always holds a whole journal. `run_id` (roslaunch's /run_id) tells a respawn within the
  /// same launch from a new launch when the journal is read back.
  Status start(const std::string& path, const Session& session, const std::string& run_id = "");
  /// Journals `op` before it is committed: `state_after` is the paper it makes (null for an
  /// undo or redo), written whole (the journal does not hold the state before it). Succeeds only once the line is
  /// written (and synced, see setSync); on a failure the caller must not commit `op`.
  Status append(const Operation& op, const Paper* state_after);
  /// The same for `before`, the session `op` is about to change: a commit is written as what it
  /// changes in `before`'s paper. A journal that is unhealthy or out of step with `before` (its
  /// revision, history depths or paper) is first started again from it.
  Status append(const Session& before, const Operation& op, const Paper* state_after);
  /// The same with the line serialised ahead (journalEvent); a delta made from another state
  /// than the one the journal's last line leaves is refused.
  Status append(const JournalEvent& event);
  Status append(const Session& before, const JournalEvent& event);
  /// Appends the operations `session` logged since the journal last wrote, after they were
  /// committed: a commit's event carries the session's current state, so call it after every
  /// operation. A journal that is unhealthy or cannot catch up is started again from `session`.
  Status record(const Session& session);

  /// Whether each event is fsync()ed before the append returns (default true). Without it a
  /// crash of the machine, not of the node, can lose the last events. start() always syncs.
  void setSync(bool sync) { sync_ = sync; }
  bool sync() const { return sync_; }
  /// Whether the events after the header outweigh it (and `min_bytes`): then a snapshot (start
  /// again from the session as it is) keeps what a restart reads within twice a header, the
  /// history the session holds (bounded by its history limit), not every state it ever made.
  /// Weighed by what a restart makes of them, not by their bytes: every state it holds in
  /// memory counts as that state written whole (the paper's bytes at the last start), however
  /// small its delta, so many small deltas cannot pile up states a restart must hold.
  bool wantsSnapshot(uint64_t min_bytes = uint64_t{ 64 } << 20) const
  {
    return healthy_ && event_weight_ > std::max(header_weight_, min_bytes);
  }
  /// Those weights: of the header (its bytes, or the states it holds, each as the paper written
  /// whole, whichever is more) and of the events after it.
  uint64_t headerWeight() const { return header_weight_; }
  uint64_t eventWeight() const { return event_weight_; }
  /// Starts again at the same path from `session`, which must be the session the journal
  /// recorded (the events so far become its header).
  Status snapshot(const Session& session)
  {
    return start(path_, session, run_id_);
  }
  /// Bytes of the header and of the events after it.
  uint64_t headerBytes() const
  {
    return header_bytes_;
  }
  uint64_t eventBytes() const
  {
    return written_ - header_bytes_;
  }

  /// For tests that cut a header short (a snapshot torn by a crash or a failing disk): a header
  /// is written in chunks of `chunk_bytes`, and after each `observer(written, total)` is called;
  /// false makes the write fail there as a full disk would. No observer: one write.
  void setHeaderWriteObserver(std::function<bool(uint64_t written, uint64_t total)> observer, size_t chunk_bytes)
  {
    header_observer_ = std::move(observer);
    header_chunk_bytes_ = std::max<size_t>(chunk_bytes, 1);
  }

  /// False before a successful start and after a failed write, until the next start.
  bool healthy() const { return healthy_; }
  const std::string& path() const { return path_; }
  const std::string& runId() const { return run_id_; }

private:
  /// An open file, closed when it goes; moved, never copied.
  class Descriptor
  {
  public:
    Descriptor() = default;
    explicit Descriptor(int fd) : fd_(fd) {}
    Descriptor(Descriptor&& other) noexcept : fd_(other.release()) {}
    Descriptor& operator=(Descriptor&& other) noexcept;
    Descriptor(const Descriptor&) = delete;
    Descriptor& operator=(const Descriptor&) = delete;
    ~Descriptor() { reset(); }
    int get() const { return fd_; }
    int release();
    void reset();

  private:
    int fd_ = -1;
  };

  Status writeEvent(const std::string& line);
  Status fail(const std::string& message);
  bool inStepWith(const Session& session) const;
  Status startUnlessInStep(const Session& before);
  bool canCatchUp(const History& history) const;

  std::string path_;
  std::string run_id_;
  Descriptor file_;
  bool healthy_ = false;
  bool sync_ = true;
  std::string failure_;       // why it is unhealthy
  uint64_t written_ = 0;      // bytes of whole lines in the file
  uint64_t header_bytes_ = 0;  // of its first line
  uint64_t state_bytes_ = 0;   // of the header's paper, written whole
  uint64_t header_weight_ = 0, event_weight_ = 0;  // see wantsSnapshot
  size_t recorded_ = 0;       // operations of the session's log in the journal
  uint64_t revision_ = 0;     // the revision the journal's last line leaves the session at
  /// Fingerprints of the state the last line leaves and of those undo and redo go back and
  /// forth through: a delta is written only from the state it applies to.
  uint64_t fingerprint_ = 0;
  std::vector<uint64_t> undo_fingerprints_, redo_fingerprints_;
  std::function<bool(uint64_t, uint64_t)> header_observer_;
  size_t header_chunk_bytes_ = 0;
};

/// What a journal holds, read up to its first bad line.
struct JournalRecovery
{
  History history;
  std::string run_id;  // empty when the journal has none
  size_t lines_read = 0;  // lines in `history`, the header included
  /// In words, the bad line, why, and the lines dropped from it on; empty for a whole journal.
  std::vector<std::string> dropped;
};

/// Reads the journal at `path`: a journal written before deltas (version 1, every state whole)
/// reads as it did; a version newer than this reader knows is refused, saying so. A bad header
/// is a failure (nothing can be recovered); any
/// later bad line (torn, not JSON, incomplete, an impossible undo or redo, a revision that is
/// not the previous one + 1, a delta that does not give the state it recorded) ends the history before it and is
/// described in `dropped`.
Expected<JournalRecovery> recoverJournal(const std::string& path);
/// recoverJournal's history alone (what was dropped is not reported).
Expected<History> readJournal(const std::string& path);

/// A name beside `path` for keeping an old journal aside, that nothing has yet:
/// `<path>.<UTC yyyymmddThhmmss.nnnnnnnnn>.<pid>[.<n>].old`.
std::string keepAsideName(const std::string& path);

}  // namespace virtual_origami::core

#include "virtual_origami/core/session_journal.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <stdexcept>
#include <type_traits>
#include <utility>

#include <nlohmann/json.hpp>

#include "virtual_origami/core/paper_delta.h"

namespace virtual_origami::core
{
using nlohmann::json;

namespace
{
/// A number that must be an integer of the given type. nlohmann's get<int>() converts any number,
/// and a float beyond the integer's range makes that undefined behaviour (found by fuzzing).
struct NotAnInteger : std::runtime_error
{
  using std::runtime_error::runtime_error;
};

template <class Integer>
Integer integer(const json& value)
{
  using Limits = std::numeric_limits<Integer>;
  if (value.is_number_unsigned())
  {
    const uint64_t u = value.get<uint64_t>();
    if (u <= static_cast<uint64_t>(Limits::max()))
      return static_cast<Integer>(u);
  }
  else if (value.is_number_integer())
  {
    const int64_t i = value.get<int64_t>();
    if (std::is_unsigned_v<Integer> ? i >= 0
                                    : i >= static_cast<int64_t>(Limits::min()) && i <= static_cast<int64_t>(Limits::max()))
      return static_cast<Integer>(i);
  }
  throw NotAnInteger(value.dump() + " is not an integer in range");
}

Expected<Paper> paperFromJson(const json& j)
{
  try
  {
    Paper paper;
    const json& cp = j.at("vertices_crease_pattern");
    const json& folded = j.at("vertices_folded");
    if (cp.size() != folded.size())
      return Expected<Paper>::failure("vertices_crease_pattern and vertices_folded differ in length");
    for (size_t i = 0; i < cp.size(); ++i)
    {
      Vertex v;
      v.crease_pattern = Vec2(cp[i].at(0).get<double>(), cp[i].at(1).get<double>());
      v.folded = Vec3(folded[i].at(0).get<double>(), folded[i].at(1).get<double>(), folded[i].at(2).get<double>());
      paper.vertices.push_back(v);
    }
    for (const json& e : j.at("edges"))
    {
      Edge edge;
      edge.vertices = { integer<int>(e.at(0)), integer<int>(e.at(1)) };
      const auto assignment = assignmentFromLetter(e.at(2).get<std::string>());
      if (!assignment)
        return Expected<Paper>::failure("unknown assignment " + e.at(2).dump());
      edge.assignment = *assignment;
      edge.fold_angle = e.at(3).get<double>();
      edge.split = e.size() > 4 && e.at(4).get<bool>();
      if (e.size() > 5)
        edge.target_angle = e.at(5).get<double>();
      paper.edges.push_back(edge);
    }
    for (const json& f : j.at("faces"))
    {
      Face face;
      for (const json& v : f)
        face.vertices.push_back(integer<int>(v));
      paper.faces.push_back(face);
    }
    for (const json& o : j.at("face_orders"))
      paper.face_orders.push_back({ integer<int>(o.at(0)), integer<int>(o.at(1)), integer<int>(o.at(2)) });
    paper.sheet_area = j.at("sheet_area").get<double>();
    const Status linked = linkTopology(paper);
    if (!linked)
      return Expected<Paper>::failure(linked.message());
    return paper;
  }
  catch (const std::exception& e)  // json::exception, NotAnInteger
  {
    return Expected<Paper>::failure(std::string("malformed paper: ") + e.what());
  }
}

json operationToJson(const Operation& op)
{
  const auto point = [](const Vec3& p) { return json::array({ p.x(), p.y(), p.z() }); };
  json j{ { "kind", kindName(op.kind) }, { "revision", op.revision } };
  switch (op.kind)
  {
    case Operation::Kind::Crease:
      j["start"] = point(op.crease.start);
      j["end"] = point(op.crease.end);
      if (op.crease.eye)
        j["eye"] = point(*op.crease.eye);
      j["snap"] = op.crease.snap;
      break;
    case Operation::Kind::Rotate:
      j["face"] = op.rotate.face;
      j["axis_edge"] = op.rotate.axis_edge;
      j["click"] = point(op.rotate.click);
      j["angle"] = op.rotate.angle;
      j["carry_stack"] = op.rotate.carry_stack;  // absent in journals written before: true
      break;
    case Operation::Kind::FlatFold:
      j["creases"] = json::array();
      for (const CreaseLineAngle& line : op.flat_fold.creases)
        j["creases"].push_back({ { "start", { line.start.x(), line.start.y() } },
                                 { "end", { line.end.x(), line.end.y() } },
                                 { "angle", line.angle } });
      j["fixed"] = { op.flat_fold.fixed_point.x(), op.flat_fold.fixed_point.y() };
      break;
    case Operation::Kind::DragVertex:
      j["vertex"] = op.drag.vertex;
      j["position"] = point(op.drag.position);
      break;
    case Operation::Kind::Reset:
      j["size"] = op.size;
      break;
    case Operation::Kind::Load:
      j["path"] = op.path;
      break;
    case Operation::Kind::AssignmentFold:
      j["fraction"] = op.fraction;
      break;
    case Operation::Kind::KeepBend:
    {
      json points = json::array(), triangles = json::array(), positions = json::array();
      for (const Vec2& p : op.bend.points)
        points.push_back({ p.x(), p.y() });
      for (const std::array<int, 3>& t : op.bend.triangles)
        triangles.push_back({ t[0], t[1], t[2] });
      for (const Vec3& p : op.bend.positions)
        positions.push_back(point(p));
      j["points"] = std::move(points);
      j["triangles"] = std::move(triangles);
      j["positions"] = std::move(positions);
      break;
    }
    case Operation::Kind::Pull:
      j["pull"] = json::array();
      for (const PullTarget& target : op.pull)
        j["pull"].push_back({ { "vertex", target.vertex }, { "position", point(target.position) } });
      break;
    default:
      break;
  }
  return j;
}

Expected<Operation> operationFromJson(const json& j)
{
  const auto point = [](const json& p) { return Vec3(p.at(0).get<double>(), p.at(1).get<double>(), p.at(2).get<double>()); };
  const auto point2 = [](const json& p) { return Vec2(p.at(0).get<double>(), p.at(1).get<double>()); };
  try
  {
    Operation op;
    const std::string kind = j.at("kind").get<std::string>();
    bool known = false;
    for (Operation::Kind k : { Operation::Kind::Crease, Operation::Kind::Rotate, Operation::Kind::Squash,
                               Operation::Kind::Undo, Operation::Kind::Redo, Operation::Kind::Reset,
                               Operation::Kind::Load, Operation::Kind::Pull, Operation::Kind::AssignmentFold,
                               Operation::Kind::FlatFold, Operation::Kind::DragVertex, Operation::Kind::KeepBend })
      if (kind == kindName(k))
      {
        op.kind = k;
        known = true;
      }
    if (!known)
      return Expected<Operation>::failure("unknown operation kind \"" + kind + "\"");
    op.revision = integer<uint64_t>(j.at("revision"));
    if (op.kind == Operation::Kind::Crease)
    {
      op.crease.start = point(j.at("start"));
      op.crease.end = point(j.at("end"));
      if (j.contains("eye"))
        op.crease.eye = point(j.at("eye"));
      op.crease.snap = j.at("snap").get<bool>();
    }
    else if (op.kind == Operation::Kind::Rotate)
    {
      op.rotate.face = integer<int>(j.at("face"));
      op.rotate.axis_edge = integer<int>(j.at("axis_edge"));
      op.rotate.click = point(j.at("click"));
      op.rotate.angle = j.at("angle").get<double>();
      op.rotate.carry_stack = j.contains("carry_stack") ? j.at("carry_stack").get<bool>() : true;
    }
    else if (op.kind == Operation::Kind::FlatFold)
    {
      for (const json& line : j.at("creases"))
        op.flat_fold.creases.push_back(
            { point2(line.at("start")), point2(line.at("end")), line.at("angle").get<double>() });
      op.flat_fold.fixed_point = point2(j.at("fixed"));
    }
    else if (op.kind == Operation::Kind::DragVertex)
      op.drag = { integer<int>(j.at("vertex")), point(j.at("position")) };
    else if (op.kind == Operation::Kind::Reset)
      op.size = j.at("size").get<double>();
    else if (op.kind == Operation::Kind::Load)
      op.path = j.at("path").get<std::string>();
    else if (op.kind == Operation::Kind::AssignmentFold)
      op.fraction = j.at("fraction").get<double>();
    else if (op.kind == Operation::Kind::KeepBend)
    {
      for (const json& p : j.at("points"))
        op.bend.points.push_back(point2(p));
      for (const json& t : j.at("triangles"))
        op.bend.triangles.push_back({ integer<int>(t.at(0)), integer<int>(t.at(1)), integer<int>(t.at(2)) });
      for (const json& p : j.at("positions"))
        op.bend.positions.push_back(point(p));
    }
    else if (op.kind == Operation::Kind::Pull)
      for (const json& target : j.at("pull"))
        op.pull.push_back({ integer<int>(target.at("vertex")), point(target.at("position")) });
    return op;
  }
  catch (const std::exception& e)  // json::exception, NotAnInteger
  {
    return Expected<Operation>::failure(std::string("malformed operation: ") + e.what());
  }
}

Status readPapers(const json& list, std::vector<Paper>& papers)
{
  for (const json& p : list)
  {
    Expected<Paper> paper = paperFromJson(p);
    if (!paper)
      return failure(paper.message());
    papers.push_back(std::move(*paper));
  }
  return success();
}

/// The states undo (or redo) goes through, each a delta from its neighbour nearer the paper:
/// the last from the paper, every other from the one after it.
Status readStateChain(const json& list, const Paper& paper, std::vector<Paper>& states)
{
  if (!list.is_array())
    return failure("a list of undo or redo states is not a list");
  states.resize(list.size());
  const Paper* next = &paper;
  for (size_t k = list.size(); k-- > 0;)
  {
    Expected<Paper> state = applyPaperDelta(*next, list[k]);
    if (!state)
      return failure(state.message());
    states[k] = std::move(*state);
    next = &states[k];
  }
  return success();
}

std::string stateChainText(const std::vector<Paper>& states, const Paper& paper)
{
  std::string list = "[";
  for (size_t k = 0; k < states.size(); ++k)
  {
    if (k > 0)
      list += ',';
    list += formatPaperDelta(k + 1 < states.size() ? states[k + 1] : paper, states[k]);
  }
  return list + "]";
}

/// Version 1: every state whole. Version 2: undo and redo states as delta chains, commits as
/// deltas or whole.
constexpr int kJournalVersion = 2;

Status readHeader(const json& j, History& history)
{
  if (!j.is_object() || j.value("journal", "") != "virtual_origami session")
    return failure("not a virtual_origami journal header");
  try
  {
    const int version = integer<int>(j.at("version"));
    if (version < 1 || version > kJournalVersion)
      return failure("journal version " + std::to_string(version) + ", which this version of virtual_origami " +
                     "does not read (it reads versions 1 to " + std::to_string(kJournalVersion) + ")");
    Expected<Paper> paper = paperFromJson(j.at("paper"));
    if (!paper)
      return failure(paper.message());
    history.paper = std::move(*paper);
    history.revision = integer<uint64_t>(j.at("revision"));
    for (const json& op : j.at("log"))
    {
      const Expected<Operation> parsed = operationFromJson(op);
      if (!parsed)
        return failure(parsed.message());
      history.log.push_back(*parsed);
    }
    if (version == 1)
    {
      const Status undo = readPapers(j.at("undo"), history.undo);
      return undo ? readPapers(j.at("redo"), history.redo) : undo;
    }
    const Status undo = readStateChain(j.at("undo"), history.paper, history.undo);
    return undo ? readStateChain(j.at("redo"), history.paper, history.redo) : undo;
  }
  catch (const std::exception& e)  // json::exception, NotAnInteger
  {
    return failure(std::string("malformed header: ") + e.what());
  }
}

bool stepsThroughHistory(Operation::Kind kind) { return kind == Operation::Kind::Undo || kind == Operation::Kind::Redo; }

/// Why `line`, an event after the header, cannot go on `history`; empty when it can, and then
/// `history` has it. `torn`: the line lacks its newline.
std::string readEvent(const std::string& line, bool torn, History& history)
{
  if (torn)
    return "torn (a write cut short)";
  const json j = json::parse(line, nullptr, false);
  if (j.is_discarded())
    return line.empty() ? "empty" : "not JSON";
  if (!j.is_object() || !j.contains("operation"))
    return "no operation";
  Expected<Operation> op = operationFromJson(j["operation"]);
  if (!op)
    return op.message();
  // The session numbers every commit, undo and redo one past the last (session.cpp), and the
  // header's revision is the last of its log: a gap or repeat means lost or replayed events.
  if (history.revision == std::numeric_limits<uint64_t>::max() || op->revision != history.revision + 1)
    return "revision " + std::to_string(op->revision) + " does not follow revision " + std::to_string(history.revision);
  if (stepsThroughHistory(op->kind))
  {
    auto& from = op->kind == Operation::Kind::Undo ? history.undo : history.redo;
    auto& to = op->kind == Operation::Kind::Undo ? history.redo : history.undo;
    if (from.empty())
      return std::string("nothing to ") + kindName(op->kind);
    to.push_back(std::move(history.paper));
    history.paper = std::move(from.back());
    from.pop_back();
  }
  else
  {
    // What the commit changed, or (journals before deltas, and commits journaled without the
    // state before them) the whole state it made.
    if (!j.contains("paper") && !j.contains("delta"))
      return "a commit without its state";
    Expected<Paper> paper =
        j.contains("delta") ? applyPaperDelta(history.paper, j["delta"]) : paperFromJson(j["paper"]);
    if (!paper)
      return paper.message();
    history.undo.push_back(std::move(history.paper));
    history.redo.clear();
    history.paper = std::move(*paper);
  }
  history.revision = op->revision;
  history.log.push_back(std::move(*op));
  return "";
}

/// One line of the journal. A string that is not UTF-8 (a loaded file's name) makes dump()
/// throw; its bad bytes are replaced instead, the event is worth more than the exact name.
std::string journalLine(const json& j) { return j.dump(-1, ' ', false, json::error_handler_t::replace) + '\n'; }

/// Writes all of `data`, going on after short writes and signals; false with `error` set if not.
bool writeAll(int fd, const char* data, size_t size, int& error)
{
  for (size_t done = 0; done < size;)
  {
    const ssize_t n = ::write(fd, data + done, size - done);
    if (n < 0 && errno == EINTR)
      continue;
    if (n <= 0)
    {
      error = n < 0 ? errno : EIO;
      return false;
    }
    done += static_cast<size_t>(n);
  }
  return true;
}

/// A rename is on disk only once the folder holding it is synced.
bool syncFolderOf(const std::string& path, int& error)
{
  const std::filesystem::path folder = std::filesystem::path(path).parent_path();
  const int fd = ::open(folder.empty() ? "." : folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0)
  {
    error = errno;
    return false;
  }
  // Some file systems cannot sync a folder (EINVAL); theirs is as durable as it gets.
  const bool synced = ::fsync(fd) == 0 || errno == EINVAL;
  error = errno;
  ::close(fd);
  return synced;
}
}  // namespace

std::string formatPaperJson(const Paper& paper)
{
  return formatPaperText(paper);
}

Expected<Paper> parsePaperJson(const std::string& text)
{
  const json j = json::parse(text, nullptr, false);
  if (j.is_discarded())
    return Expected<Paper>::failure("invalid JSON");
  return paperFromJson(j);
}

SessionJournal::Descriptor& SessionJournal::Descriptor::operator=(Descriptor&& other) noexcept
{
  if (this != &other)
  {
    reset();
    fd_ = other.release();
  }
  return *this;
}

int SessionJournal::Descriptor::release() { return std::exchange(fd_, -1); }

void SessionJournal::Descriptor::reset()
{
  if (fd_ >= 0)
    ::close(fd_);
  fd_ = -1;
}

namespace
{
/// Removes the temporary headers (`<path>.tmp.<pid>.<n>`) that processes killed while writing
/// one left: each holds up to a whole history, and nothing reads them. A live process's is
/// left alone.
void removeLeftTemporaries(const std::string& path)
{
  const std::filesystem::path journal(path);
  const std::string prefix = journal.filename().string() + ".tmp.";
  std::error_code error;
  const std::filesystem::path folder = journal.has_parent_path() ? journal.parent_path() : ".";
  for (std::filesystem::directory_iterator it(folder, error), end; !error && it != end; it.increment(error))
  {
    const std::string name = it->path().filename().string();
    if (name.compare(0, prefix.size(), prefix) != 0)
      continue;
    const size_t dot = name.find('.', prefix.size());
    const std::string digits = name.substr(prefix.size(), dot == std::string::npos ? dot : dot - prefix.size());
    if (digits.empty() || digits.size() > 9 || digits.find_first_not_of("0123456789") != std::string::npos)
      continue;
    const pid_t pid = static_cast<pid_t>(std::stol(digits));
    // One of this process's pid is from an earlier process (pid namespaces reuse it): a start
    // that fails removes its own. Only files a write left: a link there is not the journal's.
    if ((pid == ::getpid() || (::kill(pid, 0) != 0 && errno == ESRCH)) && it->is_regular_file(error) &&
        !it->is_symlink(error))
      ::unlink(it->path().c_str());
  }
}
}  // namespace

Status SessionJournal::start(const std::string& path, const Session& session, const std::string& run_id)
{
  file_.reset();
  healthy_ = false;
  // Kept even when starting fails: the next append starts again at the same place.
  path_ = path;
  run_id_ = run_id;
  // The header holds the whole history so far; events follow it.
  const History& h = session.history();
  // Neighbouring states differ by one operation: each undo and redo state is written as what
  // it changes in its neighbour nearer the paper, the paper alone whole.
  json log = json::array();
  for (const Operation& op : h.log)
    log.push_back(operationToJson(op));
  json header{ { "journal", "virtual_origami session" },
               { "version", kJournalVersion },
               { "revision", h.revision },
               { "log", log } };
  if (!run_id.empty())
    header["run_id"] = run_id;
  // The paper (its size weighs the states a restart holds) and the delta chains (text already,
  // formatPaperDelta) are spliced in before the closing brace.
  const std::string paper = formatPaperText(h.paper);
  std::string line = journalLine(header);
  line.resize(line.size() - 2);
  line += ",\"paper\":" + paper + ",\"undo\":" + stateChainText(h.undo, h.paper) +
          ",\"redo\":" + stateChainText(h.redo, h.paper) + "}\n";

  // The new journal is written beside the old one and renamed over it: a crash while the
  // header is written (it holds the whole history) must not leave a truncated journal and
  // lose the session. paper_model starts one on every (re)start. Found by killing it -9.
  // The name is new each time and opened exclusively without following links, so neither
  // a stale file nor a link planted at that name is written through.
  removeLeftTemporaries(path);
  std::string temporary;
  Descriptor file;
  int error = 0;
  for (unsigned attempt = 0; file.get() < 0 && attempt < 1000; ++attempt)
  {
    temporary = path + ".tmp." + std::to_string(::getpid()) + "." + std::to_string(attempt);
    const int fd = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0644);
    error = errno;
    file = Descriptor(fd);
    if (fd < 0 && error != EEXIST)
      break;
  }
  if (file.get() < 0)
    return fail("cannot write the journal " + path + ": cannot create " + temporary + ": " + std::strerror(error));
  const auto discard = [&](const std::string& what, int why) {
    ::unlink(temporary.c_str());
    return fail("cannot write the journal " + path + ": " + what + ": " + std::strerror(why));
  };
  for (size_t done = 0; done < line.size();)
  {
    const size_t chunk = header_observer_ ? std::min(header_chunk_bytes_, line.size() - done) : line.size();
    if (!writeAll(file.get(), line.data() + done, chunk, error))
      return discard("writing " + temporary, error);
    done += chunk;
    if (header_observer_ && !header_observer_(done, line.size()))
      return discard("writing " + temporary, ENOSPC);
  }
  // Synced before the rename: a rename that reaches the disk before the data would leave an
  // empty journal after a power cut.
  if (::fsync(file.get()) != 0)
    return discard("syncing " + temporary, errno);
  if (::rename(temporary.c_str(), path.c_str()) != 0)
    return discard("renaming " + temporary + " over it", errno);
  if (!syncFolderOf(path, error))
    return fail("cannot write the journal " + path + ": syncing its folder: " + std::strerror(error));

  // The descriptor now names the journal itself; events are written after the header.
  file_ = std::move(file);
  written_ = line.size();
  header_bytes_ = line.size();
  state_bytes_ = paper.size();
  header_weight_ = std::max<uint64_t>(header_bytes_, state_bytes_ * (1 + h.undo.size() + h.redo.size()));
  event_weight_ = 0;
  recorded_ = h.log.size();
  revision_ = h.revision;
  fingerprint_ = paperFingerprint(h.paper);
  undo_fingerprints_.clear();
  redo_fingerprints_.clear();
  for (const Paper& p : h.undo)
    undo_fingerprints_.push_back(paperFingerprint(p));
  for (const Paper& p : h.redo)
    redo_fingerprints_.push_back(paperFingerprint(p));
  failure_.clear();
  healthy_ = true;
  return success();
}

namespace
{
/// A commit's line with the whole state it makes (formatPaperText's text).
std::string commitLine(const Operation& op, const std::string& state)
{
  std::string line = journalLine(json{ { "operation", operationToJson(op) } });
  line.resize(line.size() - 2);
  return line + ",\"paper\":" + state + "}\n";
}

/// A commit's line with what it changed (formatPaperDelta's text).
std::string deltaLine(const Operation& op, const std::string& delta)
{
  std::string line = journalLine(json{ { "operation", operationToJson(op) } });
  line.resize(line.size() - 2);
  return line + ",\"delta\":" + delta + "}\n";
}
}  // namespace

JournalEvent journalEvent(const Operation& op, const Paper* state_after, const Paper* state_before)
{
  JournalEvent event{ op, state_after != nullptr, "", std::nullopt, std::nullopt, 0 };
  if (!state_after)
    event.line = journalLine(json{ { "operation", operationToJson(op) } });
  else if (op.kind == Operation::Kind::Load || op.kind == Operation::Kind::Reset)
  {
    // A new paper shares nothing with the one before it: whole, and made here.
    event.line = commitLine(op, formatPaperText(*state_after));
    event.fingerprint = paperFingerprint(*state_after);
  }
  else if (state_before)
  {
    event.fingerprint = paperFingerprint(*state_after);
    event.base_fingerprint = paperFingerprint(*state_before);
    event.line = deltaLine(op, formatPaperDelta(*state_before, *state_after, event.fingerprint));
  }
  else
  {
    // The state before is the session's, which only the append sees: the line is made there.
    event.state = *state_after;
    event.fingerprint = paperFingerprint(*state_after);
  }
  return event;
}

Status SessionJournal::append(const Operation& op, const Paper* state_after)
{
  JournalEvent event{ op, state_after != nullptr, "", std::nullopt, std::nullopt, 0 };
  if (state_after)
  {
    event.line = commitLine(op, formatPaperText(*state_after));
    event.fingerprint = paperFingerprint(*state_after);
  }
  else
    event.line = journalLine(json{ { "operation", operationToJson(op) } });
  return append(event);
}

Status SessionJournal::append(const JournalEvent& event)
{
  const Operation& op = event.operation;
  if (!healthy_)
    return failure("the journal " + path_ + " takes no event until it is started again: " +
                   (failure_.empty() ? std::string("it was never started") : failure_));
  // The journal refuses what its reader would drop, so that what it acknowledged is read back.
  const bool step = stepsThroughHistory(op.kind);
  if (step == event.has_state)
    return failure(std::string("a journaled ") + kindName(op.kind) +
                   (step ? " carries no state" : " must carry the state it makes"));
  if (op.revision != revision_ + 1 || revision_ == std::numeric_limits<uint64_t>::max())
    return failure("a journaled " + std::string(kindName(op.kind)) + " has revision " + std::to_string(op.revision) +
                   "; the journal is at revision " + std::to_string(revision_));
  if (op.kind == Operation::Kind::Undo && undo_fingerprints_.empty())
    return failure("the journal has nothing to undo");
  if (op.kind == Operation::Kind::Redo && redo_fingerprints_.empty())
    return failure("the journal has nothing to redo");
  if (event.base_fingerprint && *event.base_fingerprint != fingerprint_)
    return failure(std::string("a journaled ") + kindName(op.kind) +
                   " was computed from another state than the one the journal is at");

  const uint64_t before_bytes = written_;
  const Status written =
      writeEvent(!event.line.empty() || !event.state ? event.line : commitLine(op, formatPaperText(*event.state)));
  if (!written)
    return written;
  const uint64_t written_line = written_ - before_bytes;
  if (op.kind == Operation::Kind::Undo)
  {
    redo_fingerprints_.push_back(fingerprint_);
    fingerprint_ = undo_fingerprints_.back();
    undo_fingerprints_.pop_back();
  }
  else if (op.kind == Operation::Kind::Redo)
  {
    undo_fingerprints_.push_back(fingerprint_);
    fingerprint_ = redo_fingerprints_.back();
    redo_fingerprints_.pop_back();
  }
  else
  {
    undo_fingerprints_.push_back(fingerprint_);
    redo_fingerprints_.clear();
    fingerprint_ = event.fingerprint;
  }
  // A restart holds a state for every commit, whatever its line's size; an undo or redo only
  // moves one between the stacks.
  event_weight_ += step ? written_line : std::max(written_line, state_bytes_);
  revision_ = op.revision;
  ++recorded_;
  return success();
}

Status SessionJournal::append(const Session& before, const Operation& op, const Paper* state_after)
{
  const Status ready = startUnlessInStep(before);
  if (!ready)
    return ready;
  return append(journalEvent(op, state_after, state_after ? &before.paper() : nullptr));
}

Status SessionJournal::append(const Session& before, const JournalEvent& event)
{
  const Status ready = startUnlessInStep(before);
  if (!ready)
    return ready;
  if (event.line.empty() && event.state)
  {
    // What it changes in the session's paper, which is the state the journal is at.
    JournalEvent made{ event.operation,
                       true,
                       deltaLine(event.operation, formatPaperDelta(before.paper(), *event.state, event.fingerprint)),
                       std::nullopt,
                       fingerprint_,
                       event.fingerprint };
    return append(made);
  }
  return append(event);
}

Status SessionJournal::startUnlessInStep(const Session& before)
{
  if (path_.empty())
    return failure("the journal was never started");
  // Its paper too: a delta is written from the session's paper and read back onto the
  // journal's, which must be the same state.
  if (healthy_ && inStepWith(before) && paperFingerprint(before.paper()) == fingerprint_)
    return success();
  // Starting again replaces the file, torn line and all, by the session as it is.
  return start(path_, before, run_id_);
}

Status SessionJournal::record(const Session& session)
{
  if (path_.empty())
    return failure("the journal was never started");
  const History& h = session.history();
  if (!healthy_ || !canCatchUp(h))
    return start(path_, session, run_id_);
  while (recorded_ < h.log.size())
  {
    const Operation& op = h.log[recorded_];
    // Only the newest commit's state is at hand (canCatchUp saw that any commit is the last);
    // the state before it is the newest undo state, unless the history limit dropped it.
    Status appended = success();
    if (stepsThroughHistory(op.kind))
      appended = append(op, nullptr);
    else if (!h.undo.empty() && paperFingerprint(h.undo.back()) == fingerprint_)
      appended = append(journalEvent(op, &h.paper, &h.undo.back()));
    else
      appended = append(op, &h.paper);
    if (!appended)
      return appended;
  }
  return success();
}

bool SessionJournal::inStepWith(const Session& session) const
{
  const History& h = session.history();
  // A session that caps its undo history by memory forgets the oldest undo states, which the
  // journal keeps: deeper, but in step.
  return revision_ == h.revision && recorded_ == h.log.size() && undo_fingerprints_.size() >= h.undo.size() &&
         redo_fingerprints_.size() == h.redo.size();
}

bool SessionJournal::canCatchUp(const History& h) const
{
  if (recorded_ > h.log.size())
    return false;
  uint64_t revision = revision_;
  size_t undo = undo_fingerprints_.size(), redo = redo_fingerprints_.size();
  for (size_t i = recorded_; i < h.log.size(); ++i)
  {
    const Operation& op = h.log[i];
    if (op.revision != revision + 1)
      return false;
    revision = op.revision;
    if (op.kind == Operation::Kind::Undo || op.kind == Operation::Kind::Redo)
    {
      size_t& from = op.kind == Operation::Kind::Undo ? undo : redo;
      size_t& to = op.kind == Operation::Kind::Undo ? redo : undo;
      if (from == 0)
        return false;
      --from;
      ++to;
    }
    else
    {
      if (i + 1 != h.log.size())
        return false;  // an earlier commit's state is gone: only the whole history will do
      ++undo;
      redo = 0;
    }
  }
  return revision == h.revision && undo == h.undo.size() && redo == h.redo.size();
}

Status SessionJournal::writeEvent(const std::string& line)
{
  int error = 0;
  if (!writeAll(file_.get(), line.data(), line.size(), error))
    return fail("cannot write the journal " + path_ + ": " + std::strerror(error));
  if (sync_ && ::fsync(file_.get()) != 0)
    return fail("cannot sync the journal " + path_ + ": " + std::strerror(errno));
  written_ += line.size();
  return success();
}

Status SessionJournal::fail(const std::string& message)
{
  // Cut a torn line off if the disk still lets us; if it does not, the file is closed so
  // nothing is ever appended after it, and the reader drops it.
  if (healthy_ && file_.get() >= 0 && ::ftruncate(file_.get(), static_cast<off_t>(written_)) == 0 && sync_)
    ::fsync(file_.get());
  file_.reset();
  healthy_ = false;
  failure_ = message;
  return failure(message);
}

Expected<JournalRecovery> recoverJournal(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  if (!in)
    return Expected<JournalRecovery>::failure("cannot open the journal " + path + ": " + std::strerror(errno));
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad())
    return Expected<JournalRecovery>::failure("cannot read the journal " + path + ": " + std::strerror(errno));
  // Every line the journal writes ends in a newline; the last without one was cut short by
  // a crash or a failed write and never acknowledged.
  std::vector<std::string> lines;
  bool last_is_torn = false;
  for (size_t begin = 0; begin < text.size();)
  {
    const size_t end = text.find('\n', begin);
    if (end == std::string::npos)
    {
      lines.push_back(text.substr(begin));
      last_is_torn = true;
      break;
    }
    lines.push_back(text.substr(begin, end - begin));
    begin = end + 1;
  }
  if (lines.empty())
    return Expected<JournalRecovery>::failure("the journal " + path + " is empty");

  JournalRecovery recovery;
  History& history = recovery.history;
  {
    const auto fail = [&](const std::string& why) {
      return Expected<JournalRecovery>::failure("journal " + path + " line 1: " + why);
    };
    const json header = json::parse(lines[0], nullptr, false);
    if (header.is_discarded())
      return fail("not JSON");
    const Status read = readHeader(header, history);
    if (!read)
      return fail(read.message());
    if (header.contains("run_id"))
    {
      if (!header["run_id"].is_string())
        return fail("run_id is not a string");
      recovery.run_id = header["run_id"].get<std::string>();
    }
  }
  recovery.lines_read = 1;

  for (size_t i = 1; i < lines.size(); ++i)
  {
    const std::string why = readEvent(lines[i], i + 1 == lines.size() && last_is_torn, history);
    if (!why.empty())
    {
      const size_t first = i + 1, last = lines.size(), count = last - first + 1;
      recovery.dropped.push_back("line " + std::to_string(first) + ": " + why + "; dropped " +
                                 (count == 1 ? "line " + std::to_string(first)
                                             : "lines " + std::to_string(first) + "\u2013" + std::to_string(last)) +
                                 " (" + std::to_string(count) + (count == 1 ? " line)" : " lines)"));
      break;
    }
    ++recovery.lines_read;
  }
  return recovery;
}

Expected<History> readJournal(const std::string& path)
{
  Expected<JournalRecovery> recovery = recoverJournal(path);
  if (!recovery)
    return Expected<History>::failure(recovery.message());
  return std::move(recovery->history);
}

std::string keepAsideName(const std::string& path)
{
  timespec now{};
  ::clock_gettime(CLOCK_REALTIME, &now);
  tm utc{};
  ::gmtime_r(&now.tv_sec, &utc);
  char stamp[40];
  const size_t length = std::strftime(stamp, sizeof(stamp), "%Y%m%dT%H%M%S", &utc);
  std::snprintf(stamp + length, sizeof(stamp) - length, ".%09ld", static_cast<long>(now.tv_nsec));
  const std::string base = path + "." + stamp + "." + std::to_string(::getpid());
  // The clock may be coarse or stepped back: count on until the name is free.
  std::string name = base + ".old";
  struct stat existing;
  for (unsigned n = 1; ::lstat(name.c_str(), &existing) == 0; ++n)
    name = base + "." + std::to_string(n) + ".old";
  return name;
}

}  // namespace virtual_origami::core

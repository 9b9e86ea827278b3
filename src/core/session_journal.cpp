#include "virtual_origami/core/session_journal.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <type_traits>

#include <nlohmann/json.hpp>

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

json paperToJson(const Paper& paper)
{
  json j;
  json cp = json::array(), folded = json::array(), edges = json::array(), faces = json::array(),
       orders = json::array();
  for (const Vertex& v : paper.vertices)
  {
    cp.push_back({ v.crease_pattern.x(), v.crease_pattern.y() });
    folded.push_back({ v.folded.x(), v.folded.y(), v.folded.z() });
  }
  for (const Edge& e : paper.edges)
    edges.push_back({ e.vertices[0], e.vertices[1], std::string(1, assignmentLetter(e.assignment)), e.fold_angle });
  for (const Face& f : paper.faces)
    faces.push_back(f.vertices);
  for (const FaceOrder& o : paper.face_orders)
    orders.push_back({ o.face, o.other, o.above });
  j["vertices_crease_pattern"] = cp;
  j["vertices_folded"] = folded;
  j["edges"] = edges;
  j["faces"] = faces;
  j["face_orders"] = orders;
  j["sheet_area"] = paper.sheet_area;
  return j;
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
      break;
    case Operation::Kind::Reset:
      j["size"] = op.size;
      break;
    case Operation::Kind::Load:
      j["path"] = op.path;
      break;
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
  try
  {
    Operation op;
    const std::string kind = j.at("kind").get<std::string>();
    bool known = false;
    for (Operation::Kind k : { Operation::Kind::Crease, Operation::Kind::Rotate, Operation::Kind::Squash,
                               Operation::Kind::Undo, Operation::Kind::Redo, Operation::Kind::Reset,
                               Operation::Kind::Load, Operation::Kind::Pull })
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
    }
    else if (op.kind == Operation::Kind::Reset)
      op.size = j.at("size").get<double>();
    else if (op.kind == Operation::Kind::Load)
      op.path = j.at("path").get<std::string>();
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

Status readHeader(const json& j, History& history)
{
  if (j.value("journal", "") != "virtual_origami session")
    return failure("not a virtual_origami journal header");
  try
  {
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
    const Status undo = readPapers(j.at("undo"), history.undo);
    return undo ? readPapers(j.at("redo"), history.redo) : undo;
  }
  catch (const std::exception& e)  // json::exception, NotAnInteger
  {
    return failure(std::string("malformed header: ") + e.what());
  }
}

bool stepsThroughHistory(Operation::Kind kind) { return kind == Operation::Kind::Undo || kind == Operation::Kind::Redo; }
}  // namespace

std::string formatPaperJson(const Paper& paper) { return paperToJson(paper).dump(); }

Expected<Paper> parsePaperJson(const std::string& text)
{
  const json j = json::parse(text, nullptr, false);
  if (j.is_discarded())
    return Expected<Paper>::failure("invalid JSON");
  return paperFromJson(j);
}

Status SessionJournal::start(const std::string& path, const Session& session)
{
  out_.close();
  out_.clear();
  // The new journal is written beside the old one and renamed over it: a crash while the
  // header is written (it holds the whole history) must not leave a truncated journal and
  // lose the session. paper_model starts one on every (re)start. Found by killing it -9.
  const std::string temporary = path + ".tmp";
  out_.open(temporary, std::ios::out | std::ios::trunc);
  if (!out_)
    return failure("cannot write the journal " + temporary + ": " + std::strerror(errno));
  path_ = temporary;
  // The header holds the whole history so far; events follow it.
  const History& h = session.history();
  json undo = json::array(), redo = json::array(), log = json::array();
  for (const Paper& p : h.undo)
    undo.push_back(paperToJson(p));
  for (const Paper& p : h.redo)
    redo.push_back(paperToJson(p));
  for (const Operation& op : h.log)
    log.push_back(operationToJson(op));
  recorded_ = h.log.size();
  const Status written = writeLine(json{ { "journal", "virtual_origami session" },
                                         { "version", 1 },
                                         { "paper", paperToJson(h.paper) },
                                         { "revision", h.revision },
                                         { "undo", undo },
                                         { "redo", redo },
                                         { "log", log } }
                                       .dump());
  out_.close();
  if (!written || !out_ || std::rename(temporary.c_str(), path.c_str()) != 0)
  {
    const std::string reason = written ? std::strerror(errno) : written.message();
    std::remove(temporary.c_str());
    return failure("cannot write the journal " + path + ": " + reason);
  }
  path_ = path;
  out_.clear();
  out_.open(path, std::ios::out | std::ios::app);
  if (!out_)
    return failure("cannot append to the journal " + path + ": " + std::strerror(errno));
  return success();
}

Status SessionJournal::record(const Session& session)
{
  const History& h = session.history();
  for (; recorded_ < h.log.size(); ++recorded_)
  {
    const Operation& op = h.log[recorded_];
    json event{ { "operation", operationToJson(op) } };
    // Only the newest commit's state is at hand; replay needs every commit's, so the
    // journal must be recorded after each operation (the node does).
    if (!stepsThroughHistory(op.kind))
    {
      if (recorded_ + 1 != h.log.size())
        return failure("the journal fell behind the session: record after every operation");
      event["paper"] = paperToJson(h.paper);
    }
    const Status written = writeLine(event.dump());
    if (!written)
      return written;
  }
  return success();
}

Status SessionJournal::writeLine(const std::string& line)
{
  out_ << line << '\n';
  out_.flush();
  if (!out_)
    return failure("cannot write the journal " + path_ + ": " + std::strerror(errno));
  return success();
}

Expected<History> readJournal(const std::string& path)
{
  std::ifstream in(path);
  if (!in)
    return Expected<History>::failure("cannot open the journal " + path + ": " + std::strerror(errno));
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);)
    if (!line.empty())
      lines.push_back(line);
  if (lines.empty())
    return Expected<History>::failure("the journal " + path + " is empty");
  History history;
  for (size_t i = 0; i < lines.size(); ++i)
  {
    const auto fail = [&](const std::string& why) {
      return Expected<History>::failure("journal " + path + " line " + std::to_string(i + 1) + ": " + why);
    };
    const json j = json::parse(lines[i], nullptr, false);
    if (j.is_discarded())
    {
      if (i + 1 == lines.size() && i > 0)
        break;  // torn by a crash mid-write: everything before it stands
      return fail("not JSON");
    }
    if (i == 0)
    {
      const Status header = readHeader(j, history);
      if (!header)
        return fail(header.message());
      continue;
    }
    if (!j.contains("operation"))
      return fail("no operation");
    const Expected<Operation> op = operationFromJson(j["operation"]);
    if (!op)
      return fail(op.message());
    if (op->kind == Operation::Kind::Undo || op->kind == Operation::Kind::Redo)
    {
      auto& from = op->kind == Operation::Kind::Undo ? history.undo : history.redo;
      auto& to = op->kind == Operation::Kind::Undo ? history.redo : history.undo;
      if (from.empty())
        return fail(std::string("nothing to ") + kindName(op->kind));
      to.push_back(std::move(history.paper));
      history.paper = std::move(from.back());
      from.pop_back();
    }
    else
    {
      if (!j.contains("paper"))
        return fail("a commit without its state");
      Expected<Paper> paper = paperFromJson(j["paper"]);
      if (!paper)
        return fail(paper.message());
      history.undo.push_back(std::move(history.paper));
      history.redo.clear();
      history.paper = std::move(*paper);
    }
    history.revision = op->revision;
    history.log.push_back(*op);
  }
  return history;
}

}  // namespace virtual_origami::core

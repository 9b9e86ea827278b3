#include "virtual_origami/core/fold_sequence.h"

#include <cmath>

#include <nlohmann/json.hpp>


namespace virtual_origami::core
{
using nlohmann::json;

namespace
{
/// Thrown inside the parser only, caught in parseFoldSequence.
struct SequenceError
{
  std::string message;
};

Vec3 point(const json& j, const std::string& where)
{
  if (!j.is_array() || j.size() < 2 || j.size() > 3)
    throw SequenceError{ where + " must be [x, y] or [x, y, z]" };
  Vec3 p = Vec3::Zero();
  for (size_t i = 0; i < j.size(); ++i)
  {
    if (!j[i].is_number())
      throw SequenceError{ where + "[" + std::to_string(i) + "] is not a number" };
    p[static_cast<int>(i)] = j[i].get<double>();
  }
  return p;
}

FoldStep parseStep(const json& j, const std::string& where)
{
  if (!j.is_object())
    throw SequenceError{ where + " is not an object" };
  FoldStep step;
  step.note = j.value("note", "");
  if (j.contains("crease"))
  {
    const json& c = j["crease"];
    step.operation.kind = Operation::Kind::Crease;
    step.operation.crease.start = point(c.value("start", json()), where + ".crease.start");
    step.operation.crease.end = point(c.value("end", json()), where + ".crease.end");
    if (c.contains("eye"))
      step.operation.crease.eye = point(c["eye"], where + ".crease.eye");
    step.operation.crease.snap = c.value("snap", false);
  }
  else if (j.contains("rotate"))
  {
    const json& r = j["rotate"];
    step.operation.kind = Operation::Kind::Rotate;
    step.operation.rotate.click = r.contains("click") ? point(r["click"], where + ".rotate.click") : Vec3::Zero();
    step.operation.rotate.face = r.value("face", -1);
    step.operation.rotate.axis_edge = r.value("axis_edge", -1);
    if (!r.contains("angle_deg") || !r["angle_deg"].is_number())
      throw SequenceError{ where + ".rotate.angle_deg is missing or not a number" };
    step.operation.rotate.angle = r["angle_deg"].get<double>() * M_PI / 180.0;
    step.repeat = r.value("repeat", 1);
    if (step.repeat < 1 || step.repeat > 1000)
      throw SequenceError{ where + ".rotate.repeat must be 1 to 1000" };
  }
  else if (j.contains("flat_fold"))
  {
    const json& f = j["flat_fold"];
    const json creases = f.value("creases", json());
    if (!creases.is_array() || creases.empty())
      throw SequenceError{ where + ".flat_fold.creases is missing or empty" };
    FlatFoldRequest request;
    for (size_t k = 0; k < creases.size(); ++k)
    {
      const std::string at = where + ".flat_fold.creases[" + std::to_string(k) + "]";
      const json& c = creases[k];
      if (!c.is_object() || !c.contains("angle_deg") || !c["angle_deg"].is_number())
        throw SequenceError{ at + ".angle_deg is missing or not a number" };
      CreaseLineAngle line;
      line.start = point(c.value("start", json()), at + ".start").head<2>();
      line.end = point(c.value("end", json()), at + ".end").head<2>();
      line.angle = c["angle_deg"].get<double>() * M_PI / 180.0;
      request.creases.push_back(line);
    }
    request.fixed_point = point(f.value("fixed", json()), where + ".flat_fold.fixed").head<2>();
    step.operation.kind = Operation::Kind::FlatFold;
    step.operation.flat_fold = request;
    step.flat_fold = request;
  }
  else if (j.contains("squash"))
    step.operation.kind = Operation::Kind::Squash;
  else if (j.contains("undo"))
    step.operation.kind = Operation::Kind::Undo;
  else if (j.contains("redo"))
    step.operation.kind = Operation::Kind::Redo;
  else
    throw SequenceError{ where + " names no operation (crease, rotate, squash, flat_fold, undo, redo)" };
  return step;
}
}  // namespace

Expected<FoldSequence> parseFoldSequence(const std::string& text)
{
  const json j = json::parse(text, nullptr, false);
  if (j.is_discarded())
    return Expected<FoldSequence>::failure("the sequence is not valid JSON");
  try
  {
    if (!j.is_object() || !j.contains("steps") || !j["steps"].is_array())
      throw SequenceError{ "steps is missing or not a list" };
    FoldSequence sequence;
    sequence.title = j.value("title", "");
    sequence.size = j.value("size", 1.0);
    sequence.solver = j.value("solver", sequence.solver);
    if (!std::isfinite(sequence.size) || sequence.size <= 0)
      throw SequenceError{ "size must be a positive number" };
    for (size_t i = 0; i < j["steps"].size(); ++i)
      sequence.steps.push_back(parseStep(j["steps"][i], "steps[" + std::to_string(i) + "]"));
    return sequence;
  }
  catch (const SequenceError& e)
  {
    return Expected<FoldSequence>::failure(e.message);
  }
  catch (const json::exception& e)
  {
    return Expected<FoldSequence>::failure(std::string("malformed sequence: ") + e.what());
  }
}

Expected<std::vector<Paper>> foldSequence(const FoldSequence& sequence, Session& session,
                                          std::shared_ptr<ShapeSolver> solver)
{
  if (!solver)
    return Expected<std::vector<Paper>>::failure("no solver named \"" + sequence.solver + "\"");
  session.setSolver(solver);
  const Status reset = session.reset(sequence.size);
  if (!reset)
    return Expected<std::vector<Paper>>::failure(reset.message());
  std::vector<Paper> states{ session.paper() };
  for (size_t i = 0; i < sequence.steps.size(); ++i)
  {
    const FoldStep& step = sequence.steps[i];
    Operation op = step.operation;
    for (int k = 0; k < step.repeat; ++k)
    {
      const Status applied = session.apply(op);
      if (!applied)
        return Expected<std::vector<Paper>>::failure("step " + std::to_string(i + 1) +
                                                     (step.note.empty() ? "" : " (" + step.note + ")") + ": " +
                                                     applied.message());
      states.push_back(session.paper());
      op = session.log().back();  // again about the face and axis it resolved to
    }
  }
  return states;
}

}  // namespace virtual_origami::core

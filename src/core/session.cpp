#include "virtual_origami/core/session.h"

#include <cmath>

#include "virtual_origami/core/validity.h"

namespace virtual_origami::core
{
const char* kindName(Operation::Kind kind)
{
  switch (kind)
  {
    case Operation::Kind::Crease:
      return "crease";
    case Operation::Kind::Rotate:
      return "rotate";
    case Operation::Kind::Squash:
      return "squash";
    case Operation::Kind::Undo:
      return "undo";
    case Operation::Kind::Redo:
      return "redo";
    case Operation::Kind::Reset:
      return "reset";
    case Operation::Kind::Load:
      return "load";
    case Operation::Kind::Pull:
      return "pull";
  }
  return "unknown";
}

Session::Session(Paper initial) { history_.paper = std::move(initial); }

Session::Session(History history) : history_(std::move(history)) {}

void Session::commit(Paper next, Operation operation)
{
  history_.undo.push_back(std::move(history_.paper));
  history_.redo.clear();
  history_.paper = std::move(next);
  preview_.reset();
  operation.revision = ++history_.revision;
  history_.log.push_back(std::move(operation));
}

void Session::step(std::vector<Paper>& from, std::vector<Paper>& to, Operation::Kind kind)
{
  to.push_back(std::move(history_.paper));
  history_.paper = std::move(from.back());
  from.pop_back();
  preview_.reset();
  Operation op;
  op.kind = kind;
  op.revision = ++history_.revision;
  history_.log.push_back(op);
}

Expected<CreaseResult> Session::crease(const CreaseRequest& request)
{
  Paper next = history_.paper;
  Expected<CreaseResult> result = core::crease(next, request, snap_settings_);
  if (result)
  {
    Operation op;
    op.kind = Operation::Kind::Crease;
    op.crease = request;
    commit(std::move(next), op);
  }
  return result;
}

Expected<RotateResult> Session::rotate(const RotateRequest& request, bool commit_it)
{
  Paper next = history_.paper;
  Expected<RotateResult> result = core::rotate(next, request, solver_.get(), held_);
  if (!result)
    return result;
  for (int v : held_)
    if (v >= 0 && v < static_cast<int>(next.vertices.size()) &&
        (next.vertices[v].folded - history_.paper.vertices[v].folded).norm() > 1e-9 * next.scale())
      return Expected<RotateResult>::failure("vertex " + std::to_string(v) +
                                             " is pinned and the rotation would move it; release it first");
  if (!commit_it)
  {
    preview_ = std::move(next);
    return result;
  }
  Operation op;
  op.kind = Operation::Kind::Rotate;
  op.rotate = request;
  op.rotate.face = result->face;
  op.rotate.axis_edge = result->axis_edge;
  commit(std::move(next), op);
  return result;
}

Expected<SquashResult> Session::squash()
{
  Paper next = history_.paper;
  Expected<SquashResult> result = core::squash(next, solver_.get());
  if (result)
  {
    Operation op;
    op.kind = Operation::Kind::Squash;
    commit(std::move(next), op);
  }
  return result;
}

Status Session::undo()
{
  if (history_.undo.empty())
    return failure("nothing to undo");
  step(history_.undo, history_.redo, Operation::Kind::Undo);
  return success();
}

Status Session::redo()
{
  if (history_.redo.empty())
    return failure("nothing to redo");
  step(history_.redo, history_.undo, Operation::Kind::Redo);
  return success();
}

Status Session::reset(double size)
{
  // Tolerances are relative to the sheet's scale and its area is size²: keep both far from
  // overflow and underflow (a size of 1e308 made an infinite area, found by fuzzing).
  if (!(size >= kMinSheetSize && size <= kMaxSheetSize))
    return failure("the sheet size must be a number between 1e-6 and 1e6 m");
  Operation op;
  op.kind = Operation::Kind::Reset;
  op.size = size;
  commit(Paper::square(size), op);
  return success();
}

Status Session::load(Paper paper, const std::string& path)
{
  const double side = std::sqrt(paper.sheet_area);
  if (!(side >= kMinSheetSize && side <= kMaxSheetSize))
    return failure("the model in " + path + " is not a sheet between 1e-6 and 1e6 m across");
  const ValidityReport report = checkValidity(paper, { 1e-4, 1e-6, 1e-12 });
  if (!report.ok())
    return failure("the model in " + path + " is not valid: " + report.problems.front());
  Operation op;
  op.kind = Operation::Kind::Load;
  op.path = path;
  commit(std::move(paper), op);
  return success();
}

Expected<PullResult> Session::pull(const std::vector<PullTarget>& targets)
{
  Paper next = history_.paper;
  Expected<PullResult> result = core::pull(next, targets, solver_.get(), held_);
  if (result)
  {
    Operation op;
    op.kind = Operation::Kind::Pull;
    op.pull = targets;
    commit(std::move(next), op);
  }
  return result;
}

Status Session::apply(const Operation& operation)
{
  switch (operation.kind)
  {
    case Operation::Kind::Crease:
    {
      const auto r = crease(operation.crease);
      return r ? success() : failure(r.message());
    }
    case Operation::Kind::Rotate:
    {
      const auto r = rotate(operation.rotate, true);
      return r ? success() : failure(r.message());
    }
    case Operation::Kind::Squash:
    {
      const auto r = squash();
      return r ? success() : failure(r.message());
    }
    case Operation::Kind::Undo:
      return undo();
    case Operation::Kind::Redo:
      return redo();
    case Operation::Kind::Reset:
      return reset(operation.size);
    case Operation::Kind::Load:
      return failure("a load is replayed by loading the file itself");
    case Operation::Kind::Pull:
    {
      const auto r = pull(operation.pull);
      return r ? success() : failure(r.message());
    }
  }
  return failure("unknown operation");
}

}  // namespace virtual_origami::core

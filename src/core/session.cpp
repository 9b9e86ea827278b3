#include "virtual_origami/core/session.h"

#include <cmath>

#include "virtual_origami/core/validity.h"

namespace virtual_origami
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
  }
  return "unknown";
}

Session::Session(Paper initial) : paper_(std::move(initial)) {}

void Session::commit(Paper next, Operation operation)
{
  undo_.push_back(std::move(paper_));
  redo_.clear();
  paper_ = std::move(next);
  preview_.reset();
  operation.revision = ++revision_;
  log_.push_back(std::move(operation));
}

Expected<CreaseResult> Session::crease(const CreaseRequest& request)
{
  Paper next = paper_;
  Expected<CreaseResult> result = virtual_origami::crease(next, request, snap_settings_);
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
  Paper next = paper_;
  Expected<RotateResult> result = virtual_origami::rotate(next, request, solver_.get());
  if (!result)
    return result;
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
  Paper next = paper_;
  Expected<SquashResult> result = virtual_origami::squash(next, solver_.get());
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
  if (undo_.empty())
    return failure("nothing to undo");
  redo_.push_back(std::move(paper_));
  paper_ = std::move(undo_.back());
  undo_.pop_back();
  preview_.reset();
  Operation op;
  op.kind = Operation::Kind::Undo;
  op.revision = ++revision_;
  log_.push_back(op);
  return success();
}

Status Session::redo()
{
  if (redo_.empty())
    return failure("nothing to redo");
  undo_.push_back(std::move(paper_));
  paper_ = std::move(redo_.back());
  redo_.pop_back();
  preview_.reset();
  Operation op;
  op.kind = Operation::Kind::Redo;
  op.revision = ++revision_;
  log_.push_back(op);
  return success();
}

Status Session::reset(double size)
{
  if (!std::isfinite(size) || size <= 0)
    return failure("the sheet size must be a positive finite number");
  Operation op;
  op.kind = Operation::Kind::Reset;
  op.size = size;
  commit(Paper::square(size), op);
  return success();
}

Status Session::load(Paper paper, const std::string& path)
{
  const ValidityReport report = checkValidity(paper, { 1e-4, 1e-6, 1e-12 });
  if (!report.ok())
    return failure("the model in " + path + " is not valid: " + report.problems.front());
  Operation op;
  op.kind = Operation::Kind::Load;
  op.path = path;
  commit(std::move(paper), op);
  return success();
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
  }
  return failure("unknown operation");
}

}  // namespace virtual_origami

// Success-or-message results: operations never throw across the library boundary.
#pragma once

#include <optional>
#include <string>
#include <utility>

namespace virtual_origami::core
{
/// A value, or a message saying why there is none.
template <class T>
class Expected
{
public:
  Expected(T value) : value_(std::move(value)) {}  // NOLINT: implicit on purpose
  static Expected failure(std::string message)
  {
    Expected e;
    e.message_ = std::move(message);
    return e;
  }

  bool ok() const { return value_.has_value(); }
  explicit operator bool() const { return ok(); }
  const T& value() const { return *value_; }
  T& value() { return *value_; }
  const T* operator->() const { return &*value_; }
  T* operator->() { return &*value_; }
  const T& operator*() const { return *value_; }
  T& operator*() { return *value_; }
  /// Empty on success.
  const std::string& message() const { return message_; }

private:
  Expected() = default;
  std::optional<T> value_;
  std::string message_;
};

/// Success with no value.
struct Done
{
};
using Status = Expected<Done>;
inline Status success() { return Status(Done{}); }
inline Status failure(std::string message) { return Status::failure(std::move(message)); }

}  // namespace virtual_origami::core

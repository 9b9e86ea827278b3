// The readers' one error: a malformed file. Their checks nest deeply, so they throw it; each
// public reading function turns it into a failure, and nothing is thrown across the library
// boundary. Private to the FOLD and ORIPA readers.
#pragma once

#include <new>
#include <stdexcept>
#include <string>

#include "virtual_origami/core/result.h"

namespace virtual_origami::core
{
struct FormatError : std::runtime_error
{
  using std::runtime_error::runtime_error;
};

[[noreturn]] inline void fail(const std::string& message)
{
  throw FormatError(message);
}

/// `body()`, or its FormatError as a failure; running out of memory, or a bug (any other
/// exception), is a failure too.
template <class T, class Body>
Expected<T> guarded(const Body& body)
{
  try
  {
    return body();
  }
  catch (const FormatError& e)
  {
    return Expected<T>::failure(e.what());
  }
  catch (const std::bad_alloc&)
  {
    return Expected<T>::failure("out of memory");
  }
  catch (const std::exception& e)  // a bug here, not the file's fault: still no throw across the API
  {
    return Expected<T>::failure(std::string("internal error: ") + e.what());
  }
}

}  // namespace virtual_origami::core

// What a second thread's allocation takes from the system after this thread freed a block of
// the same size (heap_reuse_test, shared_heap_test).
#pragma once

#include <malloc.h>

#include <cstdlib>
#include <thread>

namespace virtual_origami::test
{
// Under the 64 MiB a thread's own heap can hold, over the 32 MiB the C library maps apart by itself.
constexpr size_t kThreadBlock = size_t(40) << 20;

/// A block the compiler must allocate: a malloc and free of a pointer nothing reads may be left out.
inline void* allocated(size_t bytes)
{
  static void* volatile seen;
  void* block = std::malloc(bytes);
  seen = block;
  return block;
}

/// Bytes the heaps hold from the system (arenas and blocks mapped apart).
inline size_t bytesFromTheSystem()
{
  const struct mallinfo2 m = mallinfo2();
  return m.arena + m.hblkhd;
}

/// This thread allocates and frees kThreadBlock, then a new thread allocates as much (and frees it
/// after): the bytes the heaps took from the system for the second block.
inline size_t freshBytesOfASecondThread()
{
  std::free(allocated(kThreadBlock));
  const size_t before = bytesFromTheSystem();
  size_t held = 0;
  std::thread([&] {
    void* block = allocated(kThreadBlock);
    held = bytesFromTheSystem();
    std::free(block);
  }).join();
  return held > before ? held - before : 0;
}
}  // namespace virtual_origami::test

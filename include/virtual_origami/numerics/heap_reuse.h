// The solving processes keep the memory they free for their next allocations.
#pragma once

namespace virtual_origami::numerics
{
/// Which heap a process's threads allocate from.
enum class ThreadHeaps
{
  /// The C library's default: threads that work at once (a curved sheet's frames beside the
  /// factorisations made for them) do not wait for each other's allocations.
  PerThread,
  /// One for every thread: a node's service threads take turns at the same work, and with a heap
  /// each, a frame on a thread new to it pages in what the last frame freed on another. The
  /// slider's first frames at 10,000 vertices through paper_model took 80–120 ms where the same
  /// frames in one thread take 24–31 ms (each of its four spinner threads warming a heap of its own).
  Shared,
};

/// Asks the C library to keep freed memory in the process's heap for the next allocation, rather
/// than give it back to the system: no block is mapped on its own and the heap's top is never
/// trimmed. A commit at 10,000 vertices makes its matrices, factors and triplet lists afresh
/// (tens of megabytes each), and memory new to the process costs a page fault at each page's
/// first touch: a quarter of the slider's release at 10,000 vertices in process (1.36–1.48 s,
/// 1.16–1.19 s with this, the same iterations). The process keeps its largest heap until it
/// exits. Call once at the start of main, before threads. Returns whether the library took it.
bool keepFreedMemory(ThreadHeaps heaps);
}  // namespace virtual_origami::numerics

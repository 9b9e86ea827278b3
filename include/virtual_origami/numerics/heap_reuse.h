// The solving processes keep the memory they free for their next allocations.
#pragma once

namespace virtual_origami::numerics
{
/// Asks the C library to keep freed memory in the process's heap for the next allocation, rather
/// than give it back to the system: no block is mapped on its own and the heap's top is never
/// trimmed. A commit at 10,000 vertices makes its matrices, factors and triplet lists afresh
/// (tens of megabytes each), and memory new to the process costs a page fault at each page's
/// first touch: a quarter of the slider's release at 10,000 vertices in process (1.36–1.48 s,
/// 1.16–1.19 s with this, the same iterations). The process keeps its largest heap until it
/// exits. Call once at the start of main, before threads. Returns whether the library took it.
bool keepFreedMemory();
}  // namespace virtual_origami::numerics

#pragma once
// How the process's heap treats freed memory. Trials allocate and free tables of tens of MB
// (particle tables of the multi-scan methods, per-scan graphs); by default glibc returns large
// blocks to the kernel at once (mmap/munmap, heap trimming), so the next trial page-faults the
// same memory in again — on the 2-core VM about a third of a 12-scan CV/CVS trial at 10 000
// particles (bench_multi_scan.cpp measures it). Called first by the programs (dabench,
// dabench_bench); a library user may call it too. Numbers are unaffected, only where memory
// comes from.
namespace dabench {

// Keeps freed memory in the process for reuse (glibc mallopt: blocks below 32 MiB, glibc's
// largest setting, come from the heap, and the heap is not trimmed below 2 GiB free). No effect
// with other C libraries.
void retain_freed_heap_memory();

}  // namespace dabench

// Google Benchmark's main with dabench's heap policy (harness/core/heap_policy.hpp), as in `dabench`.
#include <benchmark/benchmark.h>

#include "harness/core/heap_policy.hpp"

int main(int argc, char** argv) {
  dabench::retain_freed_heap_memory();
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}

// Google Benchmark's main with dabench's heap policy (harness/core/heap_policy.hpp), as in `dabench`,
// and the build's provenance and the command line in every output's context (git_commit,
// source_modified, command_line), as in a run's meta.json, so that a committed benchmark JSON can
// be traced to the code and the command that made it.
#include <benchmark/benchmark.h>

#include <string>

#include "harness/core/build_info.hpp"
#include "harness/core/heap_policy.hpp"

int main(int argc, char** argv) {
  dabench::retain_freed_heap_memory();
  const dabench::BuildInfo& build = dabench::build_info();
  benchmark::AddCustomContext("dabench_version", std::string(build.version));
  benchmark::AddCustomContext("git_commit", std::string(build.git_commit));
  benchmark::AddCustomContext("source_modified", build.source == dabench::Provenance::clean      ? "false"
                                                 : build.source == dabench::Provenance::modified ? "true"
                                                                                                 : "unknown");
  benchmark::AddCustomContext("build_type", std::string(build.build_type));
  std::string command_line;
  for (int i = 0; i < argc; ++i) command_line += (i ? " " : "") + std::string(argv[i]);
  benchmark::AddCustomContext("command_line", command_line);
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}

// dabench list: the registered algorithms, trackers and scenarios with their parameters and
// defaults, and the experiment files.
#include <algorithm>
#include <filesystem>
#include <set>

#include <fmt/format.h>

#include "apps/cli/command.hpp"
#include "harness/core/errors.hpp"
#include "harness/core/experiment.hpp"
#include "harness/core/input_file.hpp"
#include "harness/run/problem_kind.hpp"

namespace dabench::cli {

namespace {

namespace fs = std::filesystem;

fs::path experiments_folder() {
  if (fs::is_directory("experiments")) return "experiments";
  return fs::path(DABENCH_SOURCE_DIR) / "experiments";
}

int run_list(const Invocation& invocation) {
  if (!parse_command(kListCommand, po::options_description("list options"), po::positional_options_description(),
                     invocation)) {
    return 0;
  }
  std::string out;
  const char* gap = "";
  for (const ProblemKind* kind : problem_kinds()) {
    out += fmt::format("{}{}\n", gap, kind->algorithms_title());
    kind->list_algorithms(out);
    gap = "\n";
  }
  for (const ProblemKind* kind : problem_kinds()) {
    out += fmt::format("\n{}\n", kind->scenarios_title());
    kind->list_scenarios(out);
  }
  const fs::path folder = experiments_folder();
  out += fmt::format("\nExperiments (in {}):\n", folder.string());
  // A study keeps its experiment files in a folder of its own (experiments/<study>/): listed by
  // their path under the experiments folder, in path order.
  std::set<fs::path> files;
  std::error_code error;
  for (auto entry = fs::recursive_directory_iterator(folder, error); !error && entry != fs::recursive_directory_iterator();
       entry.increment(error)) {
    if (entry->is_regular_file() && entry->path().extension() == ".ini") files.insert(entry->path());
  }
  std::size_t name_width = 0;
  for (const auto& file : files) name_width = std::max(name_width, file.lexically_relative(folder).generic_string().size());
  for (const auto& file : files) {
    std::string description;
    try {
      description = load_experiment(file.string()).description;
    } catch (const InputError& problem) {
      description = fmt::format("(unreadable: {})", printable(problem.what()));
    }
    out += fmt::format("  {:<{}} {}\n", file.lexically_relative(folder).generic_string(), name_width, description);
  }
  print_stdout(out);
  return 0;
}

}  // namespace

const Command kListCommand{
    "list", "dabench list",
    "Prints the algorithms and trackers with their parameters and defaults, the scenarios and the\n"
    "experiment files.\n",
    run_list};

}  // namespace dabench::cli

#pragma once
// What the subcommands of the dabench command line share (apps/cli.cpp dispatches to them):
// each is a Command with its usage, defined in its own file (list.cpp, solve.cpp, run.cpp,
// merge.cpp, schedule.cpp, compare.cpp); the option parsing and the checked writes to stdout
// every command uses.
#include <optional>
#include <string>
#include <vector>

#include <boost/program_options.hpp>

namespace dabench::cli {

namespace po = boost::program_options;

// How the command was called: argv[0] is the command's name ("run"), argv[1..] its arguments;
// the whole command line as typed, and the line that finishes an interrupted run.
struct Invocation {
  int argc = 0;
  char** argv = nullptr;
  std::string command_line;
  std::string resume_line;
};

// A subcommand: `dabench --help` lists the synopses; `dabench COMMAND --help` adds the
// description and the options. `run` returns the exit status (apps/cli.hpp).
struct Command {
  const char* name;
  const char* synopsis;
  const char* description;
  int (*run)(const Invocation& invocation);
};

extern const Command kListCommand;
extern const Command kSolveCommand;
extern const Command kRunCommand;
extern const Command kMergeCommand;
extern const Command kScheduleCommand;
extern const Command kCompareCommand;

// Writes `text` to stdout and flushes it: a failed write (a full disk, a closed pipe or
// stdout) is a WriteError, exit status 1.
void print_stdout(const std::string& text);

// Parses the options of `command`, with --help/-h added; po errors become InputError with the
// command named. Returns nothing after printing the command's usage for --help (before
// required options are checked, so `dabench run --help` needs no experiment).
std::optional<po::variables_map> parse_command(const Command& command, po::options_description options,
                                               const po::positional_options_description& positional,
                                               const Invocation& invocation);

// The items of a comma-separated option value; an empty item is an error naming the command's option.
std::vector<std::string> comma_list(const std::string& text, const char* command, const char* option);

}  // namespace dabench::cli

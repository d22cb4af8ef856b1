// The dabench command line: dispatch to the subcommands of apps/cli/ (one file each), the
// program's usage and version, and the exit statuses of apps/cli.hpp.
#include "apps/cli.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <cstdio>
#include <filesystem>

#include <fmt/format.h>

#include "apps/cli/command.hpp"
#include "harness/core/build_info.hpp"
#include "harness/core/errors.hpp"
#include "harness/core/heap_policy.hpp"
#include "harness/core/input_file.hpp"

namespace dabench {

namespace {

// In the order `dabench --help` lists them.
constexpr std::array<const cli::Command*, 6> kCommands = {&cli::kListCommand,     &cli::kSolveCommand,
                                                          &cli::kRunCommand,      &cli::kMergeCommand,
                                                          &cli::kScheduleCommand, &cli::kCompareCommand};

// A standard stream the caller closed (`>&-`) is opened on /dev/null the wrong way round (read
// only for stdout and stderr): writes to it fail, as they should, and no result file opened
// later can take its descriptor and receive what was meant for the terminal.
void hold_closed_standard_streams() {
  for (const int fd : {STDIN_FILENO, STDOUT_FILENO, STDERR_FILENO}) {
    if (fcntl(fd, F_GETFD) != -1 || errno != EBADF) continue;
    const int opened = open("/dev/null", fd == STDIN_FILENO ? O_WRONLY : O_RDONLY);
    if (opened >= 0 && opened != fd) {
      dup2(opened, fd);
      close(opened);
    }
  }
}

std::string program_usage() {
  std::string text = "usage: ";
  const char* indent = "";
  for (const cli::Command* command : kCommands) {
    text += fmt::format("{}{}\n", indent, command->synopsis);
    indent = "       ";
  }
  return text + "       dabench --version\n"
                "       dabench COMMAND --help\n"
                "SPEC is NAME or NAME:key=value,key=value (see `dabench list`).\n";
}

// "dabench 0.1.0 (git <commit>)", with ", modified source" when the build's tree differed from
// that commit; the commit left out when the build did not record one.
std::string version_line() {
  const BuildInfo& build = build_info();
  if (build.git_commit.empty() || build.git_commit == "unknown") return fmt::format("dabench {}\n", build.version);
  const char* modified = build.source == Provenance::modified ? ", modified source" : "";
  return fmt::format("dabench {} (git {}{})\n", build.version, build.git_commit, modified);
}

std::string joined_command_line(int argc, char** argv) {
  std::string text;
  for (int k = 0; k < argc; ++k) {
    if (k > 0) text += ' ';
    text += argv[k];
  }
  return text;
}

// The command that finishes an interrupted run: the same words, --force/--resume replaced.
std::string resume_command_line(int argc, char** argv) {
  std::string text;
  for (int k = 0; k < argc; ++k) {
    const std::string word = argv[k];
    if (word == "--force" || word == "--resume") continue;
    text += (text.empty() ? "" : " ") + word;
  }
  return text + " --resume";
}

}  // namespace

int cli_main(int argc, char** argv) {
  hold_closed_standard_streams();
  retain_freed_heap_memory();
  const std::string command = argc > 1 ? argv[1] : "";
  try {
    for (const cli::Command* known : kCommands) {
      if (command == known->name) {
        return known->run({argc - 1, argv + 1, joined_command_line(argc, argv), resume_command_line(argc, argv)});
      }
    }
    if (command == "-h" || command == "--help" || command == "help") {
      if (argc > 2) throw InputError(fmt::format("{}: unexpected argument '{}' (for a command's usage: dabench COMMAND --help)", command, argv[2]));
      cli::print_stdout(program_usage());
      return 0;
    }
    if (command == "--version") {
      if (argc > 2) throw InputError(fmt::format("--version: unexpected argument '{}'", argv[2]));
      cli::print_stdout(version_line());
      return 0;
    }
    std::string names;
    for (std::size_t k = 0; k < kCommands.size(); ++k) {
      names += k == 0 ? "" : k + 1 == kCommands.size() ? " or " : ", ";
      names += kCommands[k]->name;
    }
    throw InputError(command.empty() ? fmt::format("missing command ({}; see dabench --help)", names)
                                     : fmt::format("unknown command '{}' ({}; see dabench --help)", command, names));
  } catch (const WriteError& error) {  // README: exit 1 when a write fails
    std::fprintf(stderr, "dabench: %s\n", printable_line(error.what()).c_str());
    return 1;
  } catch (const InputError& error) {
    std::fprintf(stderr, "dabench: %s\n", printable_line(error.what()).c_str());
    return 2;
  } catch (const std::filesystem::filesystem_error& error) {
    // The system's refusal of a path (too long, not a folder, ...): the path and the reason,
    // not the library's "filesystem error: ..." wording.
    std::fprintf(stderr, "dabench: %s\n",
                 printable_line(fmt::format("{}: {}", error.path1().string(), error.code().message())).c_str());
    return 2;
  } catch (const std::exception& error) {
    std::fprintf(stderr, "dabench: internal error: %s\n", printable_line(error.what()).c_str());
    return 1;
  }
}

}  // namespace dabench

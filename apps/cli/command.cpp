#include "apps/cli/command.hpp"

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <sstream>

#include <fmt/format.h>

#include "harness/core/errors.hpp"

namespace dabench::cli {

void print_stdout(const std::string& text) {
  errno = 0;
  if (std::fwrite(text.data(), 1, text.size(), stdout) != text.size() || std::fflush(stdout) != 0) {
    throw WriteError(fmt::format("standard output: write failed ({})", std::strerror(errno != 0 ? errno : EIO)));
  }
}

std::optional<po::variables_map> parse_command(const Command& command, po::options_description options,
                                               const po::positional_options_description& positional,
                                               const Invocation& invocation) {
  options.add_options()("help,h", "print this usage and exit");
  po::variables_map values;
  try {
    po::store(po::command_line_parser(invocation.argc, invocation.argv).options(options).positional(positional).run(),
              values);
    if (values.count("help")) {
      std::ostringstream text;
      text << "usage: " << command.synopsis << "\n" << command.description << "\n" << options;
      print_stdout(text.str());
      return std::nullopt;
    }
    po::notify(values);
  } catch (const po::error& error) {
    throw InputError(fmt::format("{}: {}", command.name, error.what()));
  }
  return values;
}

std::vector<std::string> comma_list(const std::string& text, const char* command, const char* option) {
  std::vector<std::string> items;
  std::size_t at = 0;
  while (at <= text.size()) {
    const std::size_t end = std::min(text.find(',', at), text.size());
    items.push_back(text.substr(at, end - at));
    if (items.back().empty()) throw InputError(fmt::format("{}: {} '{}' has an empty item", command, option, text));
    at = end + 1;
  }
  return items;
}

}  // namespace dabench::cli

#pragma once
// The error channel for bad configuration and bad input: a one-line message for the user.
// (Bugs abort through assertions; a failed or refused solve is reported in its result.)
#include <stdexcept>
#include <string>

namespace dabench {

class InputError : public std::runtime_error {
 public:
  // A NUL byte (quoted from a binary input) is written \x00: what() is a C string.
  explicit InputError(const std::string& message) : std::runtime_error(without_nul(message)) {}

 private:
  static std::string without_nul(std::string text) {
    for (std::size_t at = text.find('\0'); at != std::string::npos; at = text.find('\0', at)) text.replace(at, 1, "\\x00");
    return text;
  }
};

// A result file could not be written (disk full, I/O error): what was already written stays.
class WriteError : public InputError {
 public:
  explicit WriteError(const std::string& message) : InputError(message) {}
};

}  // namespace dabench

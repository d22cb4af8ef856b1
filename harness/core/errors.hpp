#pragma once
// The error channel for bad configuration and bad input: a one-line message for the user.
// (Bugs abort through assertions; a failed or refused solve is reported in its result.)
#include <stdexcept>
#include <string>

namespace dabench {

class InputError : public std::runtime_error {
 public:
  explicit InputError(const std::string& message) : std::runtime_error(message) {}
};

// A result file could not be written (disk full, I/O error): what was already written stays.
class WriteError : public InputError {
 public:
  explicit WriteError(const std::string& message) : InputError(message) {}
};

}  // namespace dabench

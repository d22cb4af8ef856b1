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

}  // namespace dabench

#pragma once
// Runs an action that must throw dabench::InputError and returns the message, so tests can
// check that the message names the offending key, value, file or line.
#include <catch2/catch.hpp>

#include <exception>
#include <string>

#include "harness/core/errors.hpp"

namespace dabench::test {

template <class Action>
std::string input_error_message(Action&& action) {
  try {
    action();
  } catch (const InputError& error) {
    return error.what();
  } catch (const std::exception& error) {
    FAIL("expected dabench::InputError, got another exception: " << error.what());
  }
  FAIL("expected dabench::InputError, nothing was thrown");
  return {};
}

}  // namespace dabench::test

// libFuzzer target: an algorithm SPEC ("name:key=value,...") as every kind's registry reads it
// (harness/core/params.hpp parse_spec, then make_single_scan_solver, make_multi_scan_solver,
// make_tracker, make_tbd_tracker: the name, each key, each value and the options' own checks).
// Any input must give an algorithm or an InputError.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "harness/core/errors.hpp"
#include "harness/core/params.hpp"
#include "harness/multi_scan/registry.hpp"
#include "harness/single_scan/registry.hpp"
#include "harness/tbd/registry.hpp"
#include "harness/tracking/registry.hpp"

namespace {

template <class Make>
void try_make(Make make, std::string_view spec) {
  try {
    (void)make(spec);
  } catch (const dabench::InputError&) {
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace dabench;
  const std::string_view spec(reinterpret_cast<const char*>(data), size);
  try {
    (void)parse_spec(spec);
  } catch (const InputError&) {
  }
  try_make([](std::string_view s) { return make_single_scan_solver(s); }, spec);
  try_make([](std::string_view s) { return make_multi_scan_solver(s); }, spec);
  try_make([](std::string_view s) { return make_tracker(s); }, spec);
  try_make([](std::string_view s) { return make_tbd_tracker(s); }, spec);
  return 0;
}

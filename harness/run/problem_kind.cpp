#include "harness/run/problem_kind.hpp"

#include <cstdio>
#include <cstdlib>
#include <stdexcept>

#include <fmt/format.h>

namespace dabench {

// The built-in kinds other than single scan (harness/run/kinds/<kind>.cpp).
const ProblemKind& multi_scan_kind();
const ProblemKind& tracking_kind();
const ProblemKind& tbd_kind();

namespace {

std::vector<const ProblemKind*>& kinds() {
  static std::vector<const ProblemKind*> all = {&single_scan_kind(), &multi_scan_kind(), &tracking_kind(), &tbd_kind()};
  return all;
}

}  // namespace

const std::vector<const ProblemKind*>& problem_kinds() { return kinds(); }

void register_problem_kind(const ProblemKind& kind) {
  for (const ProblemKind* known : kinds()) {
    if (known->name() == kind.name() || known->key() == kind.key()) {
      // Before main(): no exception can be caught, so say why and stop.
      std::fprintf(stderr, "dabench: problem kind '%.*s' (%.*s) is registered twice\n", static_cast<int>(kind.name().size()),
                   kind.name().data(), static_cast<int>(kind.key().size()), kind.key().data());
      std::abort();
    }
  }
  kinds().push_back(&kind);
}

const ProblemKind* kind_of_scenario(const std::string& scenario) {
  const ProblemKind* found = nullptr;
  for (const ProblemKind* kind : problem_kinds()) {
    if (!kind->has_scenario(scenario)) continue;
    if (found != nullptr) {  // (registries fill before main() in no fixed order: checked here, not at registration)
      throw std::logic_error(fmt::format("scenario '{}' is registered by two kinds, {} and {}", scenario, found->name(),
                                         kind->name()));
    }
    found = kind;
  }
  return found;
}

}  // namespace dabench

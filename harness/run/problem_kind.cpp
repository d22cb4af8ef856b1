#include "harness/run/problem_kind.hpp"

namespace dabench {

// The built-in kinds other than single scan (harness/run/kinds/<kind>.cpp).
const ProblemKind& multi_scan_kind();
const ProblemKind& tracking_kind();
const ProblemKind& tbd_kind();

const std::vector<const ProblemKind*>& problem_kinds() {
  static const std::vector<const ProblemKind*> kinds = {&single_scan_kind(), &multi_scan_kind(), &tracking_kind(),
                                                        &tbd_kind()};
  return kinds;
}

const ProblemKind* kind_of_scenario(const std::string& scenario) {
  for (const ProblemKind* kind : problem_kinds()) {
    if (kind->has_scenario(scenario)) return kind;
  }
  return nullptr;
}

}  // namespace dabench

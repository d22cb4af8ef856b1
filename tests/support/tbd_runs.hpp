#pragma once
// Runs of a track-before-detect tracker for the trackers' tests (test_tbd_bp, test_tbd_iemb,
// test_tbd_mb): every step of a problem, the known object's step-by-step checks, two runs
// compared bit for bit, a refused first step, and the option errors of a tracker's SPEC.
#include <catch2/catch.hpp>

#include <initializer_list>
#include <string>
#include <vector>

#include "harness/core/solve_report.hpp"
#include "harness/tbd/problem.hpp"
#include "harness/tbd/registry.hpp"
#include "harness/tbd/tracker.hpp"
#include "tests/support/input_error.hpp"

namespace dabench::test {

using EstimatesPerStep = std::vector<std::vector<TbdEstimate>>;

// Runs `tracker` over every frame of `problem`, requiring that no step is skipped; the
// estimates per step, and each step's report appended to *reports when given.
inline EstimatesPerStep estimates_per_step(TbdTracker& tracker, const TbdProblem& problem,
                                           std::vector<SolveReport>* reports = nullptr) {
  EstimatesPerStep out;
  tracker.start(problem);
  for (int k = 0; k < problem.steps(); ++k) {
    std::vector<TbdEstimate> estimates;
    SolveReport report;
    tracker.step(k, estimates, report);
    REQUIRE(report.skipped.empty());
    if (reports != nullptr) reports->push_back(report);
    out.push_back(estimates);
  }
  return out;
}

// Runs `tracker` over `problem` (one object with a known prior, label 0) step by step,
// requiring every step to report that object alone with r̃ > 0.9; check(k, estimate) then
// inspects the step (and the tracker) before the next one.
template <class Check>
void follow_known_object(TbdTracker& tracker, const TbdProblem& problem, Check&& check) {
  tracker.start(problem);
  for (int k = 0; k < problem.steps(); ++k) {
    INFO("step " << k);
    std::vector<TbdEstimate> estimates;
    SolveReport report;
    tracker.step(k, estimates, report);
    REQUIRE(report.skipped.empty());
    REQUIRE(estimates.size() == 1);
    const TbdEstimate& e = estimates[0];
    CHECK(e.label == 0);  // the prior's object throughout
    CHECK(e.existence > 0.9);
    check(k, e);
  }
}

// Two runs' estimates (of the same problem) are the same to the bit: per step the count, per
// estimate the label, the existence and every state component.
inline void check_identical_estimates(const EstimatesPerStep& a, const EstimatesPerStep& b) {
  for (std::size_t k = 0; k < a.size(); ++k) {
    REQUIRE(a[k].size() == b[k].size());
    for (std::size_t n = 0; n < a[k].size(); ++n) {
      CHECK(a[k][n].label == b[k][n].label);
      CHECK(a[k][n].existence == b[k][n].existence);
      for (int d = 0; d < 4; ++d) CHECK(a[k][n].state(d) == b[k][n].state(d));
    }
  }
}

// Starts `tracker` on `problem` and runs step 0, which must be skipped with a reason naming
// `reason` and no estimates; returns the step's report.
inline SolveReport check_first_step_skipped(TbdTracker& tracker, const TbdProblem& problem, const std::string& reason) {
  tracker.start(problem);
  std::vector<TbdEstimate> estimates;
  SolveReport report;
  tracker.step(0, estimates, report);
  INFO(report.skipped);
  CHECK(report.skipped.find(reason) != std::string::npos);
  CHECK(estimates.empty());
  return report;
}

// A SPEC that must be refused, and the option its message must name.
struct BadTbdSpec {
  const char* spec;
  const char* field;
};

// Every SPEC of `bad` is an InputError whose message names its field and the tracker `name`.
inline void check_tbd_option_errors(const std::string& name, std::initializer_list<BadTbdSpec> bad) {
  for (const BadTbdSpec& b : bad) {
    INFO(b.spec);
    const std::string message = input_error_message([&] { make_tbd_tracker(b.spec); });
    INFO(message);
    CHECK(message.find(b.field) != std::string::npos);
    CHECK(message.find(name) != std::string::npos);
  }
}

}  // namespace dabench::test

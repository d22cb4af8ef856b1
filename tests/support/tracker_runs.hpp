#pragma once
// Runs a tracker SPEC on a tracking problem for the trackers' tests and requires that it solved
// (no skipped: status), returning its tracks.
#include <catch2/catch.hpp>

#include <string>

#include "harness/tracking/registry.hpp"

namespace dabench::test {

inline TrackSet solved_tracks(const std::string& spec, const TrackingProblem& problem) {
  auto tracker = make_tracker(spec);
  TrackSet tracks;
  SolveReport report;
  tracker->run(problem, tracks, report);
  INFO(spec << ": " << report.skipped);
  REQUIRE(report.skipped.empty());
  return tracks;
}

}  // namespace dabench::test

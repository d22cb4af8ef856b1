#include "algorithms/multi_scan/exact.hpp"

#include <algorithm>

#include "harness/multi_scan/registry.hpp"

namespace dabench {

std::string MultiScanExactOptions::validate() const {
  if (max_events < 1) return "max_events must be >= 1";
  return {};
}

int MultiScanExact::digit(std::int64_t history, int scan) const {
  return static_cast<int>((history / stride_[scan]) % radix_[scan]);
}

// W_i(T) for every history T of every track; false if the tables alone exceed the work limit.
bool MultiScanExact::build_histories(const MultiScanProblem& problem) {
  const int scans = problem.scan_count();
  stride_.assign(scans, 1);
  radix_.assign(scans, 1);
  used_offset_.assign(scans + 1, 0);
  std::int64_t count = 1;
  for (int t = 0; t < scans; ++t) {
    stride_[t] = count;
    radix_[t] = problem.scans[t].measurements + 1;
    used_offset_[t + 1] = used_offset_[t] + radix_[t];
    if (count > options_.max_events / radix_[t]) return false;
    count *= radix_[t];
  }
  used_.assign(used_offset_[scans], 0);
  histories_.assign(problem.tracks(), {});
  for (int i = 0; i < problem.tracks(); ++i) {
    const int hypotheses = problem.hypotheses(i);
    work_ += count * hypotheses;
    if (work_ > options_.max_events) return false;
    TrackHistories& track = histories_[i];
    double largest = 0.0;
    for (std::int64_t history = 0; history < count; ++history) {
      double weight = 0.0;
      for (int h = 0; h < hypotheses; ++h) {
        double product = problem.prior[i][h];
        for (int t = 0; t < scans && product > 0.0; ++t) product *= problem.scans[t].factor[i](h, digit(history, t));
        weight += product;
      }
      if (weight > 0.0) {
        track.index.push_back(history);
        track.weight.push_back(weight);
        largest = std::max(largest, weight);
      }
    }
    for (double& weight : track.weight) weight /= largest;
    track.events.assign(track.weight.size(), 0.0);
  }
  return true;
}

// Depth-first search over tracks; false once the work limit is passed.
bool MultiScanExact::descend(int track, double prefix) {
  const int tracks = static_cast<int>(histories_.size());
  if (track == tracks) {
    partition_ += prefix;
    for (int i = 0; i < tracks; ++i) histories_[i].events[choice_[i]] += prefix;
    return true;
  }
  const TrackHistories& options = histories_[track];
  const int scans = static_cast<int>(radix_.size());
  for (std::size_t k = 0; k < options.index.size(); ++k) {
    if (++work_ > options_.max_events) return false;
    const std::int64_t history = options.index[k];
    bool feasible = true;
    for (int t = 0; t < scans && feasible; ++t) {
      const int j = digit(history, t);
      feasible = j == 0 || !used_[used_offset_[t] + j];
    }
    if (!feasible) continue;
    for (int t = 0; t < scans; ++t) used_[used_offset_[t] + digit(history, t)] = digit(history, t) > 0;
    choice_[track] = static_cast<int>(k);
    const bool within_limit = descend(track + 1, prefix * options.weight[k]);
    for (int t = 0; t < scans; ++t) used_[used_offset_[t] + digit(history, t)] = 0;
    if (!within_limit) return false;
  }
  return true;
}

void MultiScanExact::write_beliefs(const MultiScanProblem& problem, MultiScanBeliefs& beliefs) const {
  const int scans = problem.scan_count();
  beliefs.track.resize(problem.tracks());
  beliefs.association.resize(scans);
  for (int t = 0; t < scans; ++t) beliefs.association[t].reshape_zero(problem.tracks(), problem.scans[t].measurements);
  for (int i = 0; i < problem.tracks(); ++i) {
    const TrackHistories& track = histories_[i];
    Vector& belief = beliefs.track[i];
    belief = Vector::Zero(problem.hypotheses(i));
    for (std::size_t k = 0; k < track.index.size(); ++k) {
      if (track.events[k] == 0.0) continue;
      const double share = track.events[k] / partition_;
      for (int t = 0; t < scans; ++t) beliefs.association[t](i, digit(track.index[k], t)) += share;
      // Split the history's share over hypotheses in proportion to their term of W_i(T).
      Vector terms(problem.hypotheses(i));
      for (int h = 0; h < problem.hypotheses(i); ++h) {
        double product = problem.prior[i][h];
        for (int t = 0; t < scans && product > 0.0; ++t) product *= problem.scans[t].factor[i](h, digit(track.index[k], t));
        terms[h] = product;
      }
      belief += share / terms.sum() * terms;
    }
  }
}

void MultiScanExact::solve(const MultiScanProblem& problem, MultiScanBeliefs& beliefs, SolveReport& report) {
  report.reset();
  work_ = 0;
  partition_ = 0.0;
  if (!build_histories(problem)) {
    report.skipped = "work_limit";
    return;
  }
  choice_.assign(problem.tracks(), 0);
  if (!descend(0, 1.0)) {
    report.skipped = "work_limit";
    return;
  }
  if (!(partition_ > 0.0)) {
    report.skipped = "zero_partition";
    return;
  }
  write_beliefs(problem, beliefs);
}

DABENCH_REGISTER_MULTI_SCAN_ALGORITHM(MultiScanExact);

}  // namespace dabench

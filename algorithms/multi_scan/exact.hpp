#pragma once
// Exact multiple-scan posterior (multiscan-convex-variational, eqs 1–4) by enumerating every
// feasible global hypothesis: each track i takes a history T = (a_1, ..., a_S) of one
// measurement or a miss per scan, no two tracks use the same measurement of the same scan
// (eq 1), and the hypothesis has probability ∝ Π_i W_i(T_i) with
//   W_i(T) = Σ_{A^i} ψ^i(A^i) Π_t' ψ^i_t'(A^i, T_t')          (A^i marginalised out).
// From the weighted events come the exact beliefs
//   q^i(A^i)      = Σ_T Z_i(T)/W_i(T) · ψ^i(A^i) Π_t' ψ^i_t'(A^i, T_t') / Z      (eq 4)
//   q^{i,j}_t'    = Σ_{T: T_t' = j} Z_i(T) / Z
// where Z_i(T) sums the weights of the events in which track i takes T and Z sums all events.
// Each track's W_i is scaled by its largest value (marginals unchanged) so products stay in
// range for the small problems this serves.
//
// This is the test oracle of the multiple-scan algorithms: the cost is the number of feasible
// events, exponential in tracks × scans. Past `max_events` (search nodes, plus the per-track
// history tables) the solve is refused with status skipped:work_limit.
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "harness/core/params.hpp"
#include "harness/multi_scan/solver.hpp"

namespace dabench {

struct MultiScanExactOptions {
  std::int64_t max_events = 100000000;  // work limit: enumeration steps per problem

  void bind(ParamList& params) {
    params.add("max_events", max_events, "work limit in enumeration steps (skipped:work_limit above)");
  }
  std::string validate() const;
};

class MultiScanExact final : public MultiScanSolver {
 public:
  using Options = MultiScanExactOptions;
  static constexpr std::string_view kName = "ms-exact";
  static constexpr std::string_view kSummary =
      "exact multiple-scan posterior by enumerating feasible joint histories, eqs (1)-(4) (test oracle)";

  explicit MultiScanExact(const Options& options) : options_(options) {}
  void solve(const MultiScanProblem& problem, MultiScanBeliefs& beliefs, SolveReport& report) override;

 private:
  // One track's histories with nonzero weight: index into the mixed-radix history space.
  struct TrackHistories {
    std::vector<std::int64_t> index;
    std::vector<double> weight;   // W_i(T), scaled by 1 / max_T W_i(T)
    std::vector<double> events;   // Z_i(T), accumulated by the search
  };
  [[nodiscard]] bool build_histories(const MultiScanProblem& problem);
  [[nodiscard]] bool descend(int track, double prefix);
  void write_beliefs(const MultiScanProblem& problem, MultiScanBeliefs& beliefs) const;
  int digit(std::int64_t history, int scan) const;

  Options options_;
  std::int64_t work_ = 0;
  std::vector<std::int64_t> stride_;     // mixed radix: stride of scan t' in a history index
  std::vector<int> radix_;               // m_t' + 1
  std::vector<int> used_offset_;         // scan t' → first slot in used_
  std::vector<char> used_;               // per (scan, measurement): taken by an earlier track
  std::vector<int> choice_;              // per track: position in its history list
  std::vector<TrackHistories> histories_;
  double partition_ = 0.0;               // Z
};

}  // namespace dabench

#pragma once
// The multiple-scan methods of multiscan-convex-variational, Sec. IV, as registered solvers.
// All run Algorithm 2 (ConvexVariationalPdca, convex_variational.hpp); they differ in the
// fractional weights γ_t', the κ weights and whether scans are added one at a time:
//   cv           γ_t' = 1/(|S|+1) on every scan, Lemma-4 weights, all scans at once
//   cvs:gamma    sequential: step k adds scan k with γ on it and 0 on past scans, Lemma-4
//                weights, factors modified by Theorem 3 (eq 91) whenever a scan's γ or β changes
//   cvh          cv with the heuristic weights of eqs (93)–(95)
//   cvsh:gamma   cvs with the heuristic weights
//   cvsh1:gamma  cvsh with a single backward–forward sweep per step
//   msbp         γ_t' = 1 on every scan, heuristic weights: multiple-scan BP (non-convex)
// Every method sets β_t' so that block (t',1) sees β̃_t' = β_t'/(κ_{f,t'} + κ_{t',1,t'}) =
// beta_tilde (default 1, as in the paper's experiments). Sequential methods report the beliefs
// of the last step (all scans, every association belief q^{i,j}_t' from that final solve);
// `iterations` is the total number of sweeps over all steps.
#include <string>
#include <string_view>

#include "algorithms/convex_variational.hpp"
#include "harness/multi_scan_solver.hpp"
#include "harness/params.hpp"

namespace dabench {

// Options of the methods that iterate to convergence on all scans at once (cv, cvh, msbp).
struct ConvexVariationalOptions {
  double tolerance = 1e-9;  // stop when no dual variable λ (log units) moved more than this in a sweep
  double belief_tolerance = 1e-7;  // or when the beliefs are estimated within this of their limit
  int max_sweeps = 2000;    // sweep cap (converged=0 if reached)
  double beta_tilde = 1.0;  // β̃ of the single-scan blocks (79); >= 1 keeps Algorithm 1's β >= γ

  void bind(ParamList& params) {
    params.add("tolerance", tolerance, "stop when no dual variable moves more than this in a sweep");
    params.add("belief_tolerance", belief_tolerance,
               "or when the beliefs are estimated (from the observed linear rate) within this of their limit; 0: off");
    params.add("max_sweeps", max_sweeps, "backward-forward sweep cap (converged=0 if reached)");
    params.add("beta_tilde", beta_tilde, "false-alarm coefficient seen by the single-scan blocks (eq 79)");
  }
  std::string validate() const;
};

// Options of the sequential methods that iterate to convergence at each step (cvs, cvsh).
struct SequentialConvexVariationalOptions {
  double gamma = 0.95;      // γ of the newest scan (past scans: 0)
  double tolerance = 1e-9;
  double belief_tolerance = 1e-7;
  int max_sweeps = 2000;    // per step
  double beta_tilde = 1.0;

  void bind(ParamList& params) {
    params.add("gamma", gamma, "fractional weight of the newest scan (past scans: 0)");
    params.add("tolerance", tolerance, "stop a step when no dual variable moves more than this in a sweep");
    params.add("belief_tolerance", belief_tolerance,
               "or when the beliefs are estimated (from the observed linear rate) within this of their limit; 0: off");
    params.add("max_sweeps", max_sweeps, "backward-forward sweep cap per step (converged=0 if reached)");
    params.add("beta_tilde", beta_tilde, "false-alarm coefficient seen by the single-scan blocks (eq 79)");
  }
  std::string validate() const;  // γ in [0, 1) (Lemma 4 needs Σγ < 1)
};

// cvsh with the γ range of the heuristic weights, [0, 1].
struct HeuristicSequentialOptions : SequentialConvexVariationalOptions {
  std::string validate() const;
};

// cvsh1: one sweep per step.
struct SingleSweepOptions {
  double gamma = 0.95;
  double beta_tilde = 1.0;

  void bind(ParamList& params) {
    params.add("gamma", gamma, "fractional weight of the newest scan (past scans: 0)");
    params.add("beta_tilde", beta_tilde, "false-alarm coefficient seen by the single-scan blocks (eq 79)");
  }
  std::string validate() const;
};

// What distinguishes one method from another (see the table above).
struct ConvexVariationalSchedule {
  bool sequential = false;
  double gamma = 0.0;       // sequential: γ of the newest scan
  double beta_tilde = 1.0;
  bool bethe = false;       // batch: γ_t' = 1 (msbp) instead of 1/(|S|+1)
  PdcaSettings settings;    // κ weights, tolerances, sweep cap
};

// Runs a schedule on a problem (the body of every registered method).
void solve_convex_variational(const ConvexVariationalSchedule& schedule, ConvexVariationalPdca& pdca,
                              const MultiScanProblem& problem, MultiScanBeliefs& beliefs, SolveReport& report);

// A registered method: a name, its Options and the schedule they give.
template <class Method>
class ConvexVariationalSolver final : public MultiScanSolver {
 public:
  using Options = typename Method::Options;
  static constexpr std::string_view kName = Method::kName;
  static constexpr std::string_view kSummary = Method::kSummary;

  explicit ConvexVariationalSolver(const Options& options) : schedule_(Method::schedule(options)) {}
  void solve(const MultiScanProblem& problem, MultiScanBeliefs& beliefs, SolveReport& report) override {
    solve_convex_variational(schedule_, pdca_, problem, beliefs, report);
  }

 private:
  ConvexVariationalSchedule schedule_;
  ConvexVariationalPdca pdca_;
};

struct CvMethod {
  using Options = ConvexVariationalOptions;
  static constexpr std::string_view kName = "cv";
  static constexpr std::string_view kSummary =
      "convex variational: Algorithm 2, Lemma-4 weights, gamma=1/(|S|+1) on all scans at once";
  static ConvexVariationalSchedule schedule(const Options& options);
};

struct CvsMethod {
  using Options = SequentialConvexVariationalOptions;
  static constexpr std::string_view kName = "cvs";
  static constexpr std::string_view kSummary =
      "sequential convex variational: one scan per step, gamma on the newest, Theorem-3 factor modification";
  static ConvexVariationalSchedule schedule(const Options& options);
};

struct CvhMethod {
  using Options = ConvexVariationalOptions;
  static constexpr std::string_view kName = "cvh";
  static constexpr std::string_view kSummary = "cv with the heuristic weights of eqs (93)-(95)";
  static ConvexVariationalSchedule schedule(const Options& options);
};

struct CvshMethod {
  using Options = HeuristicSequentialOptions;
  static constexpr std::string_view kName = "cvsh";
  static constexpr std::string_view kSummary = "cvs with the heuristic weights of eqs (93)-(95)";
  static ConvexVariationalSchedule schedule(const Options& options);
};

struct Cvsh1Method {
  using Options = SingleSweepOptions;
  static constexpr std::string_view kName = "cvsh1";
  static constexpr std::string_view kSummary = "cvsh with one backward-forward sweep per step";
  static ConvexVariationalSchedule schedule(const Options& options);
};

struct MsbpMethod {
  using Options = ConvexVariationalOptions;
  static constexpr std::string_view kName = "msbp";
  static constexpr std::string_view kSummary =
      "multiple-scan BP: Algorithm 2, gamma=1 on all scans, heuristic weights (non-convex)";
  static ConvexVariationalSchedule schedule(const Options& options);
};

using ConvexVariational = ConvexVariationalSolver<CvMethod>;
using ConvexVariationalSequential = ConvexVariationalSolver<CvsMethod>;
using ConvexVariationalHeuristic = ConvexVariationalSolver<CvhMethod>;
using ConvexVariationalSequentialHeuristic = ConvexVariationalSolver<CvshMethod>;
using ConvexVariationalSingleSweep = ConvexVariationalSolver<Cvsh1Method>;
using MultipleScanBp = ConvexVariationalSolver<MsbpMethod>;

}  // namespace dabench

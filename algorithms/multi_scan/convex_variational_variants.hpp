#pragma once
// The multiple-scan methods of multiscan-convex-variational, Sec. IV, as registered solvers.
// They differ in the fractional weights γ_t', the false-alarm weights β_t' and whether scans are
// added one at a time:
//   cv           γ_t' = 1/(|S|+1) on every scan, all scans at once, β from the Lemma-4 weights
//   cvs:gamma    sequential: step k adds scan k with γ on it and 0 on past scans, factors modified
//                by Theorem 3 (eq 91) whenever a scan's γ or β changes; β from Lemma 4
//   cvh          cv with β from the heuristic weights of eqs (93)–(95)
//   cvsh:gamma   cvs with β from the heuristic weights
//   cvsh1:gamma  cvsh with a single backward–forward sweep of Algorithm 2 per step
//   msbp         γ_t' = 1 on every scan, heuristic weights: multiple-scan BP (non-convex)
// Every method sets β_t' so that block (t',1) of Algorithm 2 sees β̃_t' = β_t'/(κ_{f,t'} +
// κ_{t',1,t'}) = beta_tilde (default 1, as in the paper's experiments): with Lemma 4 that is
// β_t' = β̃ (γ_t' + 2η/(|S|+1)) (κ_{f,t'} = η/(|S|+1) and κ_{t',1,t'} = γ_t' + η/(|S|+1), eqs (69),
// (71)), with the heuristic weights β_t' = β̃.
//
// Solvers. cv, cvs, cvh and cvsh minimise the convex free energy (63) with their (γ, β), which
// is strictly convex (Σγ < 1); its minimiser does not depend on how (63) is split, so the κ
// weights only matter to Algorithm 2. By default (solver=auto) they use the reduced column-dual
// solver (column_dual_newton.hpp): damped Newton while the number of column duals Σ_t m_t is at
// most newton_limit, L-BFGS beyond (solver=newton / lbfgs force one). solver=pdca runs
// Algorithm 2 (ConvexVariationalPdca, convex_variational.hpp) with the method's κ weights —
// Lemma 4 for cv/cvs (guaranteed convergence, Theorem 2), eqs (93)–(95) for cvh/cvsh — and is the
// validator: both reach the same beliefs (tests/multi_scan/test_column_dual_newton.cpp). msbp (Σγ > 1, not
// convex) and cvsh1 (one sweep by definition) always run Algorithm 2; so do cvsh with gamma = 1
// and problems in which some track cannot miss in some scan (ColumnDualSolver::applicable).
// Sequential methods report the beliefs of the last step (all scans, every association belief
// q^{i,j}_t' from that final solve); `iterations` is the total number of Newton (or L-BFGS)
// iterations, or of Algorithm-2 sweeps, over all steps.
#include <string>
#include <string_view>

#include "algorithms/multi_scan/column_dual_newton.hpp"
#include "algorithms/multi_scan/convex_variational.hpp"
#include "harness/core/params.hpp"
#include "harness/multi_scan/solver.hpp"

namespace dabench {

// The solver choice and the column-dual solver's settings, shared by cv, cvs, cvh and cvsh.
struct ConvexSolverOptions {
  static constexpr int kAuto = 0, kNewton = 1, kLbfgs = 2, kPdca = 3;
  int solver = kAuto;                // auto: newton if Σ_t m_t <= newton_limit, else lbfgs
  double residual_tolerance = 1e-12; // newton/lbfgs: stop when every column residual |Σ_i q^{i,j} + q^{0,j} − 1| is below
  int max_iterations = 500;          // newton/lbfgs: iterations per solve (converged=0 if reached)
  int newton_limit = 1500;           // auto: largest number of column duals for newton
  double tolerance = 1e-9;           // pdca: stop when no dual variable λ (log units) moved more than this in a sweep
  double belief_tolerance = 1e-7;    // pdca: or when the beliefs are estimated within this of their limit
  int max_sweeps = 2000;             // pdca: sweep cap per solve (converged=0 if reached)
  double beta_tilde = 1.0;           // β̃ of the single-scan blocks (79); >= 1 keeps Algorithm 1's β >= γ

  void bind(ParamList& params) {
    params.add_choice("solver", solver, {"auto", "newton", "lbfgs", "pdca"},
                      "auto|newton|lbfgs|pdca: column-dual Newton or L-BFGS (auto: by size), or Algorithm 2");
    params.add("residual_tolerance", residual_tolerance, "newton/lbfgs: largest column residual at which a solve stops");
    params.add("max_iterations", max_iterations, "newton/lbfgs: iterations per solve (converged=0 if reached)");
    params.add("newton_limit", newton_limit, "auto: newton while the scans hold at most this many measurements");
    params.add("tolerance", tolerance, "pdca: stop when no dual variable moves more than this in a sweep");
    params.add("belief_tolerance", belief_tolerance,
               "pdca: or when the beliefs are estimated (from the observed linear rate) within this of their limit; 0: off");
    params.add("max_sweeps", max_sweeps, "pdca: backward-forward sweep cap per solve (converged=0 if reached)");
    params.add("beta_tilde", beta_tilde, "false-alarm coefficient seen by the single-scan blocks (eq 79)");
  }
  std::string validate() const;
};

// cv, cvh.
struct ConvexVariationalOptions : ConvexSolverOptions {};

// cvs, cvsh: the newest scan's γ.
struct SequentialConvexVariationalOptions : ConvexSolverOptions {
  double gamma = 0.95;  // γ of the newest scan (past scans: 0)

  void bind(ParamList& params) {
    params.add("gamma", gamma, "fractional weight of the newest scan (past scans: 0)");
    ConvexSolverOptions::bind(params);
  }
  std::string validate() const;  // γ in [0, 1)
};

// cvsh: γ in [0, 1] (γ = 1 runs Algorithm 2: the column-dual solvers need Σγ < 1).
struct HeuristicSequentialOptions : SequentialConvexVariationalOptions {
  std::string validate() const;
};

// msbp: Algorithm 2 only.
struct PdcaOptions {
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
  bool column_dual = false; // the column-dual solver instead of Algorithm 2
  PdcaSettings settings;    // Algorithm 2: κ weights (they also set β), tolerances, sweep cap
  ColumnDualSettings dual;  // the column-dual solver
};

// The engines a method may run, kept between solves (one per thread).
struct ConvexVariationalEngines {
  ConvexVariationalPdca pdca;
  ColumnDualSolver dual;
};

// Runs a schedule on a problem (the body of every registered method).
void solve_convex_variational(const ConvexVariationalSchedule& schedule, ConvexVariationalEngines& engines,
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
    solve_convex_variational(schedule_, engines_, problem, beliefs, report);
  }

 private:
  ConvexVariationalSchedule schedule_;
  ConvexVariationalEngines engines_;
};

struct CvMethod {
  using Options = ConvexVariationalOptions;
  static constexpr std::string_view kName = "cv";
  static constexpr std::string_view kSummary =
      "convex variational: gamma=1/(|S|+1) on all scans at once, Lemma-4 beta; column-dual Newton (or Algorithm 2)";
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
  static constexpr std::string_view kSummary =
      "cv with beta from the heuristic weights of eqs (93)-(95) (Algorithm 2 with those weights under solver=pdca)";
  static ConvexVariationalSchedule schedule(const Options& options);
};

struct CvshMethod {
  using Options = HeuristicSequentialOptions;
  static constexpr std::string_view kName = "cvsh";
  static constexpr std::string_view kSummary =
      "cvs with beta from the heuristic weights of eqs (93)-(95) (Algorithm 2 with those weights under solver=pdca)";
  static ConvexVariationalSchedule schedule(const Options& options);
};

struct Cvsh1Method {
  using Options = SingleSweepOptions;
  static constexpr std::string_view kName = "cvsh1";
  static constexpr std::string_view kSummary = "cvsh with one backward-forward sweep of Algorithm 2 per step";
  static ConvexVariationalSchedule schedule(const Options& options);
};

struct MsbpMethod {
  using Options = PdcaOptions;
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

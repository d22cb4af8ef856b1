// Tests of MD-HMHT's hypothesis machinery (algorithms/tracking/md_hmht.hpp) against an
// enumeration of association histories written here from the header's definitions — the UKF of
// algorithms/tracking/ukf.hpp per path, ψ and the scores of the header, every feasible event
// of a scan by recursion — and independent of the tracker's code (its TrackFilter, Murty,
// list merge, selection and pruning). Also: N-scan pruning (window 1 against 3) and the 3 / 5
// empty-gate deletion limit on constructed cases, and the readings report_from, assignment
// and literal.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <functional>
#include <numbers>
#include <string>
#include <tuple>
#include <vector>

#include <Eigen/LU>
#include <fmt/format.h>

#include "algorithms/tracking/chi_square.hpp"
#include "algorithms/tracking/md_hmht.hpp"
#include "algorithms/tracking/track_heads.hpp"
#include "algorithms/tracking/ukf.hpp"
#include "harness/core/errors.hpp"
#include "harness/core/random_stream.hpp"
#include "harness/tracking/registry.hpp"
#include "scenarios/tracking/othr.hpp"
#include "tests/support/tracker_runs.hpp"

namespace DABENCH_TEST_FILE {

namespace {

using dabench::Gaussian;
using dabench::Vector;
using dabench::md_hmht::HypothesisSnapshot;

constexpr int kPaths = 4;
using Assigned = std::vector<std::vector<std::vector<int>>>;  // [track][scan − 1][path]

// The OTHR model (sensor, F, Q, region) with p_d = pd on every path and λ from `clutter`; the
// scans hold only what the test puts there.
dabench::TrackingProblem model_problem(double pd, double clutter, std::vector<Eigen::MatrixXd> scans) {
  dabench::OthrOptions o;
  o.pd = pd;
  o.clutter = 0.0;
  o.scans = 1;
  dabench::TrackingScenarioSample sample;
  dabench::RandomStream rng(7, 0, 0);
  dabench::OthrScenario(o).generate(rng, sample);
  dabench::TrackingProblem problem = sample.problem;
  problem.scans = std::move(scans);
  problem.clutter_mean = clutter;
  return problem;
}

Eigen::Vector3d slant(const Vector& x, int path) {
  return dabench::othr::slant_measurement(x, dabench::othr::kPathTable[path]);
}

// Noiseless returns: per scan, per (state, path) listed, one column.
struct Return {
  Vector state;
  int path;
};
Eigen::MatrixXd scan_of(const std::vector<Return>& returns) {
  Eigen::MatrixXd scan(3, static_cast<int>(returns.size()));
  for (std::size_t c = 0; c < returns.size(); ++c) scan.col(static_cast<int>(c)) = slant(returns[c].state, returns[c].path);
  return scan;
}

// ---- The enumeration -------------------------------------------------------------------

struct Arc {
  int measurement;
  double log_psi;  // ln ψ = ln p_d + ln N(y; ŷ, S) − ln(1 − p_d p_g) − ln λ
};

// A track of one history: its filtered estimate, LLR, successive scans with empty gates, and
// what each path took at each scan after its head's (scan 0).
struct EnumTrack {
  Gaussian x;
  double llr = 0.0;
  int empty = 0;
  bool confirmed = false;
  std::vector<std::vector<int>> assigned;
};

// One association history: its live tracks, deleted confirmed tracks, log-likelihood ratio.
struct History {
  double score = 0.0;
  std::vector<EnumTrack> tracks;
  std::vector<EnumTrack> ended;
  std::vector<long> lineage;  // id of its ancestor at scans −1, 0, ..., its own scan

  Assigned assigned() const {
    Assigned a;
    for (const EnumTrack& t : tracks) a.push_back(t.assigned);
    return a;
  }
};

class Enumeration {
 public:
  // `limit`: scans with empty gates before deletion; confirmation at LLR ≥ 6.9 (the defaults).
  Enumeration(const dabench::TrackingProblem& problem, double pg, int limit = 3)
      : problem_(problem), pg_(pg), limit_(limit) {
    gate_ = dabench::chi_square_quantile(pg, 3);
    log_lambda_ = std::log(problem.clutter_mean / problem.region_volume());
  }

  // The heads of scan 0 as the tracker starts them (every measurement is a candidate).
  History root(bool alternative_heads) {
    const Eigen::MatrixXd& scan = problem_.scans[0];
    std::vector<int> all(static_cast<std::size_t>(scan.cols()));
    for (int j = 0; j < scan.cols(); ++j) all[j] = j;
    const auto options = dabench::ground_head_options(4, 3, {80.0, 0.005, 0.03}, 2e-4, gate_, alternative_heads);
    History h;
    for (dabench::TrackHead& head : dabench::form_track_heads(scan, all, *problem_.sensor, options)) {
      EnumTrack& t = h.tracks.emplace_back();
      t.x = {head.mean, head.covariance};
    }
    h.lineage = {0, next_id_++};  // the empty hypothesis before scan 0, then this one
    return h;
  }

  // Per track, per path: the gated measurements of scan k with ln ψ, and the predictions.
  struct Gates {
    std::vector<Gaussian> predicted;
    std::vector<std::array<std::vector<Arc>, kPaths>> arcs;
  };
  Gates gates(const History& h, int k) const {
    Gates g;
    const Eigen::MatrixXd& scan = problem_.scans[k];
    for (const EnumTrack& t : h.tracks) {
      const Gaussian& x = t.x;
      Gaussian p{problem_.transition * x.mean, problem_.transition * x.covariance * problem_.transition.transpose() +
                                                   problem_.process_covariance};
      auto& arcs = g.arcs.emplace_back();
      for (int tau = 0; tau < kPaths; ++tau) {
        const auto u = dabench::unscented_transform(p, [&](const Vector& s) { return problem_.sensor->measure(tau, s); });
        const Eigen::MatrixXd S = u.covariance + problem_.sensor->noise_covariance(tau);
        const Eigen::MatrixXd S_inverse = S.inverse();
        const double pd = problem_.detection_probability[tau];
        for (int j = 0; j < scan.cols(); ++j) {
          const Eigen::VectorXd d = scan.col(j) - u.mean;
          const double d2 = d.dot(S_inverse * d);
          if (d2 > gate_) continue;
          const double log_density = -0.5 * d2 - 0.5 * std::log((2.0 * std::numbers::pi * S).determinant());
          arcs[tau].push_back({j, std::log(pd) + log_density - std::log1p(-pd * pg_) - log_lambda_});
        }
      }
      g.predicted.push_back(std::move(p));
    }
    return g;
  }

  // Every event of the rows (track, τ ∈ paths) over the measurements not in `taken`: each row
  // one gated measurement or none, each measurement at most one row. `measurement` per (track,
  // path) row, −1 none; `gain` = Σ ln ψ of its pairs.
  struct Event {
    double gain = 0.0;
    std::vector<int> measurement;
  };
  static void events(const Gates& g, const std::vector<int>& paths, std::vector<char> taken, Event e, std::size_t row,
                     std::vector<Event>& out) {
    const std::size_t rows = g.arcs.size() * paths.size();
    if (row == rows) {
      out.push_back(e);
      return;
    }
    const int t = static_cast<int>(row / paths.size()), tau = paths[row % paths.size()];
    events(g, paths, taken, e, row + 1, out);  // the row takes nothing
    for (const Arc& arc : g.arcs[t][tau]) {
      if (taken[arc.measurement]) continue;
      Event next = e;
      next.gain += arc.log_psi;
      next.measurement[static_cast<std::size_t>(t) * kPaths + tau] = arc.measurement;
      taken[arc.measurement] = 1;
      events(g, paths, taken, next, row + 1, out);
      taken[arc.measurement] = 0;
    }
  }

  // The parent's children at scan k, best first: every joint event (assignment = joint), or
  // the path-by-path beam of width `beam` (assignment = per_path, header).
  std::vector<History> children(const History& h, int k, bool per_path, int beam) {
    const Gates g = gates(h, k);
    const std::size_t tracks = h.tracks.size();
    const int columns = static_cast<int>(problem_.scans[k].cols());
    std::vector<Event> list;
    const Event empty{0.0, std::vector<int>(tracks * kPaths, -1)};
    if (!per_path) {
      events(g, {0, 1, 2, 3}, std::vector<char>(columns, 0), empty, 0, list);
      by_gain(list);
    } else {
      list = {empty};
      for (int tau = 0; tau < kPaths; ++tau) {
        std::vector<Event> extended;
        for (const Event& q : list) {
          std::vector<char> taken(columns, 0);
          for (int j : q.measurement)
            if (j >= 0) taken[j] = 1;
          events(g, {tau}, taken, q, 0, extended);
        }
        by_gain(extended);
        if (static_cast<int>(extended.size()) > beam) extended.resize(beam);
        list = std::move(extended);
      }
    }
    double miss = 0.0;  // Σ over one track's rows of ln(1 − p_d p_g)
    for (int tau = 0; tau < kPaths; ++tau) miss += std::log1p(-problem_.detection_probability[tau] * pg_);
    std::vector<History> out;
    for (const Event& e : list) {
      History c;
      c.score = h.score + e.gain;
      c.lineage = h.lineage;
      c.lineage.push_back(next_id_++);
      c.ended = h.ended;
      for (std::size_t t = 0; t < tracks; ++t) {
        const int* m = &e.measurement[t * kPaths];
        EnumTrack next = h.tracks[t];
        c.score += miss;
        next.llr += miss;
        for (int tau = 0; tau < kPaths; ++tau) {
          for (const Arc& arc : g.arcs[t][tau])
            if (arc.measurement == m[tau]) next.llr += arc.log_psi;
        }
        next.confirmed = next.confirmed || next.llr >= 6.9;
        const bool gated = std::any_of(g.arcs[t].begin(), g.arcs[t].end(), [](const auto& a) { return !a.empty(); });
        next.empty = gated ? 0 : next.empty + 1;
        next.assigned.emplace_back(m, m + kPaths);
        next.x = updated(g.predicted[t], m, k);
        if (next.empty < limit_) c.tracks.push_back(std::move(next));  // else deleted, kept if confirmed
        else if (next.confirmed) c.ended.push_back(std::move(next));
      }
      out.push_back(std::move(c));
    }
    return out;
  }

  // The UKF update of `x` with the stacked measurement of the paths that took one.
  Gaussian updated(Gaussian x, const int* measurement, int k) const {
    std::vector<int> paths;
    for (int tau = 0; tau < kPaths; ++tau)
      if (measurement[tau] >= 0) paths.push_back(tau);
    if (paths.empty()) return x;
    const int m = 3 * static_cast<int>(paths.size());
    dabench::ScanMeasurement y;
    y.value.resize(m);
    y.covariance = Eigen::MatrixXd::Zero(m, m);
    for (std::size_t i = 0; i < paths.size(); ++i) {
      y.value.segment(3 * i, 3) = problem_.scans[k].col(measurement[paths[i]]);
      y.covariance.block(3 * i, 3 * i, 3, 3) = problem_.sensor->noise_covariance(paths[i]);
    }
    dabench::unscented_update(x, y, [&](const Vector& s) {
      Vector h(m);
      for (std::size_t i = 0; i < paths.size(); ++i) h.segment(3 * i, 3) = problem_.sensor->measure(paths[i], s);
      return h;
    });
    return x;
  }

  // Scans 1..K−1 from `root`: per scan, each surviving history's children (its `n` best, or
  // all with n = 0); reading A keeps the n best children overall, reading B all of them; then
  // the children whose ancestor at scan k − window differs from the best child's are dropped.
  // `observe(k, survivors)` after each scan.
  void run(History root, int n, bool per_parent, int window, bool per_path,
           const std::function<void(int, const std::vector<History>&)>& observe) {
    std::vector<History> alive{std::move(root)};
    for (int k = 1; k < problem_.scan_count(); ++k) {
      std::vector<History> next;
      for (const History& h : alive) {
        std::vector<History> c = children(h, k, per_path, n > 0 ? n : 1 << 30);
        if (n > 0 && static_cast<int>(c.size()) > n) c.resize(n);
        for (History& x : c) next.push_back(std::move(x));
      }
      std::stable_sort(next.begin(), next.end(), [](const History& a, const History& b) { return a.score > b.score; });
      if (n > 0 && !per_parent && static_cast<int>(next.size()) > n) next.resize(n);
      const int back = k - window + 1;  // index in lineage of the ancestor at scan k − window
      if (back >= 0) {
        const long anchor = next.front().lineage[back];
        std::erase_if(next, [&](const History& x) { return x.lineage[back] != anchor; });
      }
      alive = std::move(next);
      observe(k, alive);
    }
  }

 private:
  static void by_gain(std::vector<Event>& list) {
    std::stable_sort(list.begin(), list.end(), [](const Event& a, const Event& b) { return a.gain > b.gain; });
  }

  const dabench::TrackingProblem& problem_;
  double pg_;
  int limit_;
  double gate_, log_lambda_;
  long next_id_ = 1;
};

Assigned assigned_of(const HypothesisSnapshot& s) {
  Assigned a;
  for (const auto& t : s.live) a.push_back(t.assigned);
  return a;
}

// The tracker's hypotheses after scan k equal the enumeration's survivors: the same association
// histories, best first, with the same scores relative to the best; their tracks have the same
// LLRs, empty-gate counts and confirmation.
void check_same(int k, const std::vector<HypothesisSnapshot>& tracker, const std::vector<History>& expected) {
  INFO("scan " << k);
  REQUIRE(tracker.size() == expected.size());
  for (std::size_t i = 0; i < tracker.size(); ++i) {
    INFO("hypothesis " << i);
    CHECK(tracker[i].score == Approx(expected[i].score - expected[0].score).margin(1e-7));
    REQUIRE(assigned_of(tracker[i]) == expected[i].assigned());
    for (std::size_t t = 0; t < tracker[i].live.size(); ++t) {
      const auto& a = tracker[i].live[t];
      const EnumTrack& b = expected[i].tracks[t];
      CHECK(a.llr == Approx(b.llr).margin(1e-7));
      CHECK(a.empty_gates == b.empty);
      CHECK((a.confirmed_scan >= 0) == b.confirmed);
    }
    REQUIRE(tracker[i].ended.size() == expected[i].ended.size());
    for (std::size_t t = 0; t < tracker[i].ended.size(); ++t) CHECK(tracker[i].ended[t].assigned == expected[i].ended[t].assigned);
  }
}

std::vector<std::vector<HypothesisSnapshot>> observe(const dabench::MdHmhtOptions& o, const dabench::TrackingProblem& p,
                                                     dabench::TrackSet* tracks = nullptr) {
  std::vector<std::vector<HypothesisSnapshot>> per_scan;
  dabench::TrackSet local;
  dabench::md_hmht::run_observed(o, p, tracks ? *tracks : local,
                                 [&](int, const std::vector<HypothesisSnapshot>& h) { per_scan.push_back(h); });
  return per_scan;
}

// Two targets at one ground range whose bearings cross between scans 1 and 2 (ϑ̇ = ±3e-4 rad/s,
// 4.8 mrad per scan, against σ_ζ = 3 mrad; speeds 0.1 and 0.1005 km/s, so that no two events
// tie): both EE returns fall in both tracks' EE gates. Heads at scan 0 from each target's EE and
// FF returns; then their EE returns only.
std::vector<Vector> crossing_states(int target, int scans) {
  Vector x(4);
  x << 1750.0, target == 0 ? 0.1 : 0.1005, 0.54 + (target == 0 ? -0.0072 : 0.0072), target == 0 ? 3e-4 : -3e-4;
  std::vector<Vector> out;
  const dabench::TrackingProblem p = model_problem(0.75, 125.0, {});
  for (int k = 0; k < scans; ++k, x = p.transition * x) out.push_back(x);
  return out;
}

dabench::TrackingProblem crossing(int scans) {
  const auto a = crossing_states(0, scans), b = crossing_states(1, scans);
  std::vector<Eigen::MatrixXd> s;
  s.push_back(scan_of({{a[0], 0}, {a[0], 3}, {b[0], 0}, {b[0], 3}}));
  for (int k = 1; k < scans; ++k) s.push_back(scan_of({{a[k], 0}, {b[k], 0}}));
  return model_problem(0.75, 125.0, std::move(s));
}

// A target (x at scan 0) with its EE and FF returns at scan 0; at scan 1 two measurements, each
// in the gates of two paths of its track: m0 on the segment from the EE to the FE prediction
// (~33 km further in range, same azimuth), m1 from the EF to the FF prediction, both at d² =
// `d2_first` from the first path's prediction; at scan 2 its returns on EE, FE and FF. Gates
// from pg.
dabench::TrackingProblem two_path_case(double pg, double d2_first) {
  Vector x(4);
  x << 1750.0, 0.1, 0.54, 8.7e-5;
  const dabench::TrackingProblem model = model_problem(0.75, 125.0, {});
  const Vector x1 = model.transition * x, x2 = model.transition * x1;
  dabench::TrackingProblem p = model_problem(0.75, 125.0, {scan_of({{x, 0}, {x, 3}})});
  History root = Enumeration(p, pg).root(false);
  REQUIRE(root.tracks.size() == 1);
  const Gaussian& head = root.tracks[0].x;
  const Gaussian predicted{p.transition * head.mean,
                           p.transition * head.covariance * p.transition.transpose() + p.process_covariance};
  const auto between = [&](int first, int second) -> Eigen::Vector3d {
    const auto a = dabench::unscented_transform(predicted, [&](const Vector& s) { return p.sensor->measure(first, s); });
    const auto b = dabench::unscented_transform(predicted, [&](const Vector& s) { return p.sensor->measure(second, s); });
    const Eigen::VectorXd step = b.mean - a.mean;
    const double d2 = step.dot((a.covariance + p.sensor->noise_covariance(first)).inverse() * step);
    return a.mean + std::sqrt(d2_first / d2) * step;
  };
  Eigen::MatrixXd m(3, 2);
  m << between(0, 2), between(1, 3);
  p.scans.push_back(m);
  p.scans.push_back(scan_of({{x2, 0}, {x2, 2}, {x2, 3}}));
  return p;
}

// A target with its EE, EF and FF returns at scan 0 (head) and from scan 4 on; none at scans 1
// and 3; at scan 2 only a decoy's EE return, the target's state turned by 15 mrad in bearing.
dabench::TrackingProblem decoy_case(int scans) {
  const dabench::TrackingProblem model = model_problem(0.75, 125.0, {});
  Vector x(4);
  x << 1750.0, 0.1, 0.54, 8.7e-5;
  std::vector<Eigen::MatrixXd> s;
  for (int k = 0; k < scans; ++k, x = model.transition * x) {
    Vector decoy = x;
    decoy[2] += 0.015;
    if (k == 1 || k == 3) s.push_back(Eigen::MatrixXd(3, 0));
    else if (k == 2) s.push_back(scan_of({{decoy, 0}}));
    else s.push_back(scan_of({{x, 0}, {x, 1}, {x, 3}}));
  }
  return model_problem(0.75, 125.0, std::move(s));
}

// Table III's target 1 (noiseless, F only) with returns on EE, EF and FF at every scan except
// those in [gap_begin, gap_end).
dabench::TrackingProblem one_target_with_gap(double clutter, int scans, int gap_begin, int gap_end) {
  const dabench::TrackingProblem model = model_problem(0.75, clutter, {});
  Vector x = dabench::OthrScenario::initial_state(0);
  std::vector<Eigen::MatrixXd> s;
  for (int k = 0; k < scans; ++k, x = model.transition * x) {
    s.push_back(k >= gap_begin && k < gap_end ? Eigen::MatrixXd(3, 0) : scan_of({{x, 0}, {x, 1}, {x, 3}}));
  }
  return model_problem(0.75, clutter, std::move(s));
}

dabench::MdHmhtOptions options(int n, int window, int assignment = dabench::MdHmhtOptions::kJoint) {
  dabench::MdHmhtOptions o;
  o.hypotheses = n;
  o.window = window;
  o.assignment = assignment;
  o.alternative_heads = false;  // one head per return group, as Enumeration::root starts them
  return o;
}

}  // namespace

TEST_CASE("md-hmht: the k best hypotheses are the k best association histories of an enumeration", "[md_hmht]") {
  // Crossing targets, three scans: with n = 100 and no window pruning the tracker keeps every
  // history (7 after scan 1, 49 after scan 2, swaps at the crossing included), so for every k
  // its k best are the enumeration's k best, with the same scores relative to the best.
  const dabench::TrackingProblem p = crossing(3);
  Enumeration e(p, 0.971);
  std::vector<std::vector<History>> expected;
  e.run(e.root(false), 0, false, 30, false, [&](int, const std::vector<History>& h) { expected.push_back(h); });
  REQUIRE(expected.back().size() == 49);
  const auto tracker = observe(options(100, 30), p);
  REQUIRE(tracker.size() == 3);
  REQUIRE(tracker[0].size() == 1);
  CHECK(tracker[0][0].live.size() == 2);
  for (int k = 1; k < 3; ++k) check_same(k, tracker[k], expected[k - 1]);
  // Not vacuous: the two tracks' EE gates both hold both returns at every scan.
  const History& best = expected.back().front();
  CHECK(std::count_if(expected.back().begin(), expected.back().end(), [&](const History& h) {
          return h.tracks[0].assigned[1][0] == best.tracks[1].assigned[1][0] && h.tracks[1].assigned[1][0] == best.tracks[0].assigned[1][0];
        }) > 0);
}

TEST_CASE("md-hmht: n best overall (reading A) and per parent (reading B) as the enumeration selects", "[md_hmht]") {
  // Five scans, n = 3: reading A keeps the 3 best children over all parents (3 hypotheses),
  // reading B the 3 best of each parent (3, 9, 27, 81). No window pruning (W = 30 > K).
  const dabench::TrackingProblem p = crossing(5);
  for (bool per_parent : {false, true}) {
    INFO("per_parent " << per_parent);
    Enumeration e(p, 0.971);
    std::vector<std::vector<History>> expected;
    e.run(e.root(false), 3, per_parent, 30, false, [&](int, const std::vector<History>& h) { expected.push_back(h); });
    CHECK(expected.back().size() == (per_parent ? 81u : 3u));
    dabench::MdHmhtOptions o = options(3, 30);
    o.per_parent = per_parent;
    const auto tracker = observe(o, p);
    for (int k = 1; k < 5; ++k) check_same(k, tracker[k], expected[k - 1]);
  }
}

TEST_CASE("md-hmht: path-dependent assignments take the paths in turn", "[md_hmht]") {
  // One track; at scan 1 measurement m0 lies in its EE gate (d² = 13, ln ψ > 0: worth taking)
  // and, closer, in its FE gate; m1 likewise in its EF and FF gates (wide gates, p_g = 0.999, so
  // that both hold them). The joint assignment gives m0 to FE and m1 to FF (larger ψ); the
  // per-path one with one hypothesis gives them to EE and EF, the paths assigned first. Wider
  // beams are checked against the enumeration's path-by-path beam (with n = 3 the beam drops
  // the partial event that leaves EE and EF empty, from which the joint optimum grows), and a
  // beam covering all events gives the joint events.
  const double pg = 0.999;
  const dabench::TrackingProblem p = two_path_case(pg, 13.0);
  Enumeration e(p, pg);
  const History root = e.root(false);
  const auto gates = e.gates(root, 1);
  for (auto [first, second, j] : {std::tuple{0, 2, 0}, {1, 3, 1}}) {
    INFO("paths " << first << ", " << second);
    REQUIRE(gates.arcs[0][first].size() == 1);
    REQUIRE(gates.arcs[0][second].size() == 1);
    REQUIRE(gates.arcs[0][first][0].measurement == j);
    REQUIRE(gates.arcs[0][second][0].measurement == j);
    REQUIRE(gates.arcs[0][first][0].log_psi > 0.0);
    REQUIRE(gates.arcs[0][second][0].log_psi > gates.arcs[0][first][0].log_psi);
  }

  const auto run = [&](int n, int assignment) {
    dabench::MdHmhtOptions o = options(n, 30, assignment);
    o.gate_probability = pg;
    return observe(o, p);
  };
  CHECK(run(1, dabench::MdHmhtOptions::kJoint)[1][0].live[0].assigned[0] == std::vector<int>{-1, -1, 0, 1});
  CHECK(run(1, dabench::MdHmhtOptions::kPerPath)[1][0].live[0].assigned[0] == std::vector<int>{0, 1, -1, -1});

  for (int n : {1, 3, 100}) {
    INFO("beam " << n);
    std::vector<std::vector<History>> expected;
    e.run(root, n, false, 30, true, [&](int, const std::vector<History>& h) { expected.push_back(h); });
    const auto tracker = run(n, dabench::MdHmhtOptions::kPerPath);
    for (int k = 1; k < 3; ++k) check_same(k, tracker[k], expected[k - 1]);
    if (n == 3) CHECK(expected[0][0].tracks[0].assigned[0] != std::vector<int>{-1, -1, 0, 1});
  }
  std::vector<std::vector<History>> joint;
  e.run(root, 0, false, 30, false, [&](int, const std::vector<History>& h) { joint.push_back(h); });
  REQUIRE(joint.back().size() <= 100);
  const auto wide = run(100, dabench::MdHmhtOptions::kPerPath);
  for (int k = 1; k < 3; ++k) check_same(k, wide[k], joint[k - 1]);
}

TEST_CASE("md-hmht: window 3 revises an association two scans later, window 1 cannot", "[md_hmht]") {
  // Head at scan 0; at scan 2 only a decoy return, 15 mrad off in bearing but inside the gate
  // (taking it gains ln ψ over missing it); no return at scans 1 and 3, so after scan 3 the
  // branch that took the decoy still leads. Its track, pulled off, gates none of the target's
  // returns at scan 4, which the branch that missed the decoy gates.
  //  - W = 3: both branches live until scan 4 (they share their ancestor at scan 1); the
  //    returns make the decoy-free branch best: one track, from scan 0 to the end.
  //  - W = 1: the scan-2 decision is final at scan 3 (survivors share their parent): the
  //    decoy's track misses the returns, which start a new track at scan 4; the first one,
  //    never confirmed, is dropped.
  const int K = 8;
  const dabench::TrackingProblem p = decoy_case(K);
  Enumeration e(p, 0.971);
  const std::vector<int> decoy{0, -1, -1, -1}, none{-1, -1, -1, -1};

  dabench::TrackSet w3;
  const auto t3 = observe(options(3, 3), p, &w3);
  std::vector<std::vector<History>> expected;
  e.run(e.root(false), 3, false, 3, false, [&](int, const std::vector<History>& h) { expected.push_back(h); });
  for (int k = 1; k < K; ++k) check_same(k, t3[k], expected[k - 1]);
  CHECK(t3[3][0].live[0].assigned[1] == decoy);  // after scan 3 the decoy branch leads
  CHECK(t3[4][0].live[0].assigned[1] == none);   // after scan 4 it does not
  REQUIRE(w3.tracks.size() == 1);
  CHECK(w3.tracks[0].first_scan == 0);
  CHECK(w3.tracks[0].length() == K);

  // Without pruning (n = 2 per parent, W = 30) the decoy branch lives on. Its track's gates are
  // empty at scans 3, 4 and 5, so it is deleted at scan 5 (never confirmed: dropped), and from
  // scan 6 that branch's hypotheses have no pseudo-target and no miss term, the others four.
  std::vector<std::vector<History>> unpruned;
  e.run(e.root(false), 2, true, 30, false, [&](int, const std::vector<History>& h) { unpruned.push_back(h); });
  CHECK(std::any_of(unpruned.back().begin(), unpruned.back().end(), [](const History& h) { return h.tracks.empty(); }));
  dabench::MdHmhtOptions b = options(2, 30);
  b.per_parent = true;
  const auto tb = observe(b, p);
  for (int k = 1; k < K; ++k) check_same(k, tb[k], unpruned[k - 1]);

  dabench::TrackSet w1;
  const auto t1 = observe(options(3, 1), p, &w1);
  CHECK(t1[3].size() == 1);  // only the decoy branch's child (the scan had nothing to assign)
  CHECK(t1[3][0].live[0].assigned[1] == decoy);
  for (const HypothesisSnapshot& h : t1[4]) {
    REQUIRE(!h.live.empty());
    CHECK(h.live[0].assigned[1] == decoy);
    CHECK(h.live[0].assigned[2] == none);
  }
  REQUIRE(w1.tracks.size() == 1);
  CHECK(w1.tracks[0].first_scan == 4);
  CHECK(w1.tracks[0].id != w3.tracks[0].id);
}

TEST_CASE("md-hmht: report_from = confirmation starts a track at the scan its LLR reaches confirm_llr",
          "[md_hmht]") {
  // One target, returns on EE, EF and FF at every scan, no clutter: the best history takes them
  // all, and a single track's LLR is the history's score (heads start at 0). The enumeration's
  // best score after each scan gives the scan it first reaches the threshold.
  const dabench::TrackingProblem p = one_target_with_gap(125.0, 12, 0, 0);
  for (double threshold : {6.9, 40.0, 90.0}) {
    INFO("confirm_llr " << threshold);
    Enumeration e(p, 0.971);
    int confirmation = -1;
    e.run(e.root(false), 1, false, 30, false, [&](int k, const std::vector<History>& h) {
      if (confirmation < 0 && h.front().score >= threshold) confirmation = k;
    });
    REQUIRE(confirmation >= 1);
    const std::string common = fmt::format("md-hmht:alternative_heads=0,confirm_llr={}", threshold);
    const dabench::TrackSet head = dabench::test::solved_tracks(common, p);
    const dabench::TrackSet confirmed = dabench::test::solved_tracks(common + ",report_from=confirmation", p);
    REQUIRE(head.tracks.size() == 1);
    REQUIRE(confirmed.tracks.size() == 1);
    CHECK(head.tracks[0].first_scan == 0);
    CHECK(confirmed.tracks[0].first_scan == confirmation);
    CHECK(confirmed.tracks[0].length() == 12 - confirmation);
    CHECK(confirmed.tracks[0].id == head.tracks[0].id);
    CHECK(confirmed.tracks[0].states == head.tracks[0].states.rightCols(12 - confirmation));
    CHECK(confirmed.tracks[0].covariance_diagonals == head.tracks[0].covariance_diagonals.rightCols(12 - confirmation));
  }
}

TEST_CASE("md-hmht: literal = 1 is the paper-literal set; the new options are checked", "[md_hmht]") {
  dabench::MdHmhtOptions o;
  o.literal = true;
  o.hypotheses = 4;
  const dabench::MdHmhtOptions r = o.resolved();
  CHECK(!r.alternative_heads);
  CHECK(r.report_from == dabench::MdHmhtOptions::kFromConfirmation);
  CHECK(r.assignment == dabench::MdHmhtOptions::kPerPath);
  CHECK(r.hypotheses == 4);
  const dabench::MdHmhtOptions d = dabench::MdHmhtOptions{}.resolved();
  CHECK(d.alternative_heads);
  CHECK(d.report_from == dabench::MdHmhtOptions::kFromHead);
  CHECK(d.assignment == dabench::MdHmhtOptions::kJoint);

  // The tracker runs the resolved set: literal = 1 with contrary keys equals the set spelled out.
  dabench::OthrOptions scenario;
  scenario.pd = 0.4;
  dabench::TrackingScenarioSample sample;
  dabench::RandomStream rng(2019, 0, 3);
  dabench::OthrScenario(scenario).generate(rng, sample);
  const auto a = dabench::test::solved_tracks("md-hmht:literal=1,alternative_heads=1,report_from=head,assignment=joint", sample.problem);
  const auto b = dabench::test::solved_tracks("md-hmht:alternative_heads=0,report_from=confirmation,assignment=per_path", sample.problem);
  REQUIRE(a.tracks.size() == b.tracks.size());
  REQUIRE(!a.tracks.empty());
  for (std::size_t t = 0; t < a.tracks.size(); ++t) {
    CHECK(a.tracks[t].first_scan == b.tracks[t].first_scan);
    CHECK(a.tracks[t].states == b.tracks[t].states);
  }

  CHECK_THROWS_WITH(dabench::make_tracker("md-hmht:report_from=birth"), Catch::Contains("report_from"));
  CHECK_THROWS_WITH(dabench::make_tracker("md-hmht:assignment=sequential"), Catch::Contains("assignment"));
  dabench::MdHmhtOptions bad;
  bad.report_from = 2;
  CHECK_THAT(bad.validate(), Catch::Contains("report_from"));
  bad = {};
  bad.assignment = -1;
  CHECK_THAT(bad.validate(), Catch::Contains("assignment"));
  dabench::TrackSet tracks;
  CHECK_THROWS_WITH(dabench::md_hmht::run_observed(bad, sample.problem, tracks, nullptr), Catch::Contains("assignment"));
}

TEST_CASE("md-hmht: a track survives limit - 1 empty-gate scans as the same track and is deleted after limit",
          "[md_hmht]") {
  // The paper's rule (S:2469-2471): deleted after 3 successive scans with no measurement in its
  // gates at N_c = 125, 5 at N_c = 400. The returns stop at scan 10 for `gap` scans and come back
  // in the track's gates. Below the limit the same track continues (one track, scans 0-19: the
  // gap is bridged by predictions); at the limit it was deleted at scan 9 + gap, ends at its
  // last return (scan 9) and the returns start a second track. A limit one too low or too high
  // changes the count at one of the two gaps.
  for (auto [clutter, limit] : {std::pair{125.0, 3}, {400.0, 5}}) {
    for (int gap : {limit - 1, limit}) {
      INFO("N_c " << clutter << ", gap " << gap);
      const dabench::TrackSet tracks = dabench::test::solved_tracks("md-hmht", one_target_with_gap(clutter, 20, 10, 10 + gap));
      if (gap < limit) {
        REQUIRE(tracks.tracks.size() == 1);
        CHECK(tracks.tracks[0].first_scan == 0);
        CHECK(tracks.tracks[0].length() == 20);
      } else {
        REQUIRE(tracks.tracks.size() == 2);
        CHECK(tracks.tracks[0].first_scan == 0);
        CHECK(tracks.tracks[0].length() == 10);
        CHECK(tracks.tracks[1].first_scan == 10 + gap);
        CHECK(tracks.tracks[1].length() == 10 - gap);
        CHECK(tracks.tracks[1].id != tracks.tracks[0].id);
      }
    }
  }
  // deletion_misses overrides the paper's limit.
  CHECK(dabench::test::solved_tracks("md-hmht:deletion_misses=2", one_target_with_gap(125.0, 20, 10, 12)).tracks.size() == 2);
  CHECK(dabench::test::solved_tracks("md-hmht:deletion_misses=6", one_target_with_gap(400.0, 20, 10, 15)).tracks.size() == 1);
}

}  // namespace DABENCH_TEST_FILE

// `dabench run` for tracking experiments (harness/run/kinds/tracking_execution.hpp), through the C++ API
// (run_experiment): the trackers and one scenario here are test-only and registered in the
// test binary alone, so no test depends on jdt-vb or mptf existing.
//  - a constructed case (scenario test-static-target: one still target, one measurement per
//    scan plus one clutter point; test-fixed-track: constant tracks) whose trials.csv metrics,
//    tracks.csv and measurements.csv rows are computed by hand;
//  - statuses: a tracker that throws → failed:<what>, one that skips → skipped:<reason>, one
//    whose tracks do not fit the run → failed:<why>; the other trackers' rows are unaffected;
//  - a draw without targets; meta.json's metric options; summary.csv;
//  - on the othr scenario (few scans): identical files for 1 and 2 threads (tet_s aside), and
//    --resume after a hard kill (files cut anywhere, item files at least as far as trials.csv)
//    ends with the files of an uninterrupted run;
//  - unknown trackers and references are one-line errors, also from the command line.
#include <catch2/catch.hpp>

#include <cmath>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

#include "harness/run/runner.hpp"
#include "harness/tracking/registry.hpp"
#include "tests/support/cli_runner.hpp"
#include "tests/support/run_files.hpp"

namespace DABENCH_TEST_FILE {

using namespace dabench::test::cli;
using dabench::SolveReport;
using dabench::Track;
using dabench::TrackingProblem;
using dabench::TrackSet;

namespace {

// ---- test-only scenario -----------------------------------------------------------------

// One still target at [target_g, 0, target_theta, 0], alive from scan first_alive to the last
// (none if targets = 0). Each scan holds its exact measurement [target_g, 0, target_theta] through path
// τ = 2 (index 1) when it is alive, then one clutter point [1600, 0.1, 0.45].
struct StaticTargetOptions {
  int scans = 8;
  int first_alive = 1;
  int targets = 1;
  double target_g = 1800.0;
  double target_theta = 0.5;

  void bind(dabench::ParamList& p) {
    p.add("scans", scans, "scans K");
    p.add("first_alive", first_alive, "first scan of the target");
    p.add("targets", targets, "0 or 1");
    p.add("target_g", target_g, "ground range, km");
    p.add("target_theta", target_theta, "bearing, rad");
  }
  std::string validate() const { return scans >= 1 && (targets == 0 || targets == 1) ? "" : "bad test scenario"; }
};

class StaticTargetScenario final : public dabench::TrackingScenario {
 public:
  using Options = StaticTargetOptions;
  static constexpr std::string_view kName = "test-static-target";
  static constexpr std::string_view kSummary = "test only: one still target, one clutter point per scan";
  explicit StaticTargetScenario(const Options& options) : o_(options) {}

  void generate(dabench::RandomStream&, dabench::TrackingScenarioSample& sample) const override {
    const double nan = std::nan("");
    sample.problem.scans.assign(o_.scans, Eigen::MatrixXd());
    sample.truth.targets.clear();
    sample.truth.origin.assign(o_.scans, {});
    if (o_.targets == 1) sample.truth.targets.push_back({Eigen::MatrixXd::Constant(4, o_.scans, nan), std::vector<bool>(o_.scans, false)});
    for (int k = 0; k < o_.scans; ++k) {
      std::vector<Eigen::Vector3d> columns;
      if (o_.targets == 1 && k >= o_.first_alive) {
        sample.truth.targets[0].states.col(k) << o_.target_g, 0.0, o_.target_theta, 0.0;
        sample.truth.targets[0].alive[k] = true;
        columns.push_back({o_.target_g, 0.0, o_.target_theta});
        sample.truth.origin[k].push_back({0, 1});
      }
      columns.push_back({1600.0, 0.1, 0.45});
      sample.truth.origin[k].push_back({});
      sample.problem.scans[k].resize(3, static_cast<Eigen::Index>(columns.size()));
      for (std::size_t j = 0; j < columns.size(); ++j) sample.problem.scans[k].col(static_cast<Eigen::Index>(j)) = columns[j];
    }
  }

 private:
  Options o_;
};
DABENCH_REGISTER_TRACKING_SCENARIO(StaticTargetScenario);

// ---- test-only trackers -----------------------------------------------------------------

// `copies` constant tracks [g, 0.01, theta, 1e-5] with covariance diagonal [1, 2, 3, 4] over
// scans first_scan .. first_scan + length − 1 (ids id, id + 1, ...); reports 3 iterations, not
// converged, free energy −12.5; records the set twice in an iteration history when asked.
struct FixedTrackOptions {
  double g = 1803.0;
  double theta = 0.5005;
  int first_scan = 3;
  int length = 5;
  int copies = 1;
  int id = 7;
  bool confirmed = true;

  void bind(dabench::ParamList& p) {
    p.add("g", g, "ground range, km");
    p.add("theta", theta, "bearing, rad");
    p.add("first_scan", first_scan, "first scan");
    p.add("length", length, "scans");
    p.add("copies", copies, "identical tracks");
    p.add("id", id, "id of the first track");
    p.add("confirmed", confirmed, "confirmed tracks");
  }
  std::string validate() const { return ""; }
};

class FixedTrackTracker final : public dabench::Tracker {
 public:
  using Options = FixedTrackOptions;
  static constexpr std::string_view kName = "test-fixed-track";
  static constexpr std::string_view kSummary = "test only: constant tracks";
  explicit FixedTrackTracker(const Options& options) : o_(options) {}

  void run(const TrackingProblem&, TrackSet& tracks, SolveReport& report) override {
    tracks.tracks.clear();
    for (int c = 0; c < o_.copies; ++c) {
      Track track;
      track.id = o_.id + c;
      track.first_scan = o_.first_scan;
      track.confirmed = o_.confirmed;
      track.states.resize(4, o_.length);
      track.covariance_diagonals.resize(4, o_.length);
      for (int s = 0; s < o_.length; ++s) {
        track.states.col(s) << o_.g, 0.01, o_.theta, 1e-5;
        track.covariance_diagonals.col(s) << 1.0, 2.0, 3.0, 4.0;
      }
      tracks.tracks.push_back(track);
    }
    report.iterations = 3;
    report.converged = false;
    report.free_energy = -12.5;
    if (iteration_history() != nullptr) iteration_history()->assign(2, tracks);
  }

 private:
  Options o_;
};
DABENCH_REGISTER_TRACKING_TRACKER(FixedTrackTracker);

// mode 0: throws; 1: skips; 2: a track with 2 state rows; 3: a track past the last scan.
struct BadTrackerOptions {
  int mode = 0;
  void bind(dabench::ParamList& p) { p.add("mode", mode, "how to misbehave"); }
  std::string validate() const { return ""; }
};

class BadTracker final : public dabench::Tracker {
 public:
  using Options = BadTrackerOptions;
  static constexpr std::string_view kName = "test-bad-tracker";
  static constexpr std::string_view kSummary = "test only: throws, skips or returns misshapen tracks";
  explicit BadTracker(const Options& options) : o_(options) {}

  void run(const TrackingProblem& problem, TrackSet& tracks, SolveReport& report) override {
    if (o_.mode == 0) throw std::runtime_error("boom, with a comma\nand a newline");
    if (o_.mode == 1) {
      report.skipped = "not_today\nor tomorrow";
      return;
    }
    Track track;
    track.id = 4;
    track.first_scan = o_.mode == 2 ? 0 : problem.scan_count() - 1;
    const int rows = o_.mode == 2 ? 2 : 4;
    track.states = Eigen::MatrixXd::Zero(rows, 2);
    track.covariance_diagonals = Eigen::MatrixXd::Zero(rows, 2);
    tracks.tracks.assign(1, track);
  }

 private:
  Options o_;
};
DABENCH_REGISTER_TRACKING_TRACKER(BadTracker);

// One confirmed track through the first measurement [r, ṙ, ζ] of every scan (the previous
// state for an empty scan), state [r, ṙ, ζ, 0]; iterations = measurements in the run,
// converged = that count is even, free energy = −Σ r / 1000. Its output depends on every draw.
struct FirstMeasurementOptions {
  void bind(dabench::ParamList&) {}
  std::string validate() const { return ""; }
};

class FirstMeasurementTracker final : public dabench::Tracker {
 public:
  using Options = FirstMeasurementOptions;
  static constexpr std::string_view kName = "test-first-measurement";
  static constexpr std::string_view kSummary = "test only: one track through each scan's first measurement";
  explicit FirstMeasurementTracker(const Options&) {}

  void run(const TrackingProblem& problem, TrackSet& tracks, SolveReport& report) override {
    Track track;
    track.id = 1;
    track.confirmed = true;
    track.states.resize(4, problem.scan_count());
    track.covariance_diagonals = Eigen::MatrixXd::Constant(4, problem.scan_count(), 25.0);
    Eigen::Vector4d state(1750.0, 0.0, 0.5, 0.0);
    int measurements = 0;
    double free_energy = 0.0;
    for (int k = 0; k < problem.scan_count(); ++k) {
      const Eigen::MatrixXd& scan = problem.scans[k];
      measurements += static_cast<int>(scan.cols());
      if (scan.cols() > 0) state << scan(0, 0), scan(1, 0), scan(2, 0), 0.0;
      track.states.col(k) = state;
      free_energy -= state(0) / 1000.0;
    }
    tracks.tracks.assign(1, track);
    report.iterations = measurements;
    report.converged = measurements % 2 == 0;
    report.free_energy = free_energy;
  }
};
DABENCH_REGISTER_TRACKING_TRACKER(FirstMeasurementTracker);

// ---- helpers ------------------------------------------------------------------------------

// Rows of `table` whose column `key` equals `value`.
std::vector<std::size_t> rows_where(const CsvTable& table, const std::string& key, const std::string& value) {
  std::vector<std::size_t> rows;
  for (std::size_t r = 0; r < table.rows.size(); ++r) {
    if (table.at(r, key) == value) rows.push_back(r);
  }
  return rows;
}

// Ground-plane distance between (g1, θ1) and (g2, θ2), law of cosines.
double ground_distance(double g1, double theta1, double g2, double theta2) {
  return std::sqrt(g1 * g1 + g2 * g2 - 2.0 * g1 * g2 * std::cos(theta1 - theta2));
}

const char* const kConstructed =
    "scenario = test-static-target\n"
    "trials = 2\n"
    "seed = 9\n"
    "algorithm = test-fixed-track\n"
    "algorithm = test-fixed-track:g=1900,first_scan=0,length=8\n"
    "algorithm = test-fixed-track:copies=2\n"
    "algorithm = test-fixed-track:confirmed=false\n"
    "algorithm = test-bad-tracker:mode=0\n"
    "algorithm = test-bad-tracker:mode=1\n"
    "algorithm = test-bad-tracker:mode=2\n"
    "algorithm = test-bad-tracker:mode=3\n";

const std::vector<std::string> kMetricColumns = {
    "nvt",          "tpd",          "nft",      "false_tracks", "ghost_tracks", "broken_targets", "ttl_scans",
    "aee_range_km", "aee_bearing_mrad", "mospa_km", "tet_s",        "iterations",   "converged",      "free_energy"};

// OTHR, 10 scans, light clutter, a 2×2 grid as in Table IV, 6 trials: 24 items, 3 blocks.
const char* const kOthr =
    "scenario = othr\n"
    "trials = 6\n"
    "seed = 5\n"
    "algorithm = test-first-measurement\n"
    "algorithm = test-fixed-track:g=1750,theta=0.48,first_scan=0,length=10\n"
    "[scenario]\n"
    "scans = 10\n"
    "[sweep]\n"
    "pd = 0.75, 0.4\n"
    "clutter = 5, 20\n";
constexpr int kOthrTrials = 6;

// Where item `item`'s rows start in a file of this test's runs.
std::size_t item_offset(const std::string& text, long long item) { return offset_of_item(text, item, kOthrTrials); }

}  // namespace

TEST_CASE("run tracking: trials.csv metrics of a constructed case, by hand", "[run][tracking]") {
  TempDir dir;
  dir.write("c.ini", kConstructed);
  const dabench::RunOutcome outcome = run_in(dir, "c.ini", "C", 2);
  CHECK(outcome.items_total == 2);
  CHECK_FALSE(outcome.interrupted);
  CHECK(outcome.item_files == std::vector<std::string>{"tracks.csv", "measurements.csv"});
  const CsvTable trials = parse_csv(dir.read("C/trials.csv"));
  const std::vector<std::string> leading = {"point", "scans", "first_alive", "targets", "target_g", "target_theta",
                                            "trial", "seed",  "algorithm",   "status"};
  std::vector<std::string> header = leading;
  header.insert(header.end(), kMetricColumns.begin(), kMetricColumns.end());
  CHECK(trials.header == header);
  REQUIRE(trials.rows.size() == 2 * 8);
  CHECK(trials.at(1, "algorithm") == "test-fixed-track:g=1900,first_scan=0,length=8");
  CHECK(split_lines(dir.read("C/trials.csv"))[2].find("\"test-fixed-track:g=1900,first_scan=0,length=8\"") !=
        std::string::npos);

  // Target at (1800, 0.5) alive at scans 1..7 of 8; OSPA c = 50 km, p = 2; gate 20 km.
  const double d = ground_distance(1800.0, 0.5, 1803.0, 0.5005);
  REQUIRE(d < 20.0);
  for (int trial = 0; trial < 2; ++trial) {
    const std::size_t base = static_cast<std::size_t>(trial) * 8;
    INFO("trial " << trial);
    for (std::size_t a = 0; a < 8; ++a) CHECK(trials.at(base + a, "trial") == std::to_string(trial));
    // Near track at scans 3..7: valid, follows 5 of the target's 7 scans, found 2 scans late.
    std::size_t r = base;
    CHECK(trials.at(r, "status") == "ok");
    CHECK(number(trials, r, "nvt") == 1.0);
    CHECK(number(trials, r, "tpd") == Approx(5.0 / 7.0).epsilon(1e-12));
    CHECK(number(trials, r, "nft") == 0.0);
    CHECK(number(trials, r, "broken_targets") == 0.0);
    CHECK(number(trials, r, "ttl_scans") == 2.0);
    CHECK(number(trials, r, "aee_range_km") == Approx(3.0).epsilon(1e-12));
    CHECK(number(trials, r, "aee_bearing_mrad") == Approx(0.5).epsilon(1e-9));
    CHECK(number(trials, r, "mospa_km") == Approx((0.0 + 2 * 50.0 + 5 * d) / 8.0).epsilon(1e-9));
    CHECK(number(trials, r, "tet_s") >= 0.0);
    CHECK(number(trials, r, "tet_s") < 1.0);
    CHECK(trials.at(r, "iterations") == "3");
    CHECK(trials.at(r, "converged") == "0");
    CHECK(trials.at(r, "free_energy") == "-12.5");
    // Far track (100 km off) at every scan: a false track; nothing followed.
    r = base + 1;
    CHECK(trials.at(r, "status") == "ok");
    CHECK(number(trials, r, "nvt") == 0.0);
    CHECK(number(trials, r, "tpd") == 0.0);
    CHECK(number(trials, r, "nft") == 1.0);
    CHECK(number(trials, r, "false_tracks") == 1.0);
    CHECK(trials.at(r, "ttl_scans").empty());
    CHECK(trials.at(r, "aee_range_km").empty());
    CHECK(trials.at(r, "aee_bearing_mrad").empty());
    CHECK(number(trials, r, "mospa_km") == Approx(50.0).epsilon(1e-12));
    // Two copies of the near track: one valid, one ghost; OSPA with one point and two tracks.
    r = base + 2;
    CHECK(number(trials, r, "nvt") == 1.0);
    CHECK(number(trials, r, "nft") == 1.0);
    CHECK(number(trials, r, "ghost_tracks") == 1.0);
    CHECK(number(trials, r, "false_tracks") == 0.0);
    CHECK(number(trials, r, "mospa_km") ==
          Approx((2 * 50.0 + 5 * std::sqrt((d * d + 50.0 * 50.0) / 2.0)) / 8.0).epsilon(1e-9));
    // An unconfirmed track is not scored: the target is missed at its 7 scans.
    r = base + 3;
    CHECK(number(trials, r, "nvt") == 0.0);
    CHECK(number(trials, r, "nft") == 0.0);
    CHECK(number(trials, r, "tpd") == 0.0);
    CHECK(number(trials, r, "mospa_km") == Approx(7 * 50.0 / 8.0).epsilon(1e-12));
    // Misbehaving trackers: their own row only, metrics and diagnostics empty, time kept.
    CHECK(trials.at(base + 4, "status") == "failed:boom, with a comma and a newline");
    CHECK(trials.at(base + 5, "status") == "skipped:not_today or tomorrow");
    CHECK(trials.at(base + 6, "status") == "failed:track 4 has 2 state rows, expected at least 4");
    CHECK(trials.at(base + 7, "status") == "failed:track 4 covers scans 7..8, outside 0..7");
    for (std::size_t bad = base + 4; bad < base + 8; ++bad) {
      for (const auto& column : kMetricColumns) {
        if (column == "tet_s") CHECK(number(trials, bad, column) >= 0.0);
        else CHECK(trials.at(bad, column).empty());
      }
    }
  }

  const CsvTable summary = parse_csv(dir.read("C/summary.csv"));
  REQUIRE(summary.rows.size() == 8);
  CHECK(summary.at(0, "trials") == "2");
  CHECK(summary.at(0, "ok") == "2");
  CHECK(number(summary, 0, "tpd_mean") == Approx(5.0 / 7.0).epsilon(1e-12));
  CHECK(summary.at(1, "ttl_scans_count") == "0");
  CHECK(summary.at(4, "failed") == "2");
  CHECK(summary.at(5, "skipped") == "2");
  CHECK(summary.at(5, "nvt_count") == "0");

  const std::string meta = dir.read("C/meta.json");
  CHECK(contains(meta, "\"tracking_metrics\": {"));
  CHECK(contains(meta, "\"gate_km\": 20"));
  CHECK(contains(meta, "\"ospa_cutoff_km\": 50"));
  CHECK(contains(meta, "\"min_track_length\": 5"));
}

TEST_CASE("run tracking: [metrics] sets the follow gate and the OSPA cut-off", "[run][tracking]") {
  // The constructed case with a 2 km gate and c = 100 km: the near track (3.1 km off) follows
  // nothing and is false; OSPA charges 100 km where it charged 50.
  TempDir dir;
  dir.write("c.ini", std::string(kConstructed) + "[metrics]\ngate_km = 2\nospa_cutoff_km = 100\n");
  run_in(dir, "c.ini", "C", 1);
  const CsvTable trials = parse_csv(dir.read("C/trials.csv"));
  const double d = ground_distance(1800.0, 0.5, 1803.0, 0.5005);
  REQUIRE(d > 2.0);
  REQUIRE(d < 20.0);
  CHECK(number(trials, 0, "nvt") == 0.0);
  CHECK(number(trials, 0, "nft") == 1.0);
  CHECK(number(trials, 0, "false_tracks") == 1.0);
  CHECK(number(trials, 0, "tpd") == 0.0);
  CHECK(trials.at(0, "aee_range_km").empty());
  CHECK(number(trials, 0, "mospa_km") == Approx((0.0 + 2 * 100.0 + 5 * d) / 8.0).epsilon(1e-9));
  const std::string meta = dir.read("C/meta.json");
  CHECK(contains(meta, "\"gate_km\": 2,"));
  CHECK(contains(meta, "\"ospa_cutoff_km\": 100,"));
  CHECK(contains(meta, "\"min_track_length\": 5"));
}

TEST_CASE("run tracking: tracks.csv and measurements.csv of a constructed case", "[run][tracking]") {
  TempDir dir;
  dir.write("c.ini", kConstructed);
  run_in(dir, "c.ini", "C", 1);
  const CsvTable tracks = parse_csv(dir.read("C/tracks.csv"));
  CHECK(tracks.header == std::vector<std::string>{"point", "scans", "first_alive", "targets", "target_g",
                                                  "target_theta", "trial", "algorithm", "track", "confirmed", "scan",
                                                  "g", "g_dot", "theta", "theta_dot", "var_g", "var_g_dot",
                                                  "var_theta", "var_theta_dot"});
  // Per trial: truth 7 rows, near 5, far 8, two copies 10, unconfirmed 5; failed trackers none.
  REQUIRE(tracks.rows.size() == 2 * 35);
  for (int trial = 0; trial < 2; ++trial) {
    const std::size_t base = static_cast<std::size_t>(trial) * 35;
    for (std::size_t r = base; r < base + 35; ++r) CHECK(tracks.at(r, "trial") == std::to_string(trial));
    for (std::size_t r = base; r < base + 7; ++r) {
      CHECK(tracks.at(r, "algorithm") == "truth");
      CHECK(tracks.at(r, "track") == "1");
      CHECK(tracks.at(r, "confirmed") == "1");
      CHECK(tracks.at(r, "scan") == std::to_string(r - base + 1));
      CHECK(tracks.at(r, "g") == "1800");
      CHECK(tracks.at(r, "g_dot") == "0");
      CHECK(tracks.at(r, "theta") == "0.5");
      CHECK(tracks.at(r, "var_g").empty());
      CHECK(tracks.at(r, "var_theta_dot").empty());
    }
    const std::size_t near = base + 7;
    for (std::size_t s = 0; s < 5; ++s) {
      CHECK(tracks.at(near + s, "algorithm") == "test-fixed-track");
      CHECK(tracks.at(near + s, "track") == "7");
      CHECK(tracks.at(near + s, "scan") == std::to_string(3 + s));
      CHECK(tracks.at(near + s, "g") == "1803");
      CHECK(tracks.at(near + s, "g_dot") == "0.01");
      CHECK(tracks.at(near + s, "theta") == "0.5005");
      CHECK(tracks.at(near + s, "theta_dot") == "1e-05");
      CHECK(tracks.at(near + s, "var_g") == "1");
      CHECK(tracks.at(near + s, "var_g_dot") == "2");
      CHECK(tracks.at(near + s, "var_theta") == "3");
      CHECK(tracks.at(near + s, "var_theta_dot") == "4");
    }
    CHECK(tracks.at(base + 12, "algorithm") == "test-fixed-track:g=1900,first_scan=0,length=8");
    CHECK(tracks.at(base + 12, "scan") == "0");
    CHECK(tracks.at(base + 20, "track") == "7");
    CHECK(tracks.at(base + 25, "track") == "8");
    CHECK(tracks.at(base + 29, "scan") == "7");
    CHECK(tracks.at(base + 30, "algorithm") == "test-fixed-track:confirmed=false");
    CHECK(tracks.at(base + 30, "confirmed") == "0");
  }

  // Trial 0 only: scan 0 holds the clutter point, scans 1..7 the target (path τ = 2) then it.
  const CsvTable measurements = parse_csv(dir.read("C/measurements.csv"));
  CHECK(measurements.header == std::vector<std::string>{"point", "scans", "first_alive", "targets", "target_g", "target_theta", "trial",
                                                        "scan", "r", "r_dot", "azimuth", "origin_target", "origin_path"});
  REQUIRE(measurements.rows.size() == 15);
  CHECK(measurements.rows[0] == std::vector<std::string>{"0", "8", "1", "1", "1800", "0.5", "0", "0", "1600", "0.1",
                                                         "0.45", "-1", "-1"});
  CHECK(measurements.rows[1] == std::vector<std::string>{"0", "8", "1", "1", "1800", "0.5", "0", "1", "1800", "0",
                                                         "0.5", "1", "2"});
  CHECK(measurements.at(2, "origin_target") == "-1");
  CHECK(measurements.at(14, "scan") == "7");
  for (std::size_t r = 0; r < measurements.rows.size(); ++r) CHECK(measurements.at(r, "trial") == "0");
}

TEST_CASE("run tracking: a draw without targets is scored against nothing", "[run][tracking]") {
  TempDir dir;
  dir.write("n.ini",
            "scenario = test-static-target\ntrials = 1\nalgorithm = test-fixed-track:g=1900,first_scan=0,length=8\n"
            "algorithm = test-fixed-track:copies=0\n[scenario]\ntargets = 0\n");
  run_in(dir, "n.ini", "N", 1);
  const CsvTable trials = parse_csv(dir.read("N/trials.csv"));
  REQUIRE(trials.rows.size() == 2);
  CHECK(trials.at(0, "status") == "ok");
  CHECK(number(trials, 0, "nvt") == 0.0);
  CHECK(trials.at(0, "tpd").empty());
  CHECK(trials.at(0, "ttl_scans").empty());
  CHECK(number(trials, 0, "nft") == 1.0);
  CHECK(number(trials, 0, "mospa_km") == Approx(50.0).epsilon(1e-12));
  CHECK(number(trials, 1, "nft") == 0.0);
  CHECK(number(trials, 1, "mospa_km") == 0.0);
  const CsvTable tracks = parse_csv(dir.read("N/tracks.csv"));
  CHECK(rows_where(tracks, "algorithm", "truth").empty());
  CHECK(tracks.rows.size() == 8);
  CHECK(parse_csv(dir.read("N/measurements.csv")).rows.size() == 8);  // the clutter point per scan
}

TEST_CASE("run tracking: a tracker may record its per-iteration track sets", "[run][tracking]") {
  auto tracker = dabench::make_tracker("test-fixed-track:copies=2");
  TrackingProblem problem;
  problem.scans.resize(8);
  TrackSet tracks;
  SolveReport report;
  tracker->run(problem, tracks, report);  // no history set: nothing recorded, nothing breaks
  std::vector<TrackSet> history;
  tracker->record_iterations(&history);
  tracker->run(problem, tracks, report);
  REQUIRE(history.size() == 2);
  CHECK(history[1].tracks.size() == 2);
  CHECK(history[1].tracks[1].id == 8);
}

TEST_CASE("run tracking: othr, 1 and 2 threads give identical files", "[run][tracking][determinism]") {
  TempDir dir;
  dir.write("o.ini", kOthr);
  run_in(dir, "o.ini", "one", 1);
  run_in(dir, "o.ini", "two", 2);
  const CsvTable trials = without_timing(dir, "one/trials.csv");
  REQUIRE(trials.rows.size() == 4 * kOthrTrials * 2);
  CHECK(trials.header[1] == "pd");
  CHECK(trials.header[2] == "clutter");
  CHECK(trials.at(0, "pd") == "0.75");
  CHECK(trials.at(0, "clutter") == "5");
  CHECK(trials.at(3 * kOthrTrials * 2, "pd") == "0.4");
  CHECK(trials.at(3 * kOthrTrials * 2, "clutter") == "20");
  for (std::size_t r = 0; r < trials.rows.size(); ++r) CHECK(trials.at(r, "status") == "ok");
  check_same(trials, without_timing(dir, "two/trials.csv"));
  CHECK(dir.read("one/tracks.csv") == dir.read("two/tracks.csv"));
  CHECK(dir.read("one/measurements.csv") == dir.read("two/measurements.csv"));
  check_same(without_timing(dir, "one/summary.csv"), without_timing(dir, "two/summary.csv"));
  // Truth rows: targets 1, 2 alive at scans 0..9, targets 3, 4 at 9 (lifetimes cut at K = 10).
  const CsvTable tracks = parse_csv(dir.read("one/tracks.csv"));
  const auto truth = rows_where(tracks, "algorithm", "truth");
  CHECK(truth.size() == 4 * kOthrTrials * (10 + 10 + 1 + 1));
  // measurements.csv: trial 0 of each of the 4 points, origins within range.
  const CsvTable measurements = parse_csv(dir.read("one/measurements.csv"));
  CHECK(rows_where(measurements, "trial", "0").size() == measurements.rows.size());
  CHECK(rows_where(measurements, "point", "3").size() > rows_where(measurements, "point", "0").size());
  for (std::size_t r = 0; r < measurements.rows.size(); ++r) {
    const int target = std::stoi(measurements.at(r, "origin_target")), path = std::stoi(measurements.at(r, "origin_path"));
    CHECK(((target == -1 && path == -1) || (target >= 1 && target <= 4 && path >= 1 && path <= 4)));
  }
  // The draw reaches the tracker: another seed changes its rows.
  dabench::RunOptions other;
  other.experiment_path = (dir.work() / "o.ini").string();
  other.output = (dir.work() / "other").string();
  other.seed = 6;
  dabench::run_experiment(other);
  CHECK(dir.read("one/tracks.csv") != dir.read("other/tracks.csv"));
}

TEST_CASE("run tracking: othr, --resume after a hard kill finishes identically", "[run][tracking][resume]") {
  TempDir dir;
  dir.write("o.ini", kOthr);
  run_in(dir, "o.ini", "A", 2);
  const std::string trials = dir.read("A/trials.csv");
  const std::string tracks = dir.read("A/tracks.csv");
  const std::string measurements = dir.read("A/measurements.csv");
  const std::string meta = dir.read("A/meta.json");
  const CsvTable reference = without_timing(dir, "A/trials.csv");
  const CsvTable summary = without_timing(dir, "A/summary.csv");
  const std::size_t trials_header = trials.find('\n') + 1, tracks_header = tracks.find('\n') + 1;
  const std::size_t measurements_header = measurements.find('\n') + 1;
  // (what, trials.csv, tracks.csv, measurements.csv lengths); item files reach at least as far.
  const std::vector<std::tuple<std::string, std::size_t, std::size_t, std::size_t>> cuts = {
      {"all at the same item boundary", item_offset(trials, 5), item_offset(tracks, 5),
       item_offset(measurements, 5)},
      {"trials mid-line, item files further mid-line", item_offset(trials, 7) + 9, item_offset(tracks, 10) + 11,
       item_offset(measurements, 13) + 7},
      {"headers only", trials_header, tracks_header, measurements_header},
      {"trials header only, item files with rows", trials_header, item_offset(tracks, 2),
       item_offset(measurements, 7)},
      {"trials cut, item files complete", item_offset(trials, 13) + 4, tracks.size(), measurements.size()},
      {"second point, block boundary", item_offset(trials, 16), item_offset(tracks, 16) + 3,
       item_offset(measurements, 16)},
  };
  for (const auto& [what, trials_length, tracks_length, measurements_length] : cuts) {
    DYNAMIC_SECTION("cut: " << what) {
      write_run_files(dir, "K",
                      {{"trials.csv", trials.substr(0, trials_length)},
                       {"tracks.csv", tracks.substr(0, tracks_length)},
                       {"measurements.csv", measurements.substr(0, measurements_length)},
                       {"meta.json", meta}});
      run_in(dir, "o.ini", "K", 2, /*resume=*/true);
      check_finished_tracking_run(dir, "K", reference, summary,
                                  {{"tracks.csv", tracks}, {"measurements.csv", measurements}});
    }
  }
  SECTION("--resume on a finished run changes nothing") {
    run_in(dir, "o.ini", "A", 1, /*resume=*/true);
    CHECK(dir.read("A/tracks.csv") == tracks);
    CHECK(dir.read("A/measurements.csv") == measurements);
    check_same(reference, without_timing(dir, "A/trials.csv"));
  }
}

TEST_CASE("run tracking: configuration errors are one clear line", "[run][tracking]") {
  TempDir dir;
  check_refused_experiment(dir, "scenario = othr\ntrials = 2\nalgorithm = no-such-tracker\n",
                           {"bad.ini", "unknown tracker 'no-such-tracker'", "known: ", "test-fixed-track"});
  check_refused_experiment(dir, "scenario = othr\ntrials = 2\nalgorithm = bp\n",
                           {"'bp' is a single-scan algorithm", "'othr' is tracking"});
  check_refused_experiment(dir, "scenario = othr\ntrials = 2\nalgorithm = jpda-bp\n",
                           {"'jpda-bp' is a multi-scan algorithm"});
  check_refused_experiment(dir, "scenario = grid\ntrials = 2\nalgorithm = test-fixed-track\n",
                           {"'test-fixed-track' is a tracker", "single-scan"});
  check_refused_experiment(dir,
                           "scenario = othr\ntrials = 2\nreference = test-fixed-track\nalgorithm = test-fixed-track\n",
                           {"'reference' lines are not used"});
  check_refused_experiment(dir, "scenario = othr\ntrials = 2\nalgorithm = test-fixed-track:nokey=1\n", {"nokey"});
  check_refused_experiment(dir, "scenario = othr\ntrials = 2\nalgorithm = test-fixed-track\n[sweep]\npd = 0.5, 1.5\n",
                           {"sweep point 1", "pd = 1.5"});
  check_refused_experiment(dir, "scenario = othr\ntrials = 2\nalgorithm = test-fixed-track\n[metrics]\ngate_km = -1\n",
                           {"bad.ini", "[metrics]", "gate_km"});
  check_refused_experiment(dir,
                           "scenario = othr\ntrials = 2\nalgorithm = test-fixed-track\n[metrics]\ngospa_cutoff = 2\n",
                           {"bad.ini", "gospa_cutoff"});
}

TEST_CASE("run tracking: from the command line an unknown tracker is one line, status 2", "[run][tracking][cli]") {
  TempDir dir;
  check_refused_on_command_line(dir,
                                "scenario = othr\ntrials = 2\nalgorithm = no-such-tracker\n[sweep]\npd = 0.75, 0.4\n",
                                {"bad.ini: unknown tracker 'no-such-tracker' (known: "});
}

}  // namespace DABENCH_TEST_FILE

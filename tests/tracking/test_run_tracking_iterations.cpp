// `dabench run` with `iterations = true` (tracking experiments): iterations.csv, the metrics of
// every track set a tracker records per iteration (Tracker::record_iterations, Fig. 7 of
// jdt-vb-multipath-othr). Through the C++ API (run_experiment), with a test-only iterative
// tracker registered here; the scenario test-static-target is the test-only one registered in
// tests/tracking/test_run_tracking.cpp (same test binary).
//  - a constructed case whose iterations.csv rows are computed by hand; the last recorded
//    iteration equals trials.csv; trackers that record nothing, or fail, have no rows; a
//    recorded set that does not fit the run fails the tracker;
//  - without the switch: no iterations.csv (also none left from an earlier --force'd run), the
//    other files unchanged;
//  - the switch on a non-tracking experiment, or with a non-boolean value: one-line errors;
//  - on the othr scenario, with iteration counts that differ per draw: identical iterations.csv
//    for 1 and 2 threads, and --resume after a hard kill (files cut anywhere, item files at
//    least as far as trials.csv) ends with the files of an uninterrupted run.
#include <catch2/catch.hpp>

#include <cmath>
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

// At iteration r = 0..n (n = `iterations`, or with iterations = −1 the number of
// measurements in scan 0 modulo 3), one confirmed track [g + shift_km / 2^r, 0, theta, 0] over
// scans first_scan .. first_scan + length − 1 (id 1) — with from_draw, instead through the
// first measurement [r, ṙ, ζ] of every scan, r shifted likewise (the previous state for an
// empty scan) — plus, for r ≤ far_until, a confirmed false track 100 km further out (id 2).
// Records the n + 1 sets when asked (unless record = false) and returns the last one;
// bad_at = r makes the recorded set r (only) hold a track with 2 state rows.
struct IteratingOptions {
  int iterations = 2;
  bool from_draw = false;
  bool record = true;
  double g = 1800.0;
  double theta = 0.5;
  int first_scan = 1;
  int length = 7;
  double shift_km = 8.0;
  int far_until = 0;
  int bad_at = -1;

  void bind(dabench::ParamList& p) {
    p.add("iterations", iterations, "iterations n (-1: measurements of scan 0 mod 3)");
    p.add("from_draw", from_draw, "track through each scan's first measurement");
    p.add("record", record, "record the history when asked");
    p.add("g", g, "ground range, km");
    p.add("theta", theta, "bearing, rad");
    p.add("first_scan", first_scan, "first scan");
    p.add("length", length, "scans");
    p.add("shift_km", shift_km, "range offset at r = 0, halved per iteration");
    p.add("far_until", far_until, "last iteration with the false track");
    p.add("bad_at", bad_at, "recorded iteration with a misshapen track");
  }
  std::string validate() const { return iterations >= -1 ? "" : "iterations must be >= -1"; }
};

class IteratingTracker final : public dabench::Tracker {
 public:
  using Options = IteratingOptions;
  static constexpr std::string_view kName = "test-iterating";
  static constexpr std::string_view kSummary = "test only: known track sets per iteration";
  explicit IteratingTracker(const Options& options) : o_(options) {}

  void run(const TrackingProblem& problem, TrackSet& tracks, SolveReport& report) override {
    const int n = o_.iterations >= 0 ? o_.iterations
                                     : (problem.scans.empty() ? 0 : static_cast<int>(problem.scans[0].cols()) % 3);
    std::vector<TrackSet>* history = o_.record ? iteration_history() : nullptr;
    for (int r = 0; r <= n; ++r) {
      tracks = at_iteration(problem, r);
      if (history != nullptr) {
        history->push_back(tracks);
        if (r == o_.bad_at) {
          history->back().tracks[0].states.conservativeResize(2, Eigen::NoChange);
          history->back().tracks[0].covariance_diagonals.conservativeResize(2, Eigen::NoChange);
        }
      }
    }
    report.iterations = n;
    report.converged = true;
  }

 private:
  TrackSet at_iteration(const TrackingProblem& problem, int r) const {
    const double shift = o_.shift_km / std::pow(2.0, r);
    TrackSet set;
    Track track;
    track.id = 1;
    track.confirmed = true;
    if (o_.from_draw) {
      const int scans = problem.scan_count();
      track.first_scan = 0;
      track.states.resize(4, scans);
      Eigen::Vector4d state(1750.0, 0.0, 0.5, 0.0);
      for (int k = 0; k < scans; ++k) {
        const Eigen::MatrixXd& scan = problem.scans[k];
        if (scan.cols() > 0) state << scan(0, 0) + shift, scan(1, 0), scan(2, 0), 0.0;
        track.states.col(k) = state;
      }
    } else {
      track.first_scan = o_.first_scan;
      track.states.resize(4, o_.length);
      for (int s = 0; s < o_.length; ++s) track.states.col(s) << o_.g + shift, 0.0, o_.theta, 0.0;
    }
    track.covariance_diagonals = Eigen::MatrixXd::Constant(4, track.states.cols(), 1.0);
    set.tracks.push_back(track);
    if (r <= o_.far_until) {
      track.id = 2;
      track.states.row(0).array() += 100.0;
      set.tracks.push_back(track);
    }
    if (r > 0) set.objective = -100.0 / r;  // like jdt-vb: undefined before the first iteration
    return set;
  }

  Options o_;
};
DABENCH_REGISTER_TRACKING_TRACKER(IteratingTracker);

const std::vector<std::string> kIterationMetrics = {"nvt",       "tpd",          "nft",
                                                    "false_tracks", "ghost_tracks", "broken_targets",
                                                    "ttl_scans", "aee_range_km", "aee_bearing_mrad",
                                                    "mospa_km"};

// Target at (1800 km, 0.5 rad) alive at scans 1..7 of 8 (plus one clutter point per scan).
const char* const kConstructed =
    "scenario = test-static-target\n"
    "trials = 2\n"
    "seed = 9\n"
    "iterations = true\n"
    "algorithm = test-iterating\n"
    "algorithm = test-iterating:record=false\n"
    "algorithm = test-iterating:iterations=0\n"
    "algorithm = test-iterating:bad_at=1\n";

// OTHR, 10 scans, light clutter, the 2×2 grid of Table IV, 6 trials: 24 items, 3 blocks.
constexpr int kOthrTrials = 6;

// Where item `item`'s rows start in a file of this test's runs.
std::size_t item_offset(const std::string& text, long long item) { return offset_of_item(text, item, kOthrTrials); }
std::string othr_ini(bool iterations) {
  return std::string("scenario = othr\ntrials = 6\nseed = 5\n") + (iterations ? "iterations = true\n" : "") +
         "algorithm = test-iterating:iterations=-1,from_draw=true\n"
         "algorithm = test-iterating:record=false,from_draw=true\n"
         "algorithm = test-iterating:iterations=3,from_draw=true,far_until=1\n"
         "[scenario]\nscans = 10\n[sweep]\npd = 0.75, 0.4\nclutter = 5, 20\n";
}

}  // namespace

TEST_CASE("run tracking iterations: iterations.csv of a constructed case, by hand", "[run][tracking][iterations]") {
  TempDir dir;
  dir.write("c.ini", kConstructed);
  const dabench::RunOutcome outcome = run_in(dir, "c.ini", "C", 2);
  CHECK(outcome.item_files == std::vector<std::string>{"tracks.csv", "measurements.csv", "iterations.csv"});
  const CsvTable iterations = parse_csv(dir.read("C/iterations.csv"));
  std::vector<std::string> header = {"point",  "scans", "first_alive", "targets",  "target_g",
                                     "target_theta", "trial", "seed", "algorithm", "iteration"};
  header.insert(header.end(), kIterationMetrics.begin(), kIterationMetrics.end());
  header.push_back("free_energy");
  CHECK(iterations.header == header);
  // Per trial: test-iterating r = 0, 1, 2; record=false nothing; iterations=0 r = 0; bad_at=1
  // nothing (failed).
  REQUIRE(iterations.rows.size() == 2 * 4);
  const CsvTable trials = parse_csv(dir.read("C/trials.csv"));
  REQUIRE(trials.rows.size() == 2 * 4);
  const double far = std::sqrt((8.0 * 8.0 + 50.0 * 50.0) / 2.0);  // OSPA, near track 8 km off + false track
  for (int trial = 0; trial < 2; ++trial) {
    INFO("trial " << trial);
    const std::size_t base = static_cast<std::size_t>(trial) * 4;
    for (std::size_t r = base; r < base + 4; ++r) {
      CHECK(iterations.rows[r][0] == "0");
      CHECK(iterations.at(r, "trial") == std::to_string(trial));
      CHECK(iterations.at(r, "seed") == "9");
    }
    CHECK(iterations.at(base + 0, "algorithm") == "test-iterating");
    CHECK(iterations.at(base + 3, "algorithm") == "test-iterating:iterations=0");
    CHECK(iterations.at(base + 0, "iteration") == "0");
    CHECK(iterations.at(base + 1, "iteration") == "1");
    CHECK(iterations.at(base + 2, "iteration") == "2");
    CHECK(iterations.at(base + 3, "iteration") == "0");
    CHECK(iterations.at(base + 0, "free_energy").empty());
    CHECK(number(iterations, base + 1, "free_energy") == -100.0);
    CHECK(number(iterations, base + 2, "free_energy") == -50.0);
    CHECK(iterations.at(base + 3, "free_energy").empty());
    // r = 0: the near track 8 km off at scans 1..7 (valid, follows all 7 scans from the
    // first) and a false track 108 km off; OSPA 0 at scan 0, then one target vs two tracks.
    for (const std::size_t r : {base + 0, base + 3}) {
      CHECK(number(iterations, r, "nvt") == 1.0);
      CHECK(number(iterations, r, "tpd") == 1.0);
      CHECK(number(iterations, r, "nft") == 1.0);
      CHECK(number(iterations, r, "false_tracks") == 1.0);
      CHECK(number(iterations, r, "ghost_tracks") == 0.0);
      CHECK(number(iterations, r, "broken_targets") == 0.0);
      CHECK(number(iterations, r, "ttl_scans") == 0.0);
      CHECK(number(iterations, r, "aee_range_km") == Approx(8.0).epsilon(1e-12));
      CHECK(number(iterations, r, "aee_bearing_mrad") == 0.0);
      CHECK(number(iterations, r, "mospa_km") == Approx(7.0 * far / 8.0).epsilon(1e-9));
    }
    // r = 1, 2: the near track alone, 4 then 2 km off.
    for (const auto& [r, d] : {std::pair{base + 1, 4.0}, std::pair{base + 2, 2.0}}) {
      CHECK(number(iterations, r, "nvt") == 1.0);
      CHECK(number(iterations, r, "nft") == 0.0);
      CHECK(number(iterations, r, "false_tracks") == 0.0);
      CHECK(number(iterations, r, "aee_range_km") == Approx(d).epsilon(1e-9));
      CHECK(number(iterations, r, "mospa_km") == Approx(7.0 * d / 8.0).epsilon(1e-9));
    }
    // The last recorded iteration is the output: the same metrics as trials.csv.
    for (const auto& column : kIterationMetrics) {
      CHECK(iterations.at(base + 2, column) == trials.at(base + 0, column));
      CHECK(iterations.at(base + 3, column) == trials.at(base + 2, column));
    }
    CHECK(trials.at(base + 1, "status") == "ok");  // recorded nothing: ok, no rows
    CHECK(trials.at(base + 3, "status") == "failed:iteration 1: track 1 has 2 state rows, expected at least 4");
    CHECK(trials.at(base + 3, "nvt").empty());
  }
  CHECK(contains(dir.read("C/meta.json"), "\"record_iterations\": true"));
}

TEST_CASE("run tracking iterations: without the switch, no iterations.csv and nothing else changes",
          "[run][tracking][iterations]") {
  TempDir dir;
  dir.write("on.ini", othr_ini(true));
  dir.write("off.ini", othr_ini(false));
  run_in(dir, "on.ini", "on", 2);
  const dabench::RunOutcome off = run_in(dir, "off.ini", "off", 2);
  CHECK(off.item_files == std::vector<std::string>{"tracks.csv", "measurements.csv"});
  CHECK(dir.exists("on/iterations.csv"));
  CHECK_FALSE(dir.exists("off/iterations.csv"));
  check_same(without_timing(dir, "on/trials.csv"), without_timing(dir, "off/trials.csv"));
  CHECK(dir.read("on/tracks.csv") == dir.read("off/tracks.csv"));
  CHECK(dir.read("on/measurements.csv") == dir.read("off/measurements.csv"));
  CHECK_FALSE(contains(dir.read("off/meta.json"), "record_iterations"));

  SECTION("--force without the switch removes an earlier run's iterations.csv") {
    run_in(dir, "off.ini", "on", 1, /*resume=*/false, /*force=*/true);
    CHECK_FALSE(dir.exists("on/iterations.csv"));
  }
  SECTION("--resume with the switch changed is refused (a different run)") {
    CHECK_THROWS_AS(run_in(dir, "off.ini", "on", 1, /*resume=*/true), dabench::InputError);
    CHECK_THROWS_AS(run_in(dir, "on.ini", "off", 1, /*resume=*/true), dabench::InputError);
  }
}

TEST_CASE("run tracking iterations: the switch outside tracking, or not a boolean, is one clear line",
          "[run][tracking][iterations]") {
  TempDir dir;
  check_refused_experiment(dir, "scenario = grid\ntrials = 2\nreference = exact\nalgorithm = bp\niterations = true\n",
                           {"bad.ini", "'iterations = true'", "scenario 'grid' is single-scan"});
  check_refused_experiment(dir, "scenario = bearings\ntrials = 2\nalgorithm = jpda-bp\niterations = true\n",
                           {"bad.ini", "'iterations = true'", "multi-scan"});
  check_refused_experiment(dir, "scenario = othr\ntrials = 2\nalgorithm = test-iterating\niterations = sometimes\n",
                           {"bad.ini", "iterations = sometimes", "true or false"});
  // `iterations = false` is the default, accepted anywhere.
  dir.write("grid.ini", "scenario = grid\ntrials = 1\nreference = exact\nalgorithm = bp\niterations = false\n");
  run_in(dir, "grid.ini", "G", 1);
  CHECK_FALSE(dir.exists("G/iterations.csv"));

  check_refused_on_command_line(dir,
                                "scenario = grid\ntrials = 2\nreference = exact\nalgorithm = bp\niterations = true\n",
                                {"bad.ini: 'iterations = true'"});
}

TEST_CASE("run tracking iterations: othr, 1 and 2 threads give identical files",
          "[run][tracking][iterations][determinism]") {
  TempDir dir;
  dir.write("o.ini", othr_ini(true));
  run_in(dir, "o.ini", "one", 1);
  run_in(dir, "o.ini", "two", 2);
  const std::string text = dir.read("one/iterations.csv");
  CHECK(text == dir.read("two/iterations.csv"));
  check_same(without_timing(dir, "one/trials.csv"), without_timing(dir, "two/trials.csv"));
  CHECK(dir.read("one/tracks.csv") == dir.read("two/tracks.csv"));

  // Rows per item: the draw-dependent tracker 1..3 (iterations 0..2, varying), record=false
  // none, iterations=3 four; each run's last iteration equals its trials.csv row.
  const CsvTable iterations = parse_csv(text);
  const CsvTable trials = parse_csv(dir.read("one/trials.csv"));
  std::vector<int> counts(4, 0);
  std::size_t row = 0;
  for (long long item = 0; item < 4 * kOthrTrials; ++item) {
    const std::string point = std::to_string(item / kOthrTrials), trial = std::to_string(item % kOthrTrials);
    for (const std::size_t a : {0u, 2u}) {
      const std::size_t t = static_cast<std::size_t>(item) * 3 + a;
      const std::string& algorithm = trials.at(t, "algorithm");
      const int n = std::stoi(trials.at(t, "iterations"));
      for (int r = 0; r <= n; ++r, ++row) {
        REQUIRE(row < iterations.rows.size());
        CHECK(iterations.at(row, "point") == point);
        CHECK(iterations.at(row, "trial") == trial);
        CHECK(iterations.at(row, "algorithm") == algorithm);
        CHECK(iterations.at(row, "iteration") == std::to_string(r));
        if (r == n) {
          for (const auto& column : kIterationMetrics) CHECK(iterations.at(row, column) == trials.at(t, column));
        }
      }
      if (a == 0) ++counts[static_cast<std::size_t>(n)];
    }
  }
  CHECK(row == iterations.rows.size());
  CHECK(counts[0] + counts[1] + counts[2] == 4 * kOthrTrials);
  CHECK(counts[0] > 0);  // iteration counts differ between draws
  CHECK((counts[1] > 0 || counts[2] > 0));
}

TEST_CASE("run tracking iterations: othr, --resume after a hard kill finishes identically",
          "[run][tracking][iterations][resume]") {
  TempDir dir;
  dir.write("o.ini", othr_ini(true));
  run_in(dir, "o.ini", "A", 2);
  const std::string trials = dir.read("A/trials.csv");
  const std::string tracks = dir.read("A/tracks.csv");
  const std::string measurements = dir.read("A/measurements.csv");
  const std::string iterations = dir.read("A/iterations.csv");
  const std::string meta = dir.read("A/meta.json");
  const CsvTable reference = without_timing(dir, "A/trials.csv");
  const CsvTable summary = without_timing(dir, "A/summary.csv");
  const auto header = [](const std::string& text) { return text.find('\n') + 1; };
  // (what, lengths of trials.csv, tracks.csv, measurements.csv, iterations.csv); the item
  // files reach at least as far as trials.csv (the writer writes them first).
  using Cut = std::tuple<std::string, std::size_t, std::size_t, std::size_t, std::size_t>;
  const std::vector<Cut> cuts = {
      {"all at the same item boundary", item_offset(trials, 5), item_offset(tracks, 5),
       item_offset(measurements, 5), item_offset(iterations, 5)},
      {"iterations mid-line further on", item_offset(trials, 7) + 9, item_offset(tracks, 7),
       item_offset(measurements, 7), item_offset(iterations, 11) + 5},
      {"headers only", header(trials), header(tracks), header(measurements), header(iterations)},
      {"iterations header cut", header(trials), header(tracks), header(measurements), header(iterations) - 7},
      {"trials header only, iterations with rows", header(trials), item_offset(tracks, 2),
       item_offset(measurements, 7), item_offset(iterations, 9) + 2},
      {"trials cut, iterations complete", item_offset(trials, 13) + 4, tracks.size(), measurements.size(),
       iterations.size()},
      {"second point, block boundary", item_offset(trials, 16), item_offset(tracks, 16) + 3,
       item_offset(measurements, 16), item_offset(iterations, 16) + 1},
  };
  for (const auto& [what, trials_length, tracks_length, measurements_length, iterations_length] : cuts) {
    DYNAMIC_SECTION("cut: " << what) {
      write_run_files(dir, "K",
                      {{"trials.csv", trials.substr(0, trials_length)},
                       {"tracks.csv", tracks.substr(0, tracks_length)},
                       {"measurements.csv", measurements.substr(0, measurements_length)},
                       {"iterations.csv", iterations.substr(0, iterations_length)},
                       {"meta.json", meta}});
      run_in(dir, "o.ini", "K", 2, /*resume=*/true);
      check_finished_tracking_run(dir, "K", reference, summary,
                                  {{"tracks.csv", tracks}, {"measurements.csv", measurements},
                                   {"iterations.csv", iterations}});
    }
  }
  SECTION("--resume on a finished run changes nothing") {
    run_in(dir, "o.ini", "A", 1, /*resume=*/true);
    CHECK(dir.read("A/iterations.csv") == iterations);
  }
}

}  // namespace DABENCH_TEST_FILE

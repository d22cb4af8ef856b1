#include "algorithms/tbd/tbd_mb.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "algorithms/tbd/new_objects.hpp"
#include "harness/core/special_values.hpp"
#include "harness/tbd/registry.hpp"

namespace dabench {

namespace {

// A new Bernoulli enters the exclusivity SPA if its existence alone (an upper bound: ν ≤ 1)
// reaches this; the others are recycled at their own existence, and their effect on the
// Bernoullis in the SPA would be below this odds.
constexpr double kEnterExistence = 1e-4;
constexpr double kSweepTolerance = 1e-6;

}  // namespace

std::string TbdMbOptions::validate() const {
  if (particles < 10 || particles > 1000000) return "particles must be in 10..1e6";
  if (birth_grid < 1 || birth_grid > 16) return "birth_grid must be in 1..16";
  if (!(support_radius >= 0.0 && support_radius <= 100.0)) return "support_radius must be in [0, 100]";
  if (sweeps < 1 || sweeps > 10000) return "sweeps must be in 1..10000";
  if (!(detection_threshold > 0.0 && detection_threshold < 1.0)) return "detection_threshold must be in (0, 1)";
  if (!(recycle_threshold > 0.0 && recycle_threshold < detection_threshold)) {
    return "recycle_threshold must be in (0, detection_threshold)";
  }
  if (association < 0 || association > 1) return "association must be objects or none";
  return {};
}

void TbdMb::start(const TbdProblem& problem) {
  problem_ = &problem;
  const TbdSensor& sensor = problem.sensor;
  const double radius = options_.support_radius > 0.0 ? options_.support_radius : 2.0 * std::sqrt(sensor.spread_variance);
  likelihood_ = SupportLikelihood(sensor, problem.amplitude, radius);
  rng_ = RandomStream(algorithm_stream_seed(problem.trial_key.seed, options_.seed), problem.trial_key.point,
                      problem.trial_key.trial);
  next_label_ = 0;
  legacy_.clear();
  undetected_.assign(sensor.cells(), 0.0);
  make_cell_objects(sensor, options_.birth_grid, births_);
}

int TbdMb::cell_of(double px, double py) const {
  const TbdSensor& s = problem_->sensor;
  if (!s.inside(px, py)) return -1;
  const int column = std::min(static_cast<int>((px - s.x_min) / s.cell_size), s.columns - 1);
  const int row = std::min(static_cast<int>((py - s.y_min) / s.cell_size), s.rows - 1);
  return row * s.columns + column;
}

void TbdMb::recycle(const ParticleObject& object) {
  for (int i = 0; i < object.size(); ++i) {
    const int cell = cell_of(object.x[i], object.y[i]);
    if (cell >= 0) undetected_[cell] += object.existence * object.weight[i];
  }
}

void TbdMb::add_node(const ParticleObject& object, const Eigen::Matrix2Xd& frame, double pad) {
  log_weight_.resize(object.size());
  for (int i = 0; i < object.size(); ++i) {
    log_weight_[i] = std::log(object.weight[i]) + likelihood_.log_ratio(frame, object.x[i], object.y[i]);
  }
  exclusion_.add(object.x.data(), object.y.data(), log_weight_.data(), object.size(), object.existence, pad);
}

// A NaN existence means a likelihood or the frame was not finite: the run records "failed:"
// rather than recycling the Bernoulli as if it were unlikely.
void TbdMb::fail(SolveReport& report, int k, const std::string& what) {
  report.skipped = fmt::format("failed:step {}: {} is not finite (a likelihood or the frame is not)", k + 1, what);
}

// association = none: a Bernoulli's Bayes update with its separable likelihood alone — weights
// w ℓ normalised, r̃ = r T / (r T + 1 − r), T = Σ w ℓ (in logs: ℓ reaches e^{±500}).
double TbdMb::update_alone(ParticleObject& object, const Eigen::Matrix2Xd& frame) {
  double top = kMinusInfinity;
  log_weight_.resize(object.size());
  for (int i = 0; i < object.size(); ++i) {
    top = std::max(top, log_weight_[i] = std::log(object.weight[i]) + likelihood_.log_ratio(frame, object.x[i], object.y[i]));
  }
  double sum = 0.0;
  for (int i = 0; i < object.size(); ++i) sum += object.weight[i] = std::exp(log_weight_[i] - top);
  for (double& w : object.weight) w /= sum;
  const double log_odds = std::log(object.existence) - std::log1p(-object.existence) + top + std::log(sum);
  return logistic(log_odds);
}

void TbdMb::step(int k, std::vector<TbdEstimate>& estimates, SolveReport& report) {
  const TbdProblem& problem = *problem_;
  const TbdSensor& sensor = problem.sensor;
  const Eigen::Matrix2Xd& frame = problem.frames[k];
  const int p = options_.particles;
  const double survival = problem.filter.survival_probability;

  // 1. Prediction: legacy Bernoullis and the Poisson intensity of undetected objects.
  predict_objects(legacy_, problem, k, p, next_label_, rng_);
  const double birth = problem.filter.birth_mean / sensor.cells();
  for (double& mass : undetected_) mass = survival * mass + birth;

  // 2.–3. Likelihoods and the exclusivity SPA: legacy Bernoullis, then the new Bernoulli of
  //       every cell that could survive alone (log ξ_j = log Λ_j + log ℓ̄_j), strongest first
  //       (association = none: no SPA; each Bernoulli's update alone below).
  const bool exclusive = options_.association == kObjects;
  exclusion_.reset(sensor, likelihood_.radius());
  const int legacy_count = static_cast<int>(legacy_.size());
  if (exclusive) {
    for (const ParticleObject& o : legacy_) add_node(o, frame, 0.0);
  }
  log_new_odds_.assign(sensor.cells(), kMinusInfinity);
  candidates_.clear();
  const double enter_log_odds = std::log(kEnterExistence / (1.0 - kEnterExistence));
  for (int j = 0; j < sensor.cells(); ++j) {
    if (!(undetected_[j] > 0.0)) continue;
    const ParticleObject& o = births_[j];
    double top = kMinusInfinity;
    log_weight_.resize(o.size());
    for (int i = 0; i < o.size(); ++i) top = std::max(top, log_weight_[i] = likelihood_.log_ratio(frame, o.x[i], o.y[i]));
    double mean = 0.0;
    for (int i = 0; i < o.size(); ++i) mean += o.weight[i] * std::exp(log_weight_[i] - top);
    log_new_odds_[j] = std::log(undetected_[j]) + top + std::log(mean);
    if (std::isnan(log_new_odds_[j])) return fail(report, k, fmt::format("the new Bernoulli of cell {}'s existence", j));
    if (log_new_odds_[j] >= enter_log_odds) candidates_.push_back(j);
  }
  std::sort(candidates_.begin(), candidates_.end(), [&](int a, int b) {
    return log_new_odds_[a] != log_new_odds_[b] ? log_new_odds_[a] > log_new_odds_[b] : a < b;
  });
  const double pad = 0.5 * sensor.cell_size / options_.birth_grid;  // the drawn particles fill the whole cell
  if (exclusive) {
    for (const int j : candidates_) {
      births_[j].existence = undetected_[j] / (1.0 + undetected_[j]);
      add_node(births_[j], frame, pad);
    }
    report.iterations = exclusion_.solve(options_.sweeps, kSweepTolerance);
    report.converged = exclusion_.converged();
  }

  // 4.–5. Legacy Bernoullis: particles weighted by ℓ Π ν, existence r̃; below the recycling
  //       threshold their mass returns to the Poisson intensity (or is dropped).
  int kept = 0;
  for (int n = 0; n < legacy_count; ++n) {
    ParticleObject& o = legacy_[n];
    if (exclusive) {
      exclusion_.posterior_weights(n, o.weight);
      o.existence = exclusion_.existence(n);
    } else {
      o.existence = update_alone(o, frame);
    }
    if (std::isnan(o.existence)) return fail(report, k, fmt::format("Bernoulli {}'s existence", o.label));
    if (o.existence < options_.recycle_threshold) {
      if (options_.recycling && o.existence > 0.0) recycle(o);
      continue;
    }
    resample(o, p, rng_, scratch_);
    if (kept != n) std::swap(legacy_[kept], o);
    ++kept;
  }
  legacy_.resize(kept);
  // New Bernoullis: the cell's Poisson mass became the Bernoulli; kept above the recycling
  // threshold, else its existence returns to the cell's intensity (or is dropped).
  for (int j = 0; j < sensor.cells(); ++j) {
    if (log_new_odds_[j] != kMinusInfinity) undetected_[j] = options_.recycling ? logistic(log_new_odds_[j]) : 0.0;
  }
  for (int c = 0; c < static_cast<int>(candidates_.size()); ++c) {
    const int j = candidates_[c];
    const int node = legacy_count + c;
    const double existence = exclusive ? exclusion_.existence(node) : logistic(log_new_odds_[j]);
    if (std::isnan(existence)) return fail(report, k, fmt::format("the new Bernoulli of cell {}'s existence", j));
    if (existence < options_.recycle_threshold) {
      undetected_[j] = options_.recycling ? existence : 0.0;
      continue;
    }
    legacy_.emplace_back();
    ParticleObject& o = legacy_.back();
    draw_in_cell(problem, j, p, rng_, o);
    for (int i = 0; i < p; ++i) {
      o.weight[i] = likelihood_.log_ratio(frame, o.x[i], o.y[i]) +
                    (exclusive ? exclusion_.log_message_at(node, o.x[i], o.y[i]) : 0.0);
    }
    settle_drawn(o, existence, next_label_++, rng_, scratch_);
    undetected_[j] = 0.0;
  }

  // 6. Estimates.
  estimates.clear();
  for (const ParticleObject& o : legacy_) {
    if (o.existence > options_.detection_threshold) estimates.push_back({o.mean(), o.existence, o.label});
  }
}

void TbdMb::beliefs(std::vector<TbdBeliefSample>& samples) const { belief_samples(legacy_, samples); }

DABENCH_REGISTER_TBD_TRACKER(TbdMb);

}  // namespace dabench

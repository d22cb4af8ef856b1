#include "algorithms/tbd/tbd_bp.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "algorithms/tbd/new_objects.hpp"
#include "harness/tbd/registry.hpp"

namespace dabench {

std::string TbdBpOptions::validate() const {
  if (iterations < 1 || iterations > 20) return "iterations must be in 1..20";
  if (particles < 10 || particles > 1000000) return "particles must be in 10..1e6";
  if (birth_grid < 1 || birth_grid > 16) return "birth_grid must be in 1..16";
  if (!(support_sigmas >= 1.0 && support_sigmas <= 10.0)) return "support_sigmas must be in [1, 10]";
  if (!(detection_threshold > 0.0 && detection_threshold < 1.0)) return "detection_threshold must be in (0, 1)";
  if (!(pruning_threshold >= 0.0 && pruning_threshold < detection_threshold)) {
    return "pruning_threshold must be in [0, detection_threshold)";
  }
  if (!(merge_distance >= 0.0 && merge_distance <= 100.0)) return "merge_distance must be in [0, 100]";
  if (schedule == TbdBp::kJoint && (exact_kappa || !interaction)) {
    return "schedule = joint exchanges kappa-tilde messages: it needs interaction = true and exact_kappa = false";
  }
  return {};
}

void TbdBp::start(const TbdProblem& problem) {
  problem_ = &problem;
  rng_ = RandomStream(algorithm_stream_seed(problem.trial_key.seed, options_.seed), problem.trial_key.point,
                      problem.trial_key.trial);
  next_label_ = 0;
  legacy_.clear();
  make_new_objects();
  // The new POs' particles never move: their windows and spread tables are made once.
  messages_.configure(problem.sensor, problem.amplitude, support_radius());
  birth_work_.resize(births_.size());
  for (std::size_t b = 0; b < births_.size(); ++b) messages_.prepare(births_[b], birth_work_[b]);
}

double TbdBp::support_radius() const {
  return options_.support_sigmas * std::sqrt(problem_->sensor.spread_variance);
}

// One new PO per cell, r⁻ = (μ_B/J)/(1 + μ_B/J); the same for every step of a run.
void TbdBp::make_new_objects() {
  const TbdSensor& s = problem_->sensor;
  const double birth = problem_->filter.birth_mean / s.cells();
  if (!(birth > 0.0)) {
    births_.clear();
    return;
  }
  make_cell_objects(s, options_.birth_grid, births_);
  for (ParticleObject& o : births_) o.existence = birth / (1.0 + birth);
}

// A NaN existence or weight means a message or the frame was not finite: the run records
// "failed:" rather than pruning the PO as if it were unlikely.
void TbdBp::fail(SolveReport& report, int k, const std::string& what) {
  report.skipped = fmt::format("failed:step {}: {} is not finite (a message or the frame is not)", k + 1, what);
}

double TbdBp::keep_log_odds() const {
  return std::log(options_.pruning_threshold) - std::log1p(-options_.pruning_threshold);
}

// Step 3 of the header: screening against the field, then strongest first, each new PO
// re-evaluated against the field with the new POs kept before it. `joint`: the new POs kept at
// the previous iteration leave the field first, and a kept one enters with its extrinsic
// (cell-excluded) messages; else with its belief. Returns the cell of a new PO whose existence
// is NaN, else −1.
int TbdBp::new_object_stage(bool joint) {
  const double keep = keep_log_odds();
  if (joint) {
    for (const int b : kept_births_) messages_.leave_field(birth_work_[b]);
  }
  kept_births_.clear();
  order_.clear();
  for (int b = 0; b < static_cast<int>(births_.size()); ++b) {
    const double log_odds = messages_.evaluate(births_[b], birth_work_[b], options_.interaction);
    if (std::isnan(log_odds)) return b;
    if (log_odds >= keep) order_.push_back(b);
  }
  std::sort(order_.begin(), order_.end(), [&](int a, int b) {
    const double la = birth_work_[a].log_odds, lb = birth_work_[b].log_odds;
    return la != lb ? la > lb : a < b;
  });
  for (const int b : order_) {
    if (joint) {
      if (messages_.evaluate(births_[b], birth_work_[b], true, true) < keep) continue;
      messages_.enter_field(births_[b], birth_work_[b]);
    } else {
      if (!kept_births_.empty() && messages_.evaluate(births_[b], birth_work_[b], options_.interaction) < keep) continue;
      messages_.add_to_field(births_[b], birth_work_[b]);
    }
    kept_births_.push_back(b);
  }
  return -1;
}

void TbdBp::step(int k, std::vector<TbdEstimate>& estimates, SolveReport& report) {
  const TbdProblem& problem = *problem_;
  const TbdSensor& sensor = problem.sensor;
  const int p = options_.particles;
  if (options_.exact_kappa && !births_.empty()) {
    report.skipped = "exact_kappa: new potential objects (birth_mean > 0) are evaluated with kappa-tilde only";
    return;
  }
  predict_objects(legacy_, problem, k, p, next_label_, rng_);

  // 1-2. Legacy POs: L iterations among themselves (serial or flooding), then the new POs; or,
  //      joint, L iterations of both.
  all_.clear();
  for (ParticleObject& o : legacy_) all_.push_back(&o);
  const int legacy_count = static_cast<int>(legacy_.size());
  kept_births_.clear();
  if (options_.schedule == kJoint) {
    messages_.start_serial(sensor, problem.amplitude, problem.frames[k], all_, support_radius());
    for (int l = 1; l <= options_.iterations; ++l) {
      messages_.serial_sweep();
      if (const int cell = births_.empty() ? -1 : new_object_stage(true); cell >= 0) {
        return fail(report, k, fmt::format("the new potential object of cell {}'s existence", cell));
      }
    }
    messages_.finish_serial();
  } else {
    CellMessageOptions message_options;
    message_options.iterations = options_.iterations;
    message_options.support_radius = support_radius();
    message_options.interaction = options_.interaction;
    message_options.exact = options_.exact_kappa;
    message_options.serial = options_.schedule == kSerial;
    if (!messages_.run(sensor, problem.amplitude, problem.frames[k], all_, message_options)) {
      report.skipped = "exact_kappa: a data cell is reached by more than two potential objects";
      return;
    }
    if (!births_.empty()) {
      messages_.outgoing_field();
      if (const int cell = new_object_stage(false); cell >= 0) {
        return fail(report, k, fmt::format("the new potential object of cell {}'s existence", cell));
      }
    }
  }
  report.iterations = options_.iterations;
  // Kept new POs become legacy POs, in the order they were kept.
  for (const int b : kept_births_) {
    legacy_.emplace_back();
    ParticleObject& o = legacy_.back();
    draw_in_cell(problem, b, p, rng_, o);
    messages_.log_ratios_at(birth_work_[b], o, o.weight);
    settle_drawn(o, logistic(birth_work_[b].log_odds), next_label_++, rng_, scratch_);
  }

  // 3. Legacy POs of this step's run: belief, existence, prune, resample (the new POs
  //    appended after them are kept as they are).
  const double keep_log_odds = this->keep_log_odds();
  keep_.assign(legacy_count, false);
  for (int n = 0; n < legacy_count; ++n) {
    ParticleObject& o = legacy_[n];
    const double log_odds = messages_.existence_log_odds(n);
    if (std::isnan(log_odds)) return fail(report, k, fmt::format("potential object {}'s existence", o.label));
    if (!(log_odds >= keep_log_odds)) continue;
    const std::vector<double>& total = messages_.total_log_ratio(n);
    double top = -std::numeric_limits<double>::infinity();
    for (int i = 0; i < o.size(); ++i) top = std::max(top, total[i]);
    double sum = 0.0;
    for (int i = 0; i < o.size(); ++i) sum += o.weight[i] *= std::exp(total[i] - top);
    if (!(sum > 0.0 && sum < std::numeric_limits<double>::infinity())) {
      return fail(report, k, fmt::format("potential object {}'s particle weights", o.label));
    }
    for (double& w : o.weight) w /= sum;
    o.existence = logistic(log_odds);
    resample(o, p, rng_, scratch_);
    keep_[n] = true;
  }
  int kept = 0;
  for (int n = 0; n < static_cast<int>(legacy_.size()); ++n) {
    if (n >= legacy_count || keep_[n]) std::swap(legacy_[kept++], legacy_[n]);
  }
  legacy_.resize(kept);
  if (options_.merge_distance > 0.0) merge_duplicates();

  estimates.clear();
  for (const ParticleObject& o : legacy_) {
    if (o.existence > options_.detection_threshold) estimates.push_back({o.mean(), o.existence, o.label});
  }
}

// Step 5 of the header: in decreasing r̃ (ties: older first), delete a PO within
// merge_distance of one already kept.
void TbdBp::merge_duplicates() {
  order_.resize(legacy_.size());
  for (int n = 0; n < static_cast<int>(order_.size()); ++n) order_[n] = n;
  std::sort(order_.begin(), order_.end(), [&](int a, int b) {
    return legacy_[a].existence != legacy_[b].existence ? legacy_[a].existence > legacy_[b].existence
                                                        : legacy_[a].label < legacy_[b].label;
  });
  keep_.assign(legacy_.size(), false);
  kept_means_.clear();
  const double limit = options_.merge_distance * options_.merge_distance;
  for (const int n : order_) {
    const Eigen::Vector2d mean = legacy_[n].mean().head<2>();
    bool duplicate = false;
    for (const Eigen::Vector2d& other : kept_means_) duplicate = duplicate || (mean - other).squaredNorm() < limit;
    if (duplicate) continue;
    keep_[n] = true;
    kept_means_.push_back(mean);
  }
  int kept = 0;
  for (int n = 0; n < static_cast<int>(legacy_.size()); ++n) {
    if (keep_[n]) std::swap(legacy_[kept++], legacy_[n]);
  }
  legacy_.resize(kept);
}

void TbdBp::beliefs(std::vector<TbdBeliefSample>& samples) const { belief_samples(legacy_, samples); }

DABENCH_REGISTER_TBD_TRACKER(TbdBp);

}  // namespace dabench

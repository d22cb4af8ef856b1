// MD-HMHT: options, the hypothesis-oriented scan loop (Murty per cluster, selection, N-scan
// pruning, initiation) and the output. The track filter is md_hmht_tracks.cpp.
#include "algorithms/tracking/md_hmht.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>
#include <span>
#include <unordered_map>
#include <vector>

#include <fmt/format.h>

#include "algorithms/tracking/chi_square.hpp"
#include "algorithms/tracking/md_hmht_tracks.hpp"
#include "algorithms/tracking/track_heads.hpp"
#include "algorithms/assignment/murty.hpp"
#include "harness/core/errors.hpp"
#include "harness/tracking/registry.hpp"

namespace dabench {

void MdHmhtOptions::bind(ParamList& p) {
  p.add("hypotheses", hypotheses, "n best hypotheses kept, 0..100; 0 = 3 if clutter <= 200 else 2 (the paper's)");
  p.add("window", window, "N-scan pruning window W (decisions older than W scans are final), 1..30");
  p.add("deletion_misses", deletion_misses,
        "successive scans with an empty gate before deletion, 0..100; 0 = 3 if clutter <= 200 else 5");
  p.add("gate_probability", gate_probability, "p_g of the gates, in (0, 1)");
  p.add("per_parent", per_parent, "0: n best children over all parents (Cox-Hingorani); 1: n best per parent");
  p.add("confirm_llr", confirm_llr, "track log-likelihood ratio that confirms a track, > 0");
  p.add("alternative_heads", alternative_heads,
        "1: a head for every equally good path reading of a new return group (not in the paper); 0: only the best");
  p.add("head_range", head_range, "track-head threshold on slant range, km, > 0");
  p.add("head_range_rate", head_range_rate, "track-head threshold on slant range rate, km/s, > 0");
  p.add("head_azimuth", head_azimuth, "track-head threshold on azimuth, rad, > 0");
  p.add("head_bearing_rate_sd", head_bearing_rate_sd, "s.d. of the bearing rate of a new track, rad/s, > 0");
  p.add_choice("report_from", report_from, {"head", "confirmation"},
               "a confirmed track is output from its head's scan (head) or from the scan that confirmed it (confirmation)");
  p.add_choice("assignment", assignment, {"joint", "per_path"},
               "joint: one 2-D assignment over all (track, path) pseudo-targets; per_path: one per path in turn "
               "(EE, EF, FE, FF) over the measurements earlier paths left, a beam of n (the paper's path-dependent assignments)");
  p.add("literal", literal,
        "1: the paper-literal set, overriding alternative_heads = 0, report_from = confirmation, assignment = per_path");
}

std::string MdHmhtOptions::validate() const {
  if (hypotheses < 0 || hypotheses > 100) return fmt::format("hypotheses = {} must be in 0..100", hypotheses);
  if (window < 1 || window > 30) return fmt::format("window = {} must be in 1..30", window);
  if (deletion_misses < 0 || deletion_misses > 100) return fmt::format("deletion_misses = {} must be in 0..100", deletion_misses);
  if (!(gate_probability > 0.0 && gate_probability < 1.0)) {
    return fmt::format("gate_probability = {} must be in (0, 1)", gate_probability);
  }
  if (!(confirm_llr > 0.0 && std::isfinite(confirm_llr))) return fmt::format("confirm_llr = {} must be finite and > 0", confirm_llr);
  for (auto [name, v] : {std::pair{"head_range", head_range}, {"head_range_rate", head_range_rate},
                         {"head_azimuth", head_azimuth}, {"head_bearing_rate_sd", head_bearing_rate_sd}}) {
    if (!(v > 0.0 && std::isfinite(v))) return fmt::format("{} = {} must be finite and > 0", name, v);
  }
  if (report_from != kFromHead && report_from != kFromConfirmation) {
    return fmt::format("report_from = {} must be 0 (head) or 1 (confirmation)", report_from);
  }
  if (assignment != kJoint && assignment != kPerPath) {
    return fmt::format("assignment = {} must be 0 (joint) or 1 (per_path)", assignment);
  }
  return {};
}

MdHmhtOptions MdHmhtOptions::resolved() const {
  MdHmhtOptions o = *this;
  if (literal) {
    o.alternative_heads = false;
    o.report_from = kFromConfirmation;
    o.assignment = kPerPath;
  }
  return o;
}

namespace {

using md_hmht::NodePtr;
using md_hmht::TrackNode;
using md_hmht::TrackPrediction;

struct Hypothesis {
  double score = 0.0;            // log-likelihood ratio, relative to the scan's best
  std::vector<NodePtr> live;     // by increasing track id
  std::vector<NodePtr> ended;    // deleted confirmed tracks
  std::vector<long> lineage;     // ids of its ancestors, parent first, at most `window`
  long id = 0;
};

// A child before selection: its parent, score, and the measurement of each (live track of the
// parent, path), −1 for none. Children are made parent by parent, each parent's best first.
struct Child {
  int parent = 0;
  double score = 0.0;
  std::vector<int> measurement_of;  // per (track, path) of the parent
};

class MdHmhtRun {
 public:
  // `options` resolved (MdHmhtOptions::resolved); `observer` may be null.
  MdHmhtRun(const MdHmhtOptions& options, const TrackingProblem& problem, const md_hmht::ScanObserver* observer)
      : options_(options), problem_(problem), observer_(observer), filter_(problem, options.gate_probability),
        paths_(filter_.paths()) {
    const bool dense = problem.clutter_mean > 200.0;
    hypotheses_kept_ = options_.hypotheses > 0 ? options_.hypotheses : (dense ? 2 : 3);
    miss_limit_ = options_.deletion_misses > 0 ? options_.deletion_misses : (dense ? 5 : 3);
    const int ny = problem.sensor->measurement_dim();
    heads_ = ground_head_options(problem.sensor->state_dim(), ny,
                                 {options_.head_range, options_.head_range_rate, options_.head_azimuth},
                                 options_.head_bearing_rate_sd, chi_square_quantile(options_.gate_probability, ny),
                                 options_.alternative_heads);
    hypotheses_.emplace_back();
  }

  void run(TrackSet& tracks) {
    for (int k = 0; k < problem_.scan_count(); ++k) step(k);
    output(tracks);
  }

 private:
  void step(int k) {
    const Eigen::MatrixXd& scan = problem_.scans[k];
    index_.build(scan);
    updates_.clear();
    predict_tracks(scan);
    std::vector<Child> children;
    for (int h = 0; h < static_cast<int>(hypotheses_.size()); ++h) rank_children(h, children);
    select(children);
    const std::vector<NodePtr> heads = start_heads(k);
    std::vector<Hypothesis> next;
    for (const Child& c : children) next.push_back(make_child(c, heads, k));
    hypotheses_ = std::move(next);
    const double best = hypotheses_.front().score;
    for (Hypothesis& h : hypotheses_) h.score -= best;
    if (observer_ != nullptr && *observer_) (*observer_)(k, snapshots());
  }

  // Every distinct live node of every hypothesis, predicted and gated once.
  void predict_tracks(const Eigen::MatrixXd& scan) {
    slot_.clear();
    int used = 0;
    for (const Hypothesis& h : hypotheses_) {
      for (const NodePtr& node : h.live) {
        if (!slot_.emplace(node->serial, used).second) continue;
        if (used == static_cast<int>(predictions_.size())) predictions_.emplace_back();
        filter_.predict(*node, scan, index_, predictions_[used++]);
      }
    }
  }

  const TrackPrediction& prediction(const NodePtr& node) const { return predictions_[slot_.at(node->serial)]; }

  // The parent's n best children (assignment = joint): one 2-D assignment over all its
  // pseudo-targets, Murty per cluster, lists merged.
  void rank_children(int parent, std::vector<Child>& children) {
    if (options_.assignment == MdHmhtOptions::kPerPath) {
      rank_children_per_path(parent, children);
      return;
    }
    const Hypothesis& h = hypotheses_[parent];
    const int tracks = static_cast<int>(h.live.size());
    // Rows: pseudo-targets (track, path) with a gated measurement; clusters by shared measurements.
    rows_.clear();
    row_arcs_.clear();
    double miss_sum = 0.0;
    for (int t = 0; t < tracks; ++t) {
      const TrackPrediction& p = prediction(h.live[t]);
      miss_sum += p.miss_log_sum;
      for (int tau = 0; tau < paths_; ++tau) add_row(t, tau, p.arcs[tau], nullptr);
    }
    rank_rows();
    for (int i = 0; i < static_cast<int>(totals_.size()); ++i) {
      Child child;
      child.parent = parent;
      child.score = h.score + miss_sum - totals_[i];
      child.measurement_of.assign(static_cast<std::size_t>(tracks) * paths_, -1);
      write_event(i, child.measurement_of.data());
      children.push_back(std::move(child));
    }
  }

  // The parent's children under assignment = per_path (header): for τ = 0, 1, ... each of the n
  // best partial events so far is extended by the n best 2-D assignments of the tracks' path-τ
  // pseudo-targets to the measurements it has not taken; the n best extensions go on.
  void rank_children_per_path(int parent, std::vector<Child>& children) {
    const Hypothesis& h = hypotheses_[parent];
    const int tracks = static_cast<int>(h.live.size());
    double miss_sum = 0.0;
    for (int t = 0; t < tracks; ++t) miss_sum += prediction(h.live[t]).miss_log_sum;
    partials_.assign(1, {0.0, std::vector<int>(static_cast<std::size_t>(tracks) * paths_, -1)});
    taken_.assign(index_.order.size(), 0);
    for (int tau = 0; tau < paths_; ++tau) {
      extended_.clear();
      for (const Partial& q : partials_) {
        for (int j : q.measurement_of)
          if (j >= 0) taken_[j] = 1;
        rows_.clear();
        row_arcs_.clear();
        for (int t = 0; t < tracks; ++t) add_row(t, tau, prediction(h.live[t]).arcs[tau], &taken_);
        for (int j : q.measurement_of)
          if (j >= 0) taken_[j] = 0;
        rank_rows();
        for (int i = 0; i < static_cast<int>(totals_.size()); ++i) {
          Partial e{q.cost + totals_[i], q.measurement_of};
          write_event(i, e.measurement_of.data());
          extended_.push_back(std::move(e));
        }
      }
      std::stable_sort(extended_.begin(), extended_.end(), [](const Partial& a, const Partial& b) { return a.cost < b.cost; });
      if (static_cast<int>(extended_.size()) > hypotheses_kept_) extended_.resize(hypotheses_kept_);
      partials_.swap(extended_);
    }
    for (Partial& q : partials_) children.push_back({parent, h.score + miss_sum - q.cost, std::move(q.measurement_of)});
  }

  // Appends the row (track t, path τ) if it gates a measurement not in `taken` (null: none taken).
  void add_row(int t, int tau, const std::vector<md_hmht::Arc>& arcs, const std::vector<char>* taken) {
    const int begin = static_cast<int>(row_arcs_.size());
    for (const md_hmht::Arc& arc : arcs)
      if (taken == nullptr || !(*taken)[arc.measurement]) row_arcs_.push_back(arc);
    const int end = static_cast<int>(row_arcs_.size());
    if (end > begin) rows_.push_back({t, tau, begin, end});
  }

  std::span<const md_hmht::Arc> arcs(int row) const {
    const Row& r = rows_[row];
    return {row_arcs_.data() + r.begin, static_cast<std::size_t>(r.end - r.begin)};
  }

  // The n best events of rows_: clusters, Murty per cluster, lists merged into totals_ (the
  // events' costs, ascending) and choices_ (per event, the index chosen in each cluster's list).
  void rank_rows() {
    cluster_rows();
    const int clusters = static_cast<int>(cluster_rows_.size());
    if (static_cast<int>(lists_.size()) < clusters) lists_.resize(clusters);
    spans_.clear();
    for (int c = 0; c < clusters; ++c) {
      rank_cluster(c);
      spans_.push_back(lists_[c].costs());
    }
    merge_.merge(spans_, hypotheses_kept_, totals_, choices_);
  }

  // Writes event i of rank_rows into measurement[track · paths + path] (rows it leaves out untouched).
  void write_event(int i, int* measurement) const {
    const int clusters = static_cast<int>(cluster_rows_.size());
    for (int c = 0; c < clusters; ++c) {
      const auto columns = lists_[c].columns(choices_[static_cast<std::size_t>(i) * clusters + c]);
      for (int r = 0; r < static_cast<int>(columns.size()); ++r) {
        if (columns[r] < 0) continue;
        const Row& row = rows_[cluster_rows_[c][r]];
        measurement[static_cast<std::size_t>(row.track) * paths_ + row.path] = cluster_columns_[c][columns[r]];
      }
    }
  }

  // Union-find over rows sharing a measurement; clusters in order of their first row.
  void cluster_rows() {
    const int rows = static_cast<int>(rows_.size());
    root_.resize(rows);
    std::iota(root_.begin(), root_.end(), 0);
    const auto find = [&](int r) {
      while (root_[r] != r) r = root_[r] = root_[root_[r]];
      return r;
    };
    owner_.assign(index_.order.size(), -1);
    for (int r = 0; r < rows; ++r) {
      for (const md_hmht::Arc& arc : arcs(r)) {
        int& owner = owner_[arc.measurement];
        if (owner < 0) owner = r;
        else {
          const int a = find(owner), b = find(r);
          if (a != b) root_[std::max(a, b)] = std::min(a, b);
        }
      }
    }
    cluster_rows_.clear();
    cluster_of_root_.assign(rows, -1);
    for (int r = 0; r < rows; ++r) {
      int& c = cluster_of_root_[find(r)];
      if (c < 0) {
        c = static_cast<int>(cluster_rows_.size());
        cluster_rows_.emplace_back();
      }
      cluster_rows_[c].push_back(r);
    }
    cluster_columns_.resize(cluster_rows_.size());
    for (std::size_t c = 0; c < cluster_rows_.size(); ++c) {
      auto& columns = cluster_columns_[c];
      columns.clear();
      for (int r : cluster_rows_[c])
        for (const md_hmht::Arc& arc : arcs(r)) columns.push_back(arc.measurement);
      std::sort(columns.begin(), columns.end());
      columns.erase(std::unique(columns.begin(), columns.end()), columns.end());
    }
  }

  void rank_cluster(int c) {
    const auto& rows = cluster_rows_[c];
    const auto& columns = cluster_columns_[c];
    const int R = static_cast<int>(rows.size()), C = static_cast<int>(columns.size());
    cost_.assign(static_cast<std::size_t>(R) * C, std::numeric_limits<double>::infinity());
    miss_.assign(R, 0.0);  // costs are relative to the miss (ψ's denominator)
    for (int r = 0; r < R; ++r) {
      for (const md_hmht::Arc& arc : arcs(rows[r])) {
        const int column = static_cast<int>(std::lower_bound(columns.begin(), columns.end(), arc.measurement) - columns.begin());
        cost_[static_cast<std::size_t>(r) * C + column] = arc.cost;
      }
    }
    murty_.solve(cost_.data(), miss_.data(), R, C, hypotheses_kept_, lists_[c]);
  }

  // Reading A keeps the n best children overall, B every parent's n best (ties in order of
  // making); then N-scan pruning keeps the children that share the best child's ancestor
  // `window` scans back.
  void select(std::vector<Child>& children) const {
    std::stable_sort(children.begin(), children.end(), [](const Child& a, const Child& b) { return a.score > b.score; });
    if (!options_.per_parent && static_cast<int>(children.size()) > hypotheses_kept_) children.resize(hypotheses_kept_);
    const auto ancestor = [&](const Child& c) -> long {  // the ancestor at scan k − window, −1 if none
      if (options_.window == 1) return hypotheses_[c.parent].id;
      const auto& lineage = hypotheses_[c.parent].lineage;
      return static_cast<int>(lineage.size()) >= options_.window - 1 ? lineage[options_.window - 2] : -1;
    };
    const long anchor = ancestor(children.front());
    std::erase_if(children, [&](const Child& c) { return ancestor(c) != anchor; });
  }

  // Tentative tracks from the measurements outside every gate of every hypothesis' tracks.
  std::vector<NodePtr> start_heads(int k) {
    const Eigen::MatrixXd& scan = problem_.scans[k];
    std::vector<char> gated(scan.cols(), 0);
    for (const auto& [serial, slot] : slot_)
      for (const auto& arcs : predictions_[slot].arcs)
        for (const md_hmht::Arc& arc : arcs) gated[arc.measurement] = 1;
    std::vector<int> candidates;
    for (int j = 0; j < static_cast<int>(scan.cols()); ++j)
      if (!gated[j]) candidates.push_back(j);
    std::vector<NodePtr> heads;
    std::map<std::vector<int>, long> family_of_members;
    for (TrackHead& head : form_track_heads(scan, candidates, *problem_.sensor, heads_)) {
      TrackNode node;
      node.serial = node.track = next_serial_++;
      std::vector<int> members = head.members;
      std::sort(members.begin(), members.end());
      node.family = family_of_members.emplace(std::move(members), node.serial).first->second;
      node.first_scan = node.scan = node.last_hit_scan = k;
      node.estimate = {std::move(head.mean), std::move(head.covariance)};
      heads.push_back(std::make_shared<const TrackNode>(std::move(node)));
    }
    return heads;
  }

  Hypothesis make_child(const Child& c, const std::vector<NodePtr>& heads, int k) {
    const Hypothesis& parent = hypotheses_[c.parent];
    Hypothesis child;
    child.id = next_hypothesis_++;
    child.score = c.score;
    child.ended = parent.ended;
    child.lineage.push_back(parent.id);
    for (std::size_t i = 0; i + 1 < static_cast<std::size_t>(options_.window) && i < parent.lineage.size(); ++i) {
      child.lineage.push_back(parent.lineage[i]);
    }
    for (std::size_t t = 0; t < parent.live.size(); ++t) {
      const NodePtr next = updated(parent.live[t], &c.measurement_of[t * paths_], k);
      if (next->empty_gates < miss_limit_) child.live.push_back(next);
      else if (next->confirmed()) child.ended.push_back(next);
    }
    keep_one_reading(child.live);
    child.live.insert(child.live.end(), heads.begin(), heads.end());
    return child;
  }

  // Once readings of one return group are confirmed, the confirmed one with the largest LLR
  // (then the oldest) stays and its siblings go.
  static void keep_one_reading(std::vector<NodePtr>& live) {
    std::map<long, const TrackNode*> kept;  // family → its surviving confirmed reading
    for (const NodePtr& node : live) {
      if (!node->confirmed()) continue;
      const auto [it, inserted] = kept.emplace(node->family, node.get());
      if (!inserted && node->llr > it->second->llr) it->second = node.get();
    }
    std::erase_if(live, [&](const NodePtr& node) {
      const auto it = kept.find(node->family);
      return it != kept.end() && it->second != node.get();
    });
  }

  // A node updated with one child's assignment, shared with every child that assigns the same.
  NodePtr updated(const NodePtr& node, const int* measurement_of_path, int k) {
    auto [it, inserted] = updates_.try_emplace({node->serial, std::vector<int>(measurement_of_path, measurement_of_path + paths_)});
    if (!inserted) return it->second;
    TrackNode next = filter_.update(node, prediction(node), measurement_of_path, problem_.scans[k], k, next_serial_++);
    if (!next.confirmed() && next.llr >= options_.confirm_llr) next.confirmed_scan = k;
    it->second = std::make_shared<const TrackNode>(std::move(next));
    return it->second;
  }

  void output(TrackSet& tracks) const {
    tracks.tracks.clear();
    const Hypothesis& best = hypotheses_.front();
    std::vector<NodePtr> ends;
    for (const NodePtr& node : best.live)
      if (node->confirmed()) ends.push_back(node);
    ends.insert(ends.end(), best.ended.begin(), best.ended.end());
    std::sort(ends.begin(), ends.end(), [](const NodePtr& a, const NodePtr& b) { return a->track < b->track; });
    const int last_scan = problem_.scan_count() - 1;
    for (const NodePtr& end : ends) {
      // A deleted track ends at its last assigned measurement; a live one at the last scan. It
      // starts at its head, or at its confirmation (a scan with an assigned measurement: only
      // those raise the LLR, so first ≤ last).
      const int last = end->scan == last_scan && end->empty_gates < miss_limit_ ? last_scan : end->last_hit_scan;
      const int first = options_.report_from == MdHmhtOptions::kFromConfirmation ? end->confirmed_scan : end->first_scan;
      Track track;
      track.id = static_cast<int>(end->track);
      track.first_scan = first;
      track.confirmed = true;
      const int n = static_cast<int>(end->estimate.mean.size()), length = last - first + 1;
      track.states.resize(n, length);
      track.covariance_diagonals.resize(n, length);
      for (const TrackNode* node = end.get(); node != nullptr && node->scan >= first; node = node->previous.get()) {
        if (node->scan > last) continue;
        track.states.col(node->scan - first) = node->estimate.mean;
        track.covariance_diagonals.col(node->scan - first) = node->estimate.covariance.diagonal();
      }
      tracks.tracks.push_back(std::move(track));
    }
  }

  // The scan's hypotheses as the tests see them (md_hmht::run_observed).
  std::vector<md_hmht::HypothesisSnapshot> snapshots() const {
    const auto history = [](const NodePtr& end) {
      md_hmht::TrackHistory t{end->track, end->first_scan, end->confirmed_scan, end->llr, end->empty_gates, {}};
      for (const TrackNode* node = end.get(); node->scan > node->first_scan; node = node->previous.get()) {
        t.assigned.push_back(node->assigned);
      }
      std::reverse(t.assigned.begin(), t.assigned.end());
      return t;
    };
    std::vector<md_hmht::HypothesisSnapshot> out;
    for (const Hypothesis& h : hypotheses_) {
      md_hmht::HypothesisSnapshot& snapshot = out.emplace_back();
      snapshot.score = h.score;
      for (const NodePtr& node : h.live) snapshot.live.push_back(history(node));
      for (const NodePtr& node : h.ended) snapshot.ended.push_back(history(node));
    }
    return out;
  }

  struct Row {
    int track;  // index in the parent's live list
    int path;
    int begin, end;  // its arcs: row_arcs_[begin, end)
  };
  struct Partial {  // assignment = per_path: an event over the paths so far
    double cost;    // Σ c_pj of its pairs
    std::vector<int> measurement_of;  // per (track, path) of the parent, −1 none
  };

  const MdHmhtOptions& options_;
  const TrackingProblem& problem_;
  const md_hmht::ScanObserver* observer_;
  md_hmht::TrackFilter filter_;
  const int paths_;
  int hypotheses_kept_ = 3;  // N: hypotheses kept per scan (per parent with per_parent)
  int miss_limit_ = 3;       // scans without a measurement before a track is deleted
  TrackHeadOptions heads_;
  std::vector<Hypothesis> hypotheses_;
  long next_serial_ = 1, next_hypothesis_ = 1;
  ScanIndex index_;
  std::unordered_map<long, int> slot_;  // node serial → its prediction this scan
  std::vector<TrackPrediction> predictions_;
  std::map<std::pair<long, std::vector<int>>, NodePtr> updates_;  // (node serial, assignment) → this scan's update
  // Per-parent workspace.
  std::vector<Row> rows_;
  std::vector<md_hmht::Arc> row_arcs_;
  std::vector<Partial> partials_, extended_;
  std::vector<char> taken_;  // per measurement: taken by the partial event being extended
  std::vector<int> root_, owner_, cluster_of_root_;
  std::vector<std::vector<int>> cluster_rows_, cluster_columns_;
  std::vector<double> cost_, miss_, totals_;
  std::vector<int> choices_;
  std::vector<RankedAssignments> lists_;
  std::vector<std::span<const double>> spans_;
  MurtyRanking murty_;
  RankedListMerge merge_;
};

void check_md_hmht_problem(const TrackingProblem& problem) {
  const MultipathMeasurementModel& sensor = *problem.sensor;
  if (sensor.state_dim() != 4 || sensor.measurement_dim() != md_hmht::TrackFilter::kDim) {
    throw InputError("md-hmht: needs ground states [g, g', theta, theta'] and slant measurements [r, r', zeta]");
  }
  if (static_cast<int>(problem.detection_probability.size()) != sensor.paths()) {
    throw InputError("md-hmht: one detection probability per path is needed");
  }
  for (double pd : problem.detection_probability) {
    if (!(pd > 0.0 && pd <= 1.0)) throw InputError(fmt::format("md-hmht: detection probability {} not in (0, 1]", pd));
  }
  if (!(problem.region_volume() > 0.0)) throw InputError("md-hmht: the surveillance region has no volume");
  for (const Eigen::MatrixXd& scan : problem.scans) {
    if (scan.cols() > 0 && scan.rows() != sensor.measurement_dim()) {
      throw InputError("md-hmht: scans must have one row per measurement component");
    }
    if (!scan.allFinite()) throw InputError("md-hmht: a measurement is not finite");
  }
}

}  // namespace

void MdHmhtTracker::run(const TrackingProblem& problem, TrackSet& tracks, SolveReport& report) {
  report.reset();
  if (!problem.sensor) {
    report.skipped = "problem_without_multipath_sensor";
    return;
  }
  check_md_hmht_problem(problem);
  try {
    MdHmhtRun(options_, problem, nullptr).run(tracks);
  } catch (const UnscentedFailure& failure) {  // a covariance lost positive definiteness: no tracks
    tracks.tracks.clear();
    report.skipped = std::string("failed:") + failure.what();
  }
}

DABENCH_REGISTER_TRACKING_TRACKER(MdHmhtTracker);

void md_hmht::run_observed(const MdHmhtOptions& options, const TrackingProblem& problem, TrackSet& tracks,
                           const ScanObserver& observer) {
  if (std::string why = options.validate(); !why.empty()) throw InputError("md-hmht: " + why);
  if (!problem.sensor) throw InputError("md-hmht: the problem has no multipath sensor");
  check_md_hmht_problem(problem);
  const MdHmhtOptions resolved = options.resolved();
  MdHmhtRun(resolved, problem, &observer).run(tracks);
}

}  // namespace dabench

#include "algorithms/tracking/track_heads.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Cholesky>

namespace dabench {

namespace {

bool within(const Eigen::MatrixXd& scan, int a, int b, const Vector& threshold) {
  return ((scan.col(a) - scan.col(b)).cwiseAbs().array() <= threshold.array()).all();
}

// The group seeded by pool[0] (pool sorted by first component): in order, every later
// candidate within `threshold` of all members so far, up to max_members.
std::vector<int> group_from_first(const Eigen::MatrixXd& scan, const std::vector<int>& pool, const Vector& threshold,
                                  int max_members) {
  std::vector<int> group{pool[0]};
  for (std::size_t t = 1; t < pool.size() && static_cast<int>(group.size()) < max_members; ++t) {
    if (scan(0, pool[t]) - scan(0, pool[0]) > threshold[0]) break;
    if (std::all_of(group.begin(), group.end(), [&](int m) { return within(scan, m, pool[t], threshold); }))
      group.push_back(pool[t]);
  }
  return group;
}

// Member j mapped to the ground on path τ: x_j and I_j = H_jᵀ R⁻¹ H_j (valid = false: no inverse).
struct Mapped {
  bool valid = false;
  Vector state;
  Eigen::MatrixXd information;
};

struct HeadHypothesis {
  int members = 0;
  double mean_distance = std::numeric_limits<double>::infinity();
  std::vector<int> path_of;  // per group member: its path, or −1 when left out
  Vector mean;
  Eigen::MatrixXd covariance;

  bool better_than(const HeadHypothesis& other) const {
    return members > other.members || (members == other.members && mean_distance < other.mean_distance);
  }
};

// Depth-first over the group: each member is left out or takes a path no other member has.
class HypothesisSearch {
 public:
  HypothesisSearch(const std::vector<std::vector<Mapped>>& mapped, const Vector& prior_precision, double gate)
      : mapped_(mapped), prior_(prior_precision), gate_(gate), path_of_(mapped.size(), -1),
        used_(mapped.empty() ? 0 : mapped[0].size(), 0) {}

  // The best consistent hypothesis over the available members.
  HeadHypothesis best(const std::vector<char>& available) {
    available_ = &available;
    best_ = {};
    required_ = 2;
    collect_ = nullptr;
    visit(0, 0);
    return best_;
  }

  // Every consistent hypothesis that assigns all the available members (their path-shifted
  // alternatives: e.g. two members 32 km apart in slant range fit EE+FE and EF+FF alike).
  std::vector<HeadHypothesis> all_using(const std::vector<char>& available) {
    available_ = &available;
    std::vector<HeadHypothesis> found;
    collect_ = &found;
    required_ = static_cast<int>(std::count(available.begin(), available.end(), 1));
    visit(0, 0);
    collect_ = nullptr;
    return found;
  }

 private:
  void visit(std::size_t member, int assigned) {
    if (member == mapped_.size()) {
      if (assigned >= required_) evaluate(assigned);
      return;
    }
    visit(member + 1, assigned);  // left out
    if (!(*available_)[member]) return;
    for (std::size_t tau = 0; tau < used_.size(); ++tau) {
      if (used_[tau] || !mapped_[member][tau].valid) continue;
      used_[tau] = 1;
      path_of_[member] = static_cast<int>(tau);
      visit(member + 1, assigned + 1);
      path_of_[member] = -1;
      used_[tau] = 0;
    }
  }

  // Fuses the assigned members; kept when every member lies within the gate of the fused state.
  void evaluate(int assigned) {
    const int n = static_cast<int>(prior_.size());
    Eigen::MatrixXd total = prior_.asDiagonal();
    Vector weighted = Vector::Zero(n), average = Vector::Zero(n);
    for (std::size_t j = 0; j < mapped_.size(); ++j) {
      if (path_of_[j] < 0) continue;
      const Mapped& m = mapped_[j][path_of_[j]];
      total += m.information;
      weighted += m.information * m.state;
      average += m.state / assigned;
    }
    const Eigen::LLT<Eigen::MatrixXd> llt(total);
    if (llt.info() != Eigen::Success) return;
    HeadHypothesis h;
    h.members = assigned;
    h.mean = llt.solve(weighted + prior_.asDiagonal() * average);
    double distance = 0.0;
    for (std::size_t j = 0; j < mapped_.size(); ++j) {
      if (path_of_[j] < 0) continue;
      const Mapped& m = mapped_[j][path_of_[j]];
      const Vector d = m.state - h.mean;
      const double dj = d.dot(m.information * d);
      if (dj > gate_) return;
      distance += dj;
    }
    h.mean_distance = distance / assigned;
    if (!collect_ && !h.better_than(best_)) return;
    h.path_of = path_of_;
    h.covariance = llt.solve(Eigen::MatrixXd::Identity(n, n));
    if (collect_) collect_->push_back(std::move(h));
    else best_ = std::move(h);
  }

  const std::vector<std::vector<Mapped>>& mapped_;
  const Vector& prior_;
  const double gate_;
  std::vector<int> path_of_;
  std::vector<char> used_;
  const std::vector<char>* available_ = nullptr;
  int required_ = 2;                          // fewest assigned members of a hypothesis
  std::vector<HeadHypothesis>* collect_ = nullptr;  // all_using(): where hypotheses go
  HeadHypothesis best_;
};

// Keeps one of the alternatives whose states are within `gate` of each other (EF and FE,
// whose slant ranges differ by ~0.1 km, give nearly the same state).
bool distinct(const HeadHypothesis& h, const std::vector<HeadHypothesis>& kept, double gate) {
  return std::none_of(kept.begin(), kept.end(), [&](const HeadHypothesis& k) {
    const Vector d = h.mean - k.mean;
    return d.dot(k.covariance.llt().solve(d)) <= gate;
  });
}

TrackHead make_head(const HeadHypothesis& h, const std::vector<int>& group, int paths) {
  TrackHead head{h.mean, h.covariance, 0.0, {}, {}};
  for (std::size_t j = 0; j < group.size(); ++j) {
    if (h.path_of[j] < 0) continue;
    head.members.push_back(group[j]);
    head.paths.push_back(h.path_of[j]);
  }
  const double share = static_cast<double>(h.members) / paths;
  head.initial_active = std::min(1.0, share * share);
  return head;
}

}  // namespace

std::vector<TrackHead> form_track_heads(const Eigen::MatrixXd& scan, const std::vector<int>& candidates,
                                        const MultipathMeasurementModel& sensor, const TrackHeadOptions& options) {
  std::vector<TrackHead> heads;
  const int paths = sensor.paths();
  std::vector<int> pool = candidates;
  std::sort(pool.begin(), pool.end(), [&](int a, int b) { return scan(0, a) < scan(0, b) || (scan(0, a) == scan(0, b) && a < b); });
  std::vector<char> leaves(scan.cols(), 0);  // per measurement: taken out of the pool
  while (!pool.empty()) {
    const std::vector<int> group = group_from_first(scan, pool, options.threshold, 2 * paths);
    bool started = false;
    if (group.size() >= 2) {  // a lone seed can start nothing: skip mapping it to the ground
      std::vector<std::vector<Mapped>> mapped(group.size(), std::vector<Mapped>(paths));
      for (std::size_t j = 0; j < group.size(); ++j) {
        for (int tau = 0; tau < paths; ++tau) {
          Mapped& m = mapped[j][tau];
          m.valid = sensor.invert(tau, scan.col(group[j]), m.state);
          if (!m.valid) continue;
          const Eigen::MatrixXd h = sensor.jacobian(tau, m.state);
          m.information = h.transpose() * sensor.noise_covariance(tau).llt().solve(h);
        }
      }
      HypothesisSearch search(mapped, options.prior_precision, options.gate);
      const HeadHypothesis best = search.best(std::vector<char>(group.size(), 1));
      if (best.members >= 2) {
        started = true;
        std::vector<char> members(group.size(), 0);
        for (std::size_t j = 0; j < group.size(); ++j) members[j] = best.path_of[j] >= 0;
        if (options.alternative_heads) {
          std::vector<HeadHypothesis> kept;
          for (HeadHypothesis& h : search.all_using(members))
            if (distinct(h, kept, options.gate)) kept.push_back(std::move(h));
          for (const HeadHypothesis& h : kept) heads.push_back(make_head(h, group, paths));
        } else {
          heads.push_back(make_head(best, group, paths));
        }
        for (std::size_t j = 0; j < group.size(); ++j)
          if (members[j]) leaves[group[j]] = 1;
      }
    }
    if (!started) leaves[group[0]] = 1;  // the seed starts no head; its neighbours may with others
    pool.erase(std::remove_if(pool.begin(), pool.end(), [&](int j) { return leaves[j] != 0; }), pool.end());
  }
  return heads;
}

TrackHeadOptions ground_head_options(int state_dim, int measurement_dim, const Eigen::Vector3d& threshold,
                                     double bearing_rate_sd, double gate, bool alternative_heads) {
  TrackHeadOptions o;
  o.threshold = Vector::Zero(measurement_dim);
  o.threshold.head(3) = threshold;
  o.prior_precision = Vector::Constant(state_dim, 1e-6);
  if (state_dim == 4) o.prior_precision << 1e-6, 1.0, 1.0, 1.0 / (bearing_rate_sd * bearing_rate_sd);
  o.gate = gate;
  o.alternative_heads = alternative_heads;
  return o;
}

}  // namespace dabench

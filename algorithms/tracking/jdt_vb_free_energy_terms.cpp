// The terms of JDT-VB's free energy B (algorithms/tracking/jdt_vb_free_energy_terms.hpp).
#include "algorithms/tracking/jdt_vb_free_energy_terms.hpp"
#include "harness/core/special_values.hpp"

#include <cmath>
#include <numbers>

namespace dabench {
namespace {


double xlogx(double p) { return p > 0.0 ? p * std::log(p) : 0.0; }

double log_det(const Eigen::LLT<Eigen::MatrixXd>& llt) { return 2.0 * llt.matrixLLT().diagonal().array().log().sum(); }

}  // namespace

double clutter_energy(const Vector& clutter, int ungated, double log_clutter_density) {
  return (clutter.sum() + ungated) * log_clutter_density;
}

double bethe_entropy(const MultipathAssociation& q, const std::vector<std::vector<int>>& gated_columns) {
  double h = 0.0;
  for (int p = 0; p < static_cast<int>(q.miss.size()); ++p) h -= xlogx(q.miss[p]);
  for (int c = 0; c < static_cast<int>(q.clutter.size()); ++c) h -= xlogx(q.clutter[c]);
  for (int p = 0; p < static_cast<int>(gated_columns.size()); ++p)
    for (int c : gated_columns[p]) {
      const double b = q.detection(p, c);
      h -= 2.0 * xlogx(b);             // in its row and in its column
      h += xlogx(b) + xlogx(1.0 - b);  // minus its binary entropy
    }
  return h;
}

LinearisedLogLikelihood::LinearisedLogLikelihood(const Eigen::LLT<Eigen::MatrixXd>& noise, const Vector& predicted,
                                                 const Eigen::MatrixXd& jacobian, const Eigen::MatrixXd& covariance)
    : noise_(noise), predicted_(predicted),
      constant_(-0.5 * (static_cast<double>(predicted.size()) * kLog2Pi + log_det(noise) +
                        noise.solve(jacobian * covariance * jacobian.transpose()).trace())) {}

double LinearisedLogLikelihood::operator()(const Vector& y) const {
  const Vector d = y - predicted_;
  return constant_ - 0.5 * d.dot(noise_.solve(d));
}

double add_gauss_markov_energy(double sum, const GaussMarkovChain& q, const GaussMarkovPrior& prior) {
  const auto& marginal = q.marginal;
  const Eigen::MatrixXd& f = prior.transition;
  const int n = static_cast<int>(f.rows());
  const Eigen::LLT<Eigen::MatrixXd> head(prior.head.covariance);
  const Vector d0 = marginal[0].mean - prior.head.mean;
  sum -= 0.5 * (head.solve(marginal[0].covariance).trace() + d0.dot(head.solve(d0)) + n * kLog2Pi + log_det(head));
  const double entropy_constant = 0.5 * n * (1.0 + kLog2Pi);
  for (std::size_t k = 0; k + 1 < marginal.size(); ++k) {
    const Gaussian& now = marginal[k];
    const Gaussian& next = marginal[k + 1];
    const Eigen::MatrixXd& c = q.coupling[k];
    const Eigen::LLT<Eigen::MatrixXd> conditional(now.covariance - c * next.covariance.llt().solve(c.transpose()));
    if (conditional.info() != Eigen::Success) return -HUGE_VAL;
    const Vector d = next.mean - f * now.mean;
    const Eigen::MatrixXd fc = f * c;
    const Eigen::MatrixXd second = next.covariance - fc.transpose() - fc + f * now.covariance * f.transpose() + d * d.transpose();
    sum -= 0.5 * (prior.process.solve(second).trace() + n * kLog2Pi + log_det(prior.process));
    sum += entropy_constant + 0.5 * log_det(conditional);
  }
  sum += entropy_constant + 0.5 * log_det(Eigen::LLT<Eigen::MatrixXd>(marginal.back().covariance));
  return sum;
}

double meta_state_energy(const MetaStateChain& q, const std::vector<std::array<double, 2>>& evidence,
                         double initial_active, double stay) {
  const double log_stay = std::log(stay), log_move = std::log1p(-stay);
  double b = 0.0;
  const double a0 = q.active[0];
  if (a0 > 0.0) b += a0 * std::log(initial_active);
  if (a0 < 1.0) b += (1.0 - a0) * std::log1p(-initial_active);
  for (std::size_t k = 0; k < q.active.size(); ++k) b += q.active[k] * evidence[k][1] + (1.0 - q.active[k]) * evidence[k][0];
  for (std::size_t k = 0; k + 1 < q.active.size(); ++k) {
    const auto& pair = q.pairwise[k];
    b += (pair[0] + pair[3]) * log_stay + (pair[1] + pair[2]) * log_move;
    for (double v : pair) b -= xlogx(v);
    if (k > 0) b += xlogx(q.active[k]) + xlogx(1.0 - q.active[k]);
  }
  if (q.active.size() == 1) b -= xlogx(a0) + xlogx(1.0 - a0);
  return b;
}

}  // namespace dabench

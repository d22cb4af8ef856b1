#include "algorithms/multipath_association.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "harness/errors.hpp"

namespace dabench {

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

// log(e^{slack} + Σ_{k≠skip} e^{values_k}) about its largest term; −∞ if every term is 0.
template <class Values>
double log_sum_without(const Values& values, Eigen::Index skip, double slack) {
  double largest = slack;
  for (Eigen::Index k = 0; k < values.size(); ++k) {
    if (k != skip) largest = std::max(largest, values[k]);
  }
  if (largest == -kInfinity) return -kInfinity;
  double sum = std::exp(slack - largest);
  for (Eigen::Index k = 0; k < values.size(); ++k) {
    if (k != skip) sum += std::exp(values[k] - largest);
  }
  return largest + std::log(sum);
}

// 1 / (1 + e^{−log_odds}): a binary variable's belief from its log odds.
double belief_of(double log_odds) { return 1.0 / (1.0 + std::exp(-log_odds)); }

}  // namespace

std::string MultipathEvidence::validate() const {
  if (targets < 0 || paths < 1) return fmt::format("multipath evidence: {} targets and {} paths", targets, paths);
  const int rows = pseudo_targets();
  if (detection.rows() != rows || miss.size() != rows) {
    return fmt::format("multipath evidence: {} detection rows and {} miss entries, expected {} (targets x paths)",
                       detection.rows(), miss.size(), rows);
  }
  if (clutter.size() != detection.cols()) {
    return fmt::format("multipath evidence: {} clutter entries for {} measurements", clutter.size(), detection.cols());
  }
  if (detection.unaryExpr([](double chi) { return std::isnan(chi) || chi == kInfinity; }).any()) {
    return "multipath evidence: a detection evidence chi(i,j,tau) is NaN or +inf";
  }
  if (!miss.allFinite() || !clutter.allFinite()) {
    return "multipath evidence: a miss or clutter evidence chi is not finite";
  }
  return {};
}

std::string MultipathAssociationOptions::validate() const {
  if (!(tolerance > 0.0)) return "tolerance must be > 0";
  if (max_iterations < 1) return "max_iterations must be >= 1";
  return {};
}

double MultipathAssociationBp::row_step(const MultipathEvidence& evidence) {
  double change = 0.0;
  for (Eigen::Index p = 0; p < evidence.pseudo_targets(); ++p) {
    auto out = outgoing_.row(p);
    out = evidence.detection.row(p) + column_message_.row(p) + page_message_.row(p);  // ν^R (51)
    // Σ e^ν about the largest term (the miss term included); gated ν = −∞ add nothing.
    Eigen::Index top = 0;
    double largest = out.maxCoeff(&top);
    if (evidence.miss[p] >= largest) {
      largest = evidence.miss[p];
      top = -1;
    }
    auto terms = terms_.row(p);
    terms = (out.array() - largest).exp();
    const double total = terms.sum() + std::exp(evidence.miss[p] - largest);
    auto updated = updated_.row(p);
    updated = -(largest + (total - terms.array()).log());  // (48), the largest term left in
    if (top >= 0) updated[top] = -log_sum_without(out, top, evidence.miss[p]);
    change = std::max(change, (updated - row_message_.row(p)).cwiseAbs().maxCoeff());
  }
  row_message_.swap(updated_);
  return change;
}
double MultipathAssociationBp::column_step(const MultipathEvidence& evidence) {
  const Eigen::Index rows = evidence.pseudo_targets(), columns = evidence.measurements();
  outgoing_ = evidence.detection + row_message_ + page_message_;  // ν^C (52)
  // Per measurement: Σ e^ν about the largest term (the clutter term included).
  largest_ = evidence.clutter.transpose();
  top_.setConstant(columns, -1);
  for (Eigen::Index p = 0; p < rows; ++p) {
    for (Eigen::Index j = 0; j < columns; ++j) {
      if (outgoing_(p, j) > largest_[j]) {
        largest_[j] = outgoing_(p, j);
        top_[j] = static_cast<int>(p);
      }
    }
  }
  terms_ = (outgoing_.rowwise() - largest_).array().exp();
  total_ = terms_.colwise().sum() + (evidence.clutter.transpose() - largest_).array().exp().matrix();
  updated_ = -(((-terms_).rowwise() + total_).array().log().matrix().rowwise() + largest_);  // (49)
  for (Eigen::Index j = 0; j < columns; ++j) {
    if (top_[j] >= 0) updated_(top_[j], j) = -log_sum_without(outgoing_.col(j), top_[j], evidence.clutter[j]);
  }
  const double change = (updated_ - column_message_).cwiseAbs().maxCoeff();
  column_message_.swap(updated_);
  return change;
}

double MultipathAssociationBp::page_step(const MultipathEvidence& evidence) {
  const int paths = evidence.paths;
  outgoing_ = evidence.detection + row_message_ + column_message_;  // ν^P (53)
  double change = 0.0;
  for (int first = 0; first < evidence.pseudo_targets(); first += paths) {  // one target's paths
    for (Eigen::Index j = 0; j < evidence.measurements(); ++j) {
      const auto group = outgoing_.col(j).segment(first, paths);
      for (int tau = 0; tau < paths; ++tau) {
        // (50) as "at most one": the slack is the all-zero configuration, log 1 = 0.
        const double updated = -log_sum_without(group, tau, 0.0);
        change = std::max(change, std::abs(updated - page_message_(first + tau, j)));
        page_message_(first + tau, j) = updated;
      }
    }
  }
  return change;
}

void MultipathAssociationBp::solve(const MultipathEvidence& evidence, const MultipathAssociationOptions& options,
                                   MultipathAssociation& result) {
  if (const std::string error = evidence.validate(); !error.empty()) throw InputError(error);
  if (const std::string error = options.validate(); !error.empty()) throw InputError("multipath association: " + error);
  const int rows = evidence.pseudo_targets(), columns = evidence.measurements();
  row_message_.setZero(rows, columns);  // (47): messages start from the evidence alone
  column_message_.setZero(rows, columns);
  page_message_.setZero(rows, columns);
  outgoing_.resize(rows, columns);
  terms_.resize(rows, columns);
  updated_.resize(rows, columns);
  result.converged = rows == 0 || columns == 0;  // nothing to associate
  result.iterations = 0;
  while (!result.converged && result.iterations < options.max_iterations) {
    ++result.iterations;
    double change = row_step(evidence);
    change = std::max(change, column_step(evidence));
    if (options.page_factor && evidence.paths > 1) change = std::max(change, page_step(evidence));
    result.converged = change < options.tolerance;
  }
  // Beliefs (54)-(55); gated-out variables are exactly 0.
  result.detection.resize(rows, columns);
  for (int p = 0; p < rows; ++p) {
    for (int j = 0; j < columns; ++j) {
      const double chi = evidence.detection(p, j);
      result.detection(p, j) =
          chi == -kInfinity ? 0.0 : belief_of(chi + row_message_(p, j) + column_message_(p, j) + page_message_(p, j));
    }
  }
  outgoing_ = evidence.detection + column_message_ + page_message_;  // ν^R
  result.miss.resize(rows);
  for (int p = 0; p < rows; ++p) {
    result.miss[p] = belief_of(evidence.miss[p] - log_sum_without(outgoing_.row(p), -1, -kInfinity));
  }
  outgoing_ = evidence.detection + row_message_ + page_message_;  // ν^C
  result.clutter.resize(columns);
  for (int j = 0; j < columns; ++j) {
    result.clutter[j] = belief_of(evidence.clutter[j] - log_sum_without(outgoing_.col(j), -1, -kInfinity));
  }
}

}  // namespace dabench

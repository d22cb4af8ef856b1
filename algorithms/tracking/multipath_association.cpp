#include "algorithms/tracking/multipath_association.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "harness/core/errors.hpp"
#include "harness/core/special_values.hpp"

namespace dabench {

namespace {

// 1 / (1 + e^{−log_odds}): a binary variable's belief from its log odds.
double belief_of(double log_odds) { return 1.0 / (1.0 + std::exp(-log_odds)); }

// log Σ_k e^{values_k} about its largest term; −∞ for no terms.
double log_sum(const double* values, int count) {
  if (count == 0) return -kInfinity;
  const double largest = *std::max_element(values, values + count);
  double sum = 0.0;
  for (int k = 0; k < count; ++k) sum += std::exp(values[k] - largest);
  return largest + std::log(sum);
}

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

void MultipathAssociationBp::build_graph(const MultipathEvidence& evidence, bool page_factor) {
  const int rows = evidence.pseudo_targets(), columns = evidence.measurements();
  pair_row_.clear();
  pair_column_.clear();
  pair_chi_.clear();
  rows_.start.assign(1, 0);
  rows_.pairs.clear();
  std::vector<int>& column_start = columns_.start;
  column_start.assign(columns + 1, 0);
  for (int p = 0; p < rows; ++p) {
    for (int j = 0; j < columns; ++j) {
      const double chi = evidence.detection(p, j);
      if (chi == -kInfinity) continue;  // outside the gate
      rows_.pairs.push_back(static_cast<int>(pair_chi_.size()));
      pair_row_.push_back(p);
      pair_column_.push_back(j);
      pair_chi_.push_back(chi);
      ++column_start[j + 1];
    }
    rows_.start.push_back(static_cast<int>(rows_.pairs.size()));
  }
  const int pairs = static_cast<int>(pair_chi_.size());
  // Columns by counting sort: within a column the pairs stay in row order.
  for (int j = 0; j < columns; ++j) column_start[j + 1] += column_start[j];
  columns_.pairs.resize(pairs);
  next_slot_.assign(column_start.begin(), column_start.end() - 1);
  for (int e = 0; e < pairs; ++e) columns_.pairs[next_slot_[pair_column_[e]]++] = e;
  // Pages: the pairs of one column that belong to the same target, when there are two or more
  // (a page factor over one variable sends the constant message log 1 = 0).
  pages_.start.assign(1, 0);
  pages_.pairs.clear();
  if (page_factor && evidence.paths > 1) {
    for (int j = 0; j < columns; ++j) {
      for (int k = column_start[j]; k < column_start[j + 1];) {
        const int target = pair_row_[columns_.pairs[k]] / evidence.paths;
        int end = k + 1;
        while (end < column_start[j + 1] && pair_row_[columns_.pairs[end]] / evidence.paths == target) ++end;
        if (end - k >= 2) {
          pages_.pairs.insert(pages_.pairs.end(), columns_.pairs.begin() + k, columns_.pairs.begin() + end);
          pages_.start.push_back(static_cast<int>(pages_.pairs.size()));
        }
        k = end;
      }
    }
  }
  row_message_.assign(pairs, 0.0);  // (47): messages start from the evidence alone
  column_message_.assign(pairs, 0.0);
  page_message_.assign(pairs, 0.0);
  int largest_factor = 0;
  for (const FactorIndex* index : {&rows_, &columns_, &pages_}) {
    for (std::size_t f = 0; f + 1 < index->start.size(); ++f) {
      largest_factor = std::max(largest_factor, index->start[f + 1] - index->start[f]);
    }
  }
  values_.resize(largest_factor);
  terms_.resize(largest_factor);
}

// Eqs (48)-(50) for every factor of one kind. A factor is "exactly one of its variables or its
// slack" (rows: the miss, columns: the clutter; pages: "at most one", slack log 1 = 0); the log
// ratio to variable k is −log(e^{slack} + Σ_{k'≠k} e^{ν_k'}), with ν_k' the variable's incoming
// log ratio from its other factors. Returns the largest change of a message.
double MultipathAssociationBp::update(Kind kind, const FactorIndex& index, const double* slack) {
  std::vector<double>& own = kind == Kind::row ? row_message_ : kind == Kind::column ? column_message_ : page_message_;
  double change = 0.0;
  for (std::size_t f = 0; f + 1 < index.start.size(); ++f) {
    const int* pairs = index.pairs.data() + index.start[f];
    const int count = index.start[f + 1] - index.start[f];
    if (count == 0) continue;
    const double slack_value = slack == nullptr ? 0.0 : slack[f];
    double largest = slack_value;
    int top = -1;
    for (int k = 0; k < count; ++k) {
      const int e = pairs[k];
      values_[k] = pair_chi_[e] + row_message_[e] + column_message_[e] + page_message_[e] - own[e];  // ν (51)-(53)
      if (values_[k] > largest) {
        largest = values_[k];
        top = k;
      }
    }
    double total = std::exp(slack_value - largest);
    for (int k = 0; k < count; ++k) {
      terms_[k] = std::exp(values_[k] - largest);
      total += terms_[k];
    }
    // Leaving out a term other than the largest keeps the largest's 1 in the sum: no cancellation.
    // The sum without the largest term is formed afresh about the second largest.
    double without_top = 0.0;
    if (top >= 0) {
      double second = slack_value;
      for (int k = 0; k < count; ++k) {
        if (k != top) second = std::max(second, values_[k]);
      }
      double sum = std::exp(slack_value - second);
      for (int k = 0; k < count; ++k) {
        if (k != top) sum += std::exp(values_[k] - second);
      }
      without_top = second + std::log(sum);
    }
    for (int k = 0; k < count; ++k) {
      const double updated = -(k == top ? without_top : largest + std::log(total - terms_[k]));
      double& message = own[pairs[k]];
      change = std::max(change, std::abs(updated - message));
      message = updated;
    }
  }
  return change;
}

void MultipathAssociationBp::solve(const MultipathEvidence& evidence, const MultipathAssociationOptions& options,
                                   MultipathAssociation& result) {
  if (const std::string error = evidence.validate(); !error.empty()) throw InputError(error);
  if (const std::string error = options.validate(); !error.empty()) throw InputError("multipath association: " + error);
  build_graph(evidence, options.page_factor);
  const int pairs = static_cast<int>(pair_chi_.size());
  result.iterations = 0;
  result.converged = pairs == 0;  // nothing to associate
  while (!result.converged && result.iterations < options.max_iterations) {
    ++result.iterations;
    double change = update(Kind::row, rows_, evidence.miss.data());
    change = std::max(change, update(Kind::column, columns_, evidence.clutter.data()));
    change = std::max(change, update(Kind::page, pages_, nullptr));
    result.converged = change < options.tolerance;
  }
  // Beliefs (54)-(55); pairs outside the gate are exactly 0.
  result.detection.setZero(evidence.pseudo_targets(), evidence.measurements());
  for (int e = 0; e < pairs; ++e) {
    result.detection(pair_row_[e], pair_column_[e]) =
        belief_of(pair_chi_[e] + row_message_[e] + column_message_[e] + page_message_[e]);
  }
  // A slack's belief from its factor: log odds = slack − log Σ e^ν over the factor's variables.
  auto slack_belief = [&](const FactorIndex& index, std::size_t f, double slack_value, const std::vector<double>& own) {
    const int* factor_pairs = index.pairs.data() + index.start[f];
    const int count = index.start[f + 1] - index.start[f];
    for (int k = 0; k < count; ++k) {
      const int e = factor_pairs[k];
      values_[k] = pair_chi_[e] + row_message_[e] + column_message_[e] + page_message_[e] - own[e];
    }
    return belief_of(slack_value - log_sum(values_.data(), count));
  };
  result.miss.resize(evidence.pseudo_targets());
  for (int p = 0; p < evidence.pseudo_targets(); ++p) result.miss[p] = slack_belief(rows_, p, evidence.miss[p], row_message_);
  result.clutter.resize(evidence.measurements());
  for (int j = 0; j < evidence.measurements(); ++j) {
    result.clutter[j] = slack_belief(columns_, j, evidence.clutter[j], column_message_);
  }
}

}  // namespace dabench

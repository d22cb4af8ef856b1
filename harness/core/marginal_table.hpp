#pragma once
// Marginal association probabilities p(a_i = j), n×(m+1), column 0 = missed detection.
// Storage is reused across solves: reshape() allocates only when a problem is larger than
// any seen before, so the solve loop of a run does not allocate.
#include <cassert>
#include <vector>

#include "harness/core/matrix_types.hpp"

namespace dabench {

class MarginalTable {
 public:
  using View = Eigen::Map<RowMatrix>;
  using ConstView = Eigen::Map<const RowMatrix>;

  void reshape(int targets, int measurements) {
    targets_ = targets;
    columns_ = measurements + 1;
    const std::size_t size = static_cast<std::size_t>(targets_) * static_cast<std::size_t>(columns_);
    if (storage_.size() < size) storage_.resize(size);
  }
  void reshape_zero(int targets, int measurements) {
    reshape(targets, measurements);
    view().setZero();
  }

  int targets() const { return targets_; }
  int measurements() const { return columns_ - 1; }

  double& operator()(int i, int j) {
    assert(i >= 0 && i < targets_ && j >= 0 && j < columns_);
    return storage_[static_cast<std::size_t>(i) * columns_ + j];
  }
  double operator()(int i, int j) const {
    assert(i >= 0 && i < targets_ && j >= 0 && j < columns_);
    return storage_[static_cast<std::size_t>(i) * columns_ + j];
  }
  double* row(int i) { return storage_.data() + static_cast<std::size_t>(i) * columns_; }
  const double* row(int i) const { return storage_.data() + static_cast<std::size_t>(i) * columns_; }

  View view() { return View(storage_.data(), targets_, columns_); }
  ConstView view() const { return ConstView(storage_.data(), targets_, columns_); }

 private:
  std::vector<double> storage_;
  int targets_ = 0;
  int columns_ = 1;
};

}  // namespace dabench

#pragma once
// One scan's measurements ordered by slant range (the first measurement component), so that a
// track gates its scan by binary search over the ranges instead of testing every measurement.
// Shared by the OTHR trackers that gate per track: MPTF's PDA filters (mptf.hpp) and MD-HMHT's
// hypothesis tree (md_hmht_tracks.hpp).
#include <algorithm>
#include <numeric>
#include <vector>

#include <Eigen/Core>

namespace dabench {

struct ScanIndex {
  std::vector<int> order;     // measurement columns by increasing range (ties: lower column first)
  std::vector<double> range;  // their ranges

  // Indexes the columns of `scan` (n_y × M); reuses the storage.
  void build(const Eigen::MatrixXd& scan) {
    const int m = static_cast<int>(scan.cols());
    order.resize(m);
    std::iota(order.begin(), order.end(), 0);
    std::sort(order.begin(), order.end(), [&](int a, int b) {
      return scan(0, a) < scan(0, b) || (scan(0, a) == scan(0, b) && a < b);
    });
    range.resize(m);
    for (int i = 0; i < m; ++i) range[i] = scan(0, order[i]);
  }
};

}  // namespace dabench

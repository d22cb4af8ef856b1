#pragma once
// Eigen types used across dabench. Association tables are row-major: one row per target.
#include <Eigen/Core>

namespace dabench {

using RowMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
using Vector = Eigen::VectorXd;

}  // namespace dabench

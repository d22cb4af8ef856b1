#pragma once
// The special doubles the algorithms and metrics use by name: ±∞ for "no finite cost" or log 0,
// NaN for "undefined" (a metric with nothing to measure); log 2π of the Gaussian densities.
#include <cmath>
#include <limits>
#include <numbers>

namespace dabench {

inline constexpr double kInfinity = std::numeric_limits<double>::infinity();
inline constexpr double kMinusInfinity = -std::numeric_limits<double>::infinity();
inline constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
inline const double kLog2Pi = std::log(2.0 * std::numbers::pi);

}  // namespace dabench

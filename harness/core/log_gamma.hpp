#pragma once
// ln Γ(x) for x > 0, safe to call from many threads: std::lgamma also writes the sign of Γ(x) to
// the global `signgam` (POSIX), a data race between trials run in parallel; lgamma_r returns it
// through a local instead and computes the same value (glibc: one implementation behind both).
#include <math.h>

namespace dabench {

inline double log_gamma(double x) {
  int sign;
  return ::lgamma_r(x, &sign);
}

}  // namespace dabench

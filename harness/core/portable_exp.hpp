#pragma once
// portable_exp(x): e^x in plain double arithmetic, for hot loops that must vectorise.
//
// std::exp is a library call, so a loop that calls it stays scalar (GCC vectorises it only
// through libmvec, which needs -ffast-math and picks its code by CPU at run time). This one is
// inline, branch-free and made of +, ×, min, |·| and integer bit operations, so GCC vectorises
// loops around it at the baseline ISA (SSE2 on x86-64) under -O3 (or with `#pragma omp simd`)
// without -ffast-math, and its result depends on nothing but x (and the compiled code: no
// choice by CPU at run time): the same bits on every CPU, thread count and host.
//
// Method (Cody–Waite): n = round(x / ln 2), r = x − n·ln2_hi − n·ln2_lo with |r| ≤ ½ ln 2
// (n·ln2_hi exact: ln2_hi has 21 trailing zero bits), e^r by its Taylor polynomial of degree 13
// (remainder < 2^−57 relative), e^x = e^r · 2^⌊n/2⌋ · 2^(n−⌊n/2⌋) (two factors, so results down
// in the subnormal range are still formed; each factor is a normal power of two).
// Accuracy: relative error below 4e-16 (≤ 2 ulp) wherever e^x is normal (tests/core/
// test_portable_exp.cpp); in the subnormal range (x < −708.4) the absolute error is below one
// subnormal step. Special values: −∞ and x < −745.2 give 0, x > 709.78 and +∞ give +∞, NaN
// gives NaN.
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>

namespace dabench {

inline double portable_exp(double x) {
  constexpr double kLog2e = 0x1.71547652b82fep0;
  constexpr double kLn2Hi = 0x1.62e42fee00000p-1;
  constexpr double kLn2Lo = 0x1.a39ef35793c76p-33;
  constexpr double kRound = 0x1.8p52;  // adding it rounds to an integer (round to nearest)
  // |x| ≤ 746 keeps n within the scaling's range; beyond it e^x is 0 or +∞ anyway. One
  // comparison on |x|, not two on x: GCC does not if-convert (so vectorise) two under the
  // default -ftrapping-math. NaN passes through.
  x = std::copysign(std::min(std::abs(x), 746.0), x);
  const double shifted = x * kLog2e + kRound;
  const double n = shifted - kRound;
  const double r = (x - n * kLn2Hi) - n * kLn2Lo;
  // e^r = Σ_{k=0}^{13} r^k / k!  (Horner)
  double p = 1.0 / 6227020800.0;  // 1/13!
  p = p * r + 1.0 / 479001600.0;
  p = p * r + 1.0 / 39916800.0;
  p = p * r + 1.0 / 3628800.0;
  p = p * r + 1.0 / 362880.0;
  p = p * r + 1.0 / 40320.0;
  p = p * r + 1.0 / 5040.0;
  p = p * r + 1.0 / 720.0;
  p = p * r + 1.0 / 120.0;
  p = p * r + 1.0 / 24.0;
  p = p * r + 1.0 / 6.0;
  p = p * r + 0.5;
  p = p * r + 1.0;
  p = p * r + 1.0;
  // n sits in the low bits of `shifted` (two's complement, |n| ≤ 1077).
  const std::int64_t k = std::bit_cast<std::int64_t>(shifted) - std::bit_cast<std::int64_t>(kRound);
  const std::int64_t half = k >> 1;
  const double scale1 = std::bit_cast<double>((half + 1023) << 52);
  const double scale2 = std::bit_cast<double>((k - half + 1023) << 52);
  return p * scale1 * scale2;
}

}  // namespace dabench

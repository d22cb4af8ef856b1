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
// (n·ln2_hi exact: ln2_hi has 21 trailing zero bits), e^r by a polynomial of degree 11,
// e^x = e^r · 2^⌊n/2⌋ · 2^(n−⌊n/2⌋) (two factors, so results down in the subnormal range are
// still formed; each factor is a normal power of two).
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
  // e^r by its degree-11 Chebyshev interpolant on [−½ ln 2, ½ ln 2] (coefficients computed in
  // 60-digit arithmetic, rounded to double: relative error below 1.6e-17, a seventh of an ulp,
  // checked on 4001 points in 50-digit arithmetic), in Horner form.
  double p = 0x1.af785e0a5dff9p-26;
  p = p * r + 0x1.28b40639f7187p-22;
  p = p * r + 0x1.71dde76a2f6d2p-19;
  p = p * r + 0x1.a01991aba6f13p-16;
  p = p * r + 0x1.a01a01b802660p-13;
  p = p * r + 0x1.6c16c187fc3e6p-10;
  p = p * r + 0x1.111111110db75p-7;
  p = p * r + 0x1.555555554f0ccp-5;
  p = p * r + 0x1.5555555555562p-3;
  p = p * r + 0x1.0000000000011p-1;
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

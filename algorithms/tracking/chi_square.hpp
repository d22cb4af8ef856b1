#pragma once
// The χ² quantile that sets the gates of the trackers: γ with P(χ²_n ≤ γ) = p, the threshold of
// JDT-VB's eq (33) (P_G = 0.971, n = 3: γ ≈ 9.02) and of MPTF's gates.
//
// Method: bisection on γ over [0, 10n + 100] for P(n/2, γ/2) = p, where P(a, x) =
// γ(a, x)/Γ(a), the regularised lower incomplete gamma function, is summed by its power series
// x^a e^{−x}/Γ(a+1) · Σ_k x^k / ((a+1)···(a+k)) (all terms positive: no cancellation). The
// bisection runs until the bracket is two adjacent doubles.
// Accuracy: limited by the rounding of P (about 1e-16 absolute), which moves γ by that over the
// density. Relative error, against 40-digit values, for p ≤ 0.999: below 1e-13 with dof ≤ 10,
// below 1e-12 with dof ≤ 100; in the far tail it grows, to at most 1e-9 at p = 1 − 1e-6
// (tests/tracking/test_chi_square.cpp).
namespace dabench {

// Domain: 0 < probability < 1 and 1 ≤ dof ≤ 100 (beyond, the series overflows); outside it
// throws std::invalid_argument.
double chi_square_quantile(double probability, int dof);

}  // namespace dabench

#pragma once
// Metrics of a particle belief against the truth (multiscan-convex-variational, Sec. IV): the
// HPD value of eq (92) and the differential entropy of the location belief.
//
// Density estimator. A scenario draws a track's particles x_p, p = 1..N, i.i.d. from a known
// proposal density g and gives them prior weights ψ(p) ∝ π0(x_p)/g(x_p) (importance weights for
// the initial posterior π0). Every multi-scan method returns q(p) ∝ ψ(p)·f(x_p) for a function
// f of the factors at x_p (its likelihood of the scans), i.e. it represents the density
// p(x) = π0(x) f(x) / ∫π0 f. Self-normalised importance sampling gives, at each particle,
//     p̂(x_p) = N·q(p)·g(x_p)          (exact π0·f, divided by the IS estimate of ∫π0 f),
// so density_scale = N·g(x_p). f at the truth x* comes from the truth probe (a hypothesis at x*
// with prior ε·π0(x*)/g(x*)): p̂(x*) = q(probe)·N·g(x*)/ε, on the same scale.
//   HPD, eq (92):  HPD(p, x*) = ∫_{p(x) ≥ p(x*)} p(x) dx ≈ Σ_p q̃(p)·[p̂(x_p) ≥ p̂(x*)]
//   entropy:       H(p) = −∫ p log p dx ≈ −Σ_p q̃(p)·log p̂(x_p)   (nats, in log area units)
// with q̃ the belief renormalised over the particles (probe excluded). Both are consistent as
// N → ∞; the comparisons inside HPD are between exact values of π0·f (the estimate of ∫π0 f
// cancels), so HPD's only error is the Monte Carlo error of the weighted sum.
//   HPD ranked by likelihood [R]: the paper ranks by the density (eq 92); ranking by the
//   method's likelihood of the scans, f(x_p) = q(p)/ψ(p), instead, HPD_f = Σ_p q̃(p)·[f(x_p) ≥
//   f(x*)] with f(x*) = q(probe)/ψ(probe), is the same construction with another statistic: for
//   a truth drawn from the belief it is Uniform(0, 1) too (P(T(X) ≥ T(X*)) for X, X* i.i.d.),
//   so both are calibration checks; they weigh the prior's shape differently.
#include "harness/core/matrix_types.hpp"

namespace dabench {

struct ParticleBeliefMetrics {
  double hpd = 0.0;             // eq (92), in [0, 1]
  double entropy = 0.0;         // differential entropy estimate, nats
  double hpd_likelihood = 0.0;  // HPD ranked by the likelihood q/ψ, in [0, 1]
};

// `belief` q over hypotheses (probe included), `density_scale` s with p̂ = q·s, `prior` ψ,
// `probe` the index of the truth probe. NaN values if the particles carry no belief.
ParticleBeliefMetrics particle_belief_metrics(const Vector& belief, const Vector& density_scale, const Vector& prior,
                                              int probe);

}  // namespace dabench

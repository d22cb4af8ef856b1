#pragma once
// Track heads of JDT-VB (jdt-vb-multipath-othr, Sec. III-E): new tracks started from the
// measurements of one scan that no existing track gates. The OTHR trackers' shared initiator:
// JDT-VB (jdt_vb_run.hpp) and MD-HMHT (md_hmht.cpp) start the same heads from the same scan.
//  - Grouping: the candidates form a pool in increasing first measurement component (slant
//    range). The first of the pool seeds a group and, in that order, the group takes every
//    later candidate within `threshold` (per component, |Δy| ≤ ρ) of all members so far, up to
//    2 N_P members ("any two measurements are within a preset threshold vector ρ").
//  - Heads within a group: a hypothesis assigns distinct paths to some of the members (at
//    least two: "it is rare to receive the measurement only from one path"; a target yields
//    at most one measurement per path). Each assigned member y_j is mapped to the ground,
//    x_j = (h^τ_j)⁻¹(y_j) (MultipathMeasurementModel::invert), with information
//    I_j = H_jᵀ R⁻¹ H_j (H_j the Jacobian at x_j), and the states are fused:
//      P = (Σ_j I_j + Λ₀)⁻¹,  x̂ = P (Σ_j I_j x_j + Λ₀ x̄),  x̄ = mean of the x_j,
//    with Λ₀ = diag(prior_precision) covering the components the measurements do not see
//    (OTHR: ϑ̇). A hypothesis is consistent when every member has (x_j − x̂)ᵀ I_j (x_j − x̂) ≤
//    `gate`. The best is the consistent hypothesis with the most members, ties broken by the
//    least mean distance (the paper's "minimum average Mahalanobis distance"). Its members can
//    also fit other path assignments (two measurements received on one layer fit that layer
//    pair and the other one, ~30 km apart on the ground): with `alternative_heads` (the
//    default; not in the paper) every consistent assignment of exactly those members whose
//    state differs from the ones kept (beyond `gate`) starts a head too, and the later scans'
//    association decides between them; without it only the best starts one. The members leave the
//    pool; if the group has no consistent pair, only the seed leaves. Repeat until the pool
//    is empty; a group may thus hold two targets' measurements (Table III's parallel targets
//    1 and 2 are 50 km apart, inside ρ_r = 80 km) and give a head for each.
//  - p(s = 1) = min(1, (|Y| / N_P)²).
#include <vector>

#include <Eigen/Core>

#include "harness/core/matrix_types.hpp"
#include "harness/tracking/problem.hpp"

namespace dabench {

struct TrackHead {
  Vector mean;                 // x̂
  Eigen::MatrixXd covariance;  // P
  double initial_active = 0.0; // p(s = 1)
  std::vector<int> members;    // measurement indices (columns of the scan)
  std::vector<int> paths;      // the chosen path of each member
};

struct TrackHeadOptions {
  Vector threshold;        // ρ, per measurement component (n_y)
  Vector prior_precision;  // Λ₀ diagonal, per state component (n_x), > 0
  double gate = 9.0;       // consistency bound on each member's Mahalanobis distance
  bool alternative_heads = true;  // also a head per other path reading of the best's members
};

// The OTHR trackers' options: ρ = `threshold` on [r, ṙ, ζ] (0 on further components), Λ₀ weak
// (1e-6: 1000 km, 1 km/s, 1 rad) on the observed ground components and 1/σ² on ϑ̇, σ =
// `bearing_rate_sd`, for the ground state [g, ġ, ϑ, ϑ̇] (all 1e-6 for another state size).
TrackHeadOptions ground_head_options(int state_dim, int measurement_dim, const Eigen::Vector3d& threshold,
                                     double bearing_rate_sd, double gate, bool alternative_heads);

// Heads from the columns `candidates` of `scan` (n_y × M).
std::vector<TrackHead> form_track_heads(const Eigen::MatrixXd& scan, const std::vector<int>& candidates,
                                        const MultipathMeasurementModel& sensor, const TrackHeadOptions& options);

}  // namespace dabench

#pragma once
// The iterative message passing of TBD-BP between potential objects (POs) and data cells
// (tbd-bp-supplement, Sec. 1; docs/models/track-before-detect.md §3.3), on particle POs:
//
//  β^(ℓ)_{n,j}(y) ∝ α_n(y) Π_{j'≠j} κ^(ℓ−1)_{n,j'}(y)              (κ^(0) ≡ 1, so β^(1) = α)
//  μ^(ℓ)_{n,j} = ∫ μ_j(x) β^(ℓ)_{n,j}(x,1) dx,  R^(ℓ)_{n,j} = ∫ (C_j(x) + μ_j μ_jᵀ) β^(ℓ)_{n,j}(x,1) dx
//  κ̃^(ℓ)_{n,j}(y) = N(z_j; r μ_j(x) + Σ_{n'≠n} μ_{n',j}, r C_j(x) + C_ε + Σ_{n'≠n} (R_{n',j} − μ_{n',j}μ_{n',j}ᵀ))
//                                                                     (supplement eqs (5), (9))
// The sums over n' ≠ n come from per-cell totals M_j = Σ_n μ_{n,j}, V_j = Σ_n (R_{n,j} − μμᵀ)
// minus PO n's own term, so an iteration costs O(Σ_n P_n |W_n|) — linear in the number of POs
// (P_n particles, W_n the PO's window of cells). Everything is carried as log-ratios
// λ_{n,j}(x) = log κ̃_{n,j}(x,1) − log κ̃_{n,j}(0), the only form β and the belief need:
// b^(i)_{n,j} ∝ w^(i) r exp(Σ_{j'≠j} λ_{n,j'}(x^(i))), b^0_{n,j} ∝ 1 − r.
//
// Window: the cells whose centre lies within `support_radius` of the PO's particles' bounding
// box; outside it μ_j(x) and C_j(x) are taken as zero (then the cell's κ̃ ratio is 1). With
// the default radius of 4σ_h, g_j ≤ e^{−8} ≈ 3e-4 there (C_j ≤ 0.01 at γ = 60 against C_ε = 1).
//
// Speed: the passes are loops over a PO's particles per window cell, written to vectorise at
// the baseline ISA (SSE2) without -ffast-math: e^x by portable_exp (harness/core), reductions
// under `#pragma omp simd` (their order is fixed when compiling: no choice by CPU or thread
// count, so results stay bit-identical across threads, processes and hosts), a kernel without
// square roots where V and C_j are isotropic and μ_j ≡ 0 (D1), and one log per particle for
// Σ_j log det ratios. Runtime: bench/tbd/bench_tbd.cpp.
//
// Variants (the same passes): `interaction = false` drops the Σ_{n'≠n} terms, so each PO sees
// the cells alone (the non-interacting update of TBD-MB); `exact = true` replaces κ̃ by the
// exact κ of the letter's eq (5), a sum over the other POs' particles and existence — only for
// cells that at most two POs reach (the supplement's toy); run() returns false otherwise.
//
// New POs (TbdBp, one per cell) do not take part in run(): after it, outgoing_field() forms
// the field they see — per cell the totals of the run's POs' next messages β^(L+1)_{n,j} —
// and evaluate() runs one new PO against the field (its own term is not in it), with κ̃;
// add_to_field() then adds an accepted new PO's belief, so the next new PO sees it (a serial
// schedule over the new POs; see tbd_bp.hpp for why). TbdBp's joint schedule instead runs the
// serial schedule in its parts (start_serial, serial_sweep, finish_serial) and puts the kept
// new POs' extrinsic messages into the field between the sweeps (enter_field, leave_field).
#include <cmath>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "algorithms/tbd/particle_object.hpp"
#include "harness/tbd/problem.hpp"

namespace dabench {

struct CellWindow {
  int column_begin = 0, column_end = 0;  // [begin, end)
  int row_begin = 0, row_end = 0;
  int columns() const { return column_end - column_begin; }
  int rows() const { return row_end - row_begin; }
  int cells() const { return columns() * rows(); }
};

struct CellMessageOptions {
  int iterations = 2;          // L
  double support_radius = 0.0; // window margin, m (set by the tracker: 4σ_h by default)
  bool interaction = true;     // false: Σ_{n'≠n} terms dropped (TBD-MB)
  bool exact = false;          // exact κ of eq (5) (at most two POs per cell)
  // Schedule: flooding (every PO's β^(ℓ) from the others' κ̃^(ℓ−1)), or serial (POs in the
  // given order, each against the others' newest messages; Gaussian, interacting only).
  bool serial = false;
};

class CellMessages {
 public:
  // Per cell of a PO's window: the moments of its last β (eqs 5, 9) and its last κ̃.
  struct CellTerms {
    double mean_x = 0.0, mean_y = 0.0;          // μ_{n,j}
    double r_xx = 0.0, r_xy = 0.0, r_yy = 0.0;  // R_{n,j}
    // κ̃_{n,j}(0) = N(z_j; z_j − e, V): e = z_j − Σ_{n'≠n} μ_{n',j}, V = C_ε + Σ_{n'≠n} (R − μμᵀ);
    // κ̃_{n,j}(x,1) adds μ_j(x) to the mean and C_j(x) to V.
    double e_x = 0.0, e_y = 0.0, v_xx = 0.0, v_xy = 0.0, v_yy = 0.0;
  };
  struct Work {  // one PO's state in the passes
    CellWindow window;
    std::vector<double> spread_x;  // g along x: [window column][particle]
    std::vector<double> spread_y;  // g along y: [window row][particle]
    std::vector<double> own_factor;  // exp(−λ_{n,j}(x^(i))) = κ̃(0)/κ̃(x^(i),1): [window cell][particle]
    std::vector<double> total;     // Σ_j λ_{n,j}(x^(i))
    std::vector<CellTerms> terms;  // per window cell
    double log_odds = 0.0;
  };

  // L iterations over `objects` on one frame. Afterwards total_log_ratio(n)[i] =
  // Σ_j λ^(L)_{n,j}(x^(i)) and existence_log_odds(n) is the belief's log r̃/(1 − r̃).
  // Returns false (and computes nothing) if `exact` is set and a cell is reached by more than
  // two POs.
  [[nodiscard]] bool run(const TbdSensor& sensor, double amplitude, const Eigen::Matrix2Xd& frame,
                         const std::vector<ParticleObject*>& objects, const CellMessageOptions& options);

  const std::vector<double>& total_log_ratio(int n) const { return work_[n].total; }
  double existence_log_odds(int n) const { return work_[n].log_odds; }
  const CellWindow& window(int n) const { return work_[n].window; }
  // Window cell c of PO n (row-major in the window: c = (row − row_begin)·columns + column − column_begin).
  const CellTerms& cell_terms(int n, int c) const { return work_[n].terms[c]; }
  // λ^(L)_{n,j}(x^(i)) at window cell c.
  double log_ratio(int n, int c, int i) const {
    return -std::log(work_[n].own_factor[static_cast<std::size_t>(c) * work_[n].total.size() + i]);
  }

  // The field new POs see (after run()): per cell, Σ over the run's POs of the moments of
  // their messages β^(L+1)_{n,j} (from the final κ̃), plus each added new PO's belief.
  void outgoing_field();
  // Sets the sensor, μ_j/C_j and the window margin; run() calls it. Then prepare() fills a
  // PO's window and spread tables (once for POs whose particles do not move: new POs).
  void configure(const TbdSensor& sensor, double amplitude, double support_radius);
  void prepare(const ParticleObject& object, Work& work) const;
  // One new PO, prepared, against the field (κ̃) of the last run()'s frame — or, with
  // `interaction` false, against the frame alone: fills Σ_j λ and the log-odds in `work` and
  // returns the belief's log r̃/(1 − r̃).
  // With `own_factors`, also keeps exp(−λ) per cell and particle, for enter_field().
  double evaluate(const ParticleObject& object, Work& work, bool interaction, bool own_factors = false);
  // The serial schedule in parts, so that TbdBp's joint schedule can put its new POs between
  // the sweeps: start_serial() prepares `objects` and puts their α moments (β^(1)) into the
  // field; each serial_sweep() is one iteration ℓ over them in order (each takes its own message
  // out, computes κ̃ against the field, puts its new extrinsic β back); finish_serial() forms
  // their beliefs (total_log_ratio, existence_log_odds). Whatever else is in the field when a
  // sweep runs — new POs put there by enter_field() — is part of what the POs see.
  void start_serial(const TbdSensor& sensor, double amplitude, const Eigen::Matrix2Xd& frame,
                    const std::vector<ParticleObject*>& objects, double support_radius);
  void serial_sweep();
  void finish_serial();
  // A new PO evaluated with own_factors: its extrinsic messages β_{n,j} ∝ α Π_{j'≠j} κ̃ (cell j's
  // own factor excluded) enter the field; leave_field() takes them out again.
  void enter_field(const ParticleObject& object, Work& work);
  void leave_field(Work& work);
  // Adds the belief of an evaluated PO (existence r̃ = logistic(work.log_odds)) to the field.
  void add_to_field(const ParticleObject& object, const Work& work);
  // out[i] = Σ_j λ_{n,j} at the positions of `object`'s particles (not those of the evaluated
  // PO `work`), under the messages evaluate() used and over its window: for the particles drawn
  // when a new PO becomes a legacy PO. `out` may be object.weight. It reads the κ̃ parameters
  // (e, V) that evaluate() leaves in `work`: new POs are always evaluated with κ̃, and an exact
  // run() leaves no such parameters for its POs.
  void log_ratios_at(const Work& work, const ParticleObject& object, std::vector<double>& out);

 private:
  struct CellTotals {
    double mean_x = 0.0, mean_y = 0.0;
    double v_xx = 0.0, v_xy = 0.0, v_yy = 0.0;
  };

  // β moments of a PO per window cell: α (from_prior), else the extrinsic β from its λ.
  void moments(const ParticleObject& object, Work& work, bool from_prior);
  // run()'s and start_serial()'s set-up: sensor, frame, the POs' windows and tables.
  void begin(const TbdSensor& sensor, double amplitude, const Eigen::Matrix2Xd& frame,
             const std::vector<ParticleObject*>& objects, double support_radius);
  void start_serial();
  // Adds (sign = +1) or removes the PO's cell terms to or from totals_.
  void accumulate(const Work& work, double sign);
  // λ of every particle and window cell: Σ_j λ in work.total and, with own_factors, exp(−λ)
  // per pair (what the next β moments divide out).
  void gaussian_log_ratios(const ParticleObject& object, Work& work, bool interaction, bool own_factors);
  // The passes' kernel: total[i] = Σ_j λ_j(x^(i)) over spread.window for the particles
  // tabulated in `spread`, under the κ̃(0) parameters (e, V) of `terms`; with own_factor,
  // exp(−λ) per [window cell][particle] too.
  void sum_log_ratios(const std::vector<CellTerms>& terms, const Work& spread, int p, std::vector<double>& total,
                      double* own_factor);
  // work.spread_x, work.spread_y for `object`'s particles over work.window.
  void tabulate_spread(const ParticleObject& object, Work& work) const;
  void exact_log_ratios(const std::vector<ParticleObject*>& objects);
  void belief(const ParticleObject& object, Work& work);

  const TbdSensor* sensor_ = nullptr;
  const Eigen::Matrix2Xd* frame_ = nullptr;
  double support_radius_ = 0.0;
  // μ_j(x) = (mean_per_spread · g, 0), c_j(x) = variance_per_spread · g + variance_per_spread2 · g²
  double mean_per_spread_ = 0.0, variance_per_spread_ = 0.0, variance_per_spread2_ = 0.0;
  std::vector<Work> work_;
  std::vector<const ParticleObject*> objects_;  // of the last run()
  bool outgoing_moments_ready_ = false;  // the last run() left β^(L+1) moments in its POs' terms
  std::vector<CellTotals> totals_;  // per cell of the frame: the Σ_n of eqs (5), (9)
  std::vector<std::vector<double>> exact_lambda_;  // exact runs: each PO's λ per [window cell][particle]
  std::vector<double> shifted_;       // scratch: one PO's (log) weights
  std::vector<double> ones_;          // own factors of κ^(0) ≡ 1 (moments from the prior)
  Work drawn_;                        // scratch: log_ratios_at()'s spread tables
  std::vector<double> work_product_;         // scratch: product of determinant ratios (mantissa)
  std::vector<std::int64_t> work_exponent_;  // scratch: its binary exponent
};

}  // namespace dabench

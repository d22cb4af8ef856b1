#pragma once
// A potential object (PO) of the particle track-before-detect trackers (tbd-bp-supplement;
// docs/models/track-before-detect.md §3): y_n = (x_n, r_n), x = [p_x, p_y, v_x, v_y], held as weighted particles of
// x given r = 1 plus the existence probability r. Shared by TBD-BP and TBD-MB.
//
//  - predict(): the prediction message α_n of a legacy PO (docs/models/track-before-detect.md §3.2): each particle
//    moves by the nearly-constant-velocity model, r⁻ = p_s r, with p_s = 0 once the PO's mean
//    has left the region ([C] of the notes).
//  - resample(): systematic resampling to a given count (equal weights after).
//  - sample_prior(): particles of a TbdPrior (a Gaussian, possibly singular).
//  - predict_objects(): the legacy POs of step k: at k = 0 the problem's initial objects
//    (sample_prior, new labels), afterwards each PO predicted.
//  - belief_samples(): POs' particles as the tracker's belief samples (beliefs.csv).
#include <cmath>
#include <vector>

#include <Eigen/Core>

#include "harness/core/random_stream.hpp"
#include "harness/tbd/problem.hpp"
#include "harness/tbd/tracker.hpp"

namespace dabench {

// An existence probability r from its log-odds log r/(1 − r).
inline double logistic(double log_odds) { return 1.0 / (1.0 + std::exp(-log_odds)); }

struct ParticleObject {
  int label = -1;          // unique over a run
  double existence = 0.0;  // r: predicted (α) before an update, r̃ after
  std::vector<double> x, y, vx, vy;  // particles, structure of arrays
  std::vector<double> weight;        // normalised: Σ weight = 1

  int size() const { return static_cast<int>(x.size()); }
  void resize(int count);
  Eigen::Vector4d mean() const;  // Σ weight · particle
};

// α of a legacy PO from its belief at the previous step (see the header).
void predict(ParticleObject& object, const TbdMotion& motion, const TbdSensor& sensor, double survival,
             RandomStream& rng);

// Systematic resampling (one uniform) to `count` equally weighted particles; `scratch` is reused.
void resample(ParticleObject& object, int count, RandomStream& rng, ParticleObject& scratch);

// `count` equally weighted particles drawn from N(prior.mean, prior.covariance), r = prior.existence.
void sample_prior(ParticleObject& object, const TbdPrior& prior, int count, RandomStream& rng);

// The legacy POs at step k (see the header), `particles` per initial object.
void predict_objects(std::vector<ParticleObject>& objects, const TbdProblem& problem, int k, int particles,
                     int& next_label, RandomStream& rng);

// `samples` (replaced) = every particle of every PO with its label, existence and weight.
void belief_samples(const std::vector<ParticleObject>& objects, std::vector<TbdBeliefSample>& samples);

}  // namespace dabench

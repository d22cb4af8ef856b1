#include "algorithms/tbd/particle_object.hpp"

#include <cmath>

#include <Eigen/Eigenvalues>

namespace dabench {

void ParticleObject::resize(int count) {
  x.resize(count);
  y.resize(count);
  vx.resize(count);
  vy.resize(count);
  weight.resize(count);
}

Eigen::Vector4d ParticleObject::mean() const {
  Eigen::Vector4d m = Eigen::Vector4d::Zero();
  for (int i = 0; i < size(); ++i) m += weight[i] * Eigen::Vector4d(x[i], y[i], vx[i], vy[i]);
  return m;
}

void predict(ParticleObject& object, const TbdMotion& motion, const TbdSensor& sensor, double survival,
             RandomStream& rng) {
  const Eigen::Vector4d m = object.mean();
  object.existence *= sensor.inside(m(0), m(1)) ? survival : 0.0;
  // x_k = A x_{k−1} + W a, A = [I T·I; 0 I], W = [T²/2 I; T I], a ~ N(0, σ_a² I₂).
  const double t = motion.scan_interval;
  const double sd = std::sqrt(motion.driving_noise_variance);
  for (int i = 0; i < object.size(); ++i) {
    const double ax = sd * rng.normal();
    const double ay = sd * rng.normal();
    object.x[i] += t * object.vx[i] + 0.5 * t * t * ax;
    object.y[i] += t * object.vy[i] + 0.5 * t * t * ay;
    object.vx[i] += t * ax;
    object.vy[i] += t * ay;
  }
}

void resample(ParticleObject& object, int count, RandomStream& rng, ParticleObject& scratch) {
  scratch.resize(count);
  const int n = object.size();
  const double step = 1.0 / count;
  double u = rng.uniform() * step;
  double cumulative = object.weight[0];
  int i = 0;
  for (int s = 0; s < count; ++s) {
    while (u > cumulative && i < n - 1) cumulative += object.weight[++i];
    scratch.x[s] = object.x[i];
    scratch.y[s] = object.y[i];
    scratch.vx[s] = object.vx[i];
    scratch.vy[s] = object.vy[i];
    scratch.weight[s] = step;
    u += step;
  }
  std::swap(object.x, scratch.x);
  std::swap(object.y, scratch.y);
  std::swap(object.vx, scratch.vx);
  std::swap(object.vy, scratch.vy);
  std::swap(object.weight, scratch.weight);
}

void sample_prior(ParticleObject& object, const TbdPrior& prior, int count, RandomStream& rng) {
  // A square root S S^T = P that exists for singular P too (eigen-decomposition).
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix4d> eigen(prior.covariance);
  const Eigen::Vector4d root_values = eigen.eigenvalues().cwiseMax(0.0).cwiseSqrt();
  const Eigen::Matrix4d root = eigen.eigenvectors() * root_values.asDiagonal();
  object.resize(count);
  object.existence = prior.existence;
  for (int i = 0; i < count; ++i) {
    Eigen::Vector4d z;
    for (int d = 0; d < 4; ++d) z(d) = rng.normal();
    const Eigen::Vector4d s = prior.mean + root * z;
    object.x[i] = s(0);
    object.y[i] = s(1);
    object.vx[i] = s(2);
    object.vy[i] = s(3);
    object.weight[i] = 1.0 / count;
  }
}

void predict_objects(std::vector<ParticleObject>& objects, const TbdProblem& problem, int k, int particles,
                     int& next_label, RandomStream& rng) {
  if (k == 0) {
    for (const TbdPrior& prior : problem.initial_objects) {
      objects.emplace_back();
      sample_prior(objects.back(), prior, particles, rng);
      objects.back().label = next_label++;
    }
    return;
  }
  for (ParticleObject& o : objects) {
    predict(o, problem.motion, problem.sensor, problem.filter.survival_probability, rng);
  }
}

void belief_samples(const std::vector<ParticleObject>& objects, std::vector<TbdBeliefSample>& samples) {
  samples.clear();
  for (const ParticleObject& o : objects) {
    for (int i = 0; i < o.size(); ++i) samples.push_back({o.label, o.existence, o.x[i], o.y[i], o.weight[i]});
  }
}

}  // namespace dabench

#pragma once
// Counter-based random streams. Philox4x32-10 (Salmon et al., "Parallel random numbers: as
// easy as 1, 2, 3", SC 2011) keyed by the run's master seed; the counter holds
// (block, point, trial), so the numbers a trial sees depend only on (seed, point, trial) and
// never on which thread or process runs it. Distributions are our own code (not std::), so a
// seed means the same trials with every standard library.
#include <array>
#include <cstdint>

namespace dabench {

class Philox4x32 {
 public:
  using Block = std::array<std::uint32_t, 4>;
  using Key = std::array<std::uint32_t, 2>;
  static Block generate(Block counter, Key key);
};

// Identity of the trial a problem belongs to. Stochastic algorithms (MCMCDA, the particle
// trackers) draw from RandomStream(mix(seed, their own seed option), point, trial), so their
// output depends only on the trial, never on the thread that runs it. `dabench solve` uses
// {0, 0, 0}.
struct TrialKey {
  std::uint64_t seed = 0;
  std::uint32_t point = 0;
  std::uint32_t trial = 0;
};

// The master seed of an algorithm's own stream for trial seed `trial_seed` and the algorithm's
// `seed` option: splitmix64(trial_seed ^ (0x9E3779B97F4A7C15 · (option_seed + 1))), so runs with
// different `seed` options draw independent numbers on the same trial.
std::uint64_t algorithm_stream_seed(std::uint64_t trial_seed, std::int64_t option_seed);

class RandomStream {
 public:
  RandomStream(std::uint64_t seed, std::uint32_t point, std::uint32_t trial);

  std::uint64_t next_u64();
  double uniform();                        // [0, 1), 53 random bits
  double uniform(double lo, double hi);    // [lo, hi)
  double normal();                         // N(0, 1), Marsaglia polar method
  bool bernoulli(double p) { return uniform() < p; }
  std::int64_t poisson(double mean);       // inversion below 12, Hörmann's PTRS above

 private:
  void refill();
  Philox4x32::Key key_;
  Philox4x32::Block counter_;
  Philox4x32::Block buffer_{};
  int used_ = 4;                 // 32-bit words of buffer_ consumed
  double spare_normal_ = 0.0;
  bool has_spare_normal_ = false;
};

}  // namespace dabench

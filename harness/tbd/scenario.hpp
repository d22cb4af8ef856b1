#pragma once
// The interface of track-before-detect scenario generators: a pure function of (parameters,
// random stream) that draws one run of K frames with its truth. Parameters are fixed when the
// object is built (one per sweep point); generate() may be called from many threads at once.
#include "harness/core/random_stream.hpp"
#include "harness/tbd/problem.hpp"

namespace dabench {

class TbdScenario {
 public:
  virtual ~TbdScenario() = default;
  virtual void generate(RandomStream& rng, TbdSample& sample) const = 0;
};

}  // namespace dabench

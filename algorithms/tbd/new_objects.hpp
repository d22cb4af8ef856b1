#pragma once
// New potential objects, one per data cell (docs/models/track-before-detect.md §3.2; shared by TBD-BP and TBD-MB).
//
//  - make_cell_objects(): PO j is uniform over cell j's square, held as a Q × Q midpoint
//    quadrature of the cell (μ_j(x) and C_j(x) depend on the position only, so the velocity
//    prior does not enter the messages, and a new PO costs Q² instead of P particles).
//  - draw_in_cell(), then settle_drawn(): a new PO that is kept becomes a legacy PO: P
//    particles uniform over its cell with velocity ~ N(0, σ_v² I₂), weighted by what the
//    caller puts in their log weights in between (TBD-BP: Σ_j λ under the messages the PO was
//    evaluated with; TBD-MB: its likelihood and exclusivity messages), then resampled.
#include <vector>

#include "algorithms/tbd/particle_object.hpp"
#include "harness/core/random_stream.hpp"
#include "harness/tbd/problem.hpp"

namespace dabench {

// One PO per cell (index j = row · columns + column), Q = `grid` points per axis, existence 0.
void make_cell_objects(const TbdSensor& sensor, int grid, std::vector<ParticleObject>& objects);

// `particles` particles of new PO `cell` drawn from `rng`; object.weight holds LOG weights, 0.
void draw_in_cell(const TbdProblem& problem, int cell, int particles, RandomStream& rng, ParticleObject& object);
// Log weights to normalised weights, existence and label set, resampled to its size.
void settle_drawn(ParticleObject& object, double existence, int label, RandomStream& rng, ParticleObject& scratch);

}  // namespace dabench

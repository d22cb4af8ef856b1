#include "algorithms/tbd/new_objects.hpp"

#include <algorithm>
#include <cmath>

namespace dabench {

void make_cell_objects(const TbdSensor& sensor, int grid, std::vector<ParticleObject>& objects) {
  const int q = grid;
  objects.resize(sensor.cells());
  for (int row = 0; row < sensor.rows; ++row) {
    for (int column = 0; column < sensor.columns; ++column) {
      ParticleObject& o = objects[row * sensor.columns + column];
      o.resize(q * q);
      o.existence = 0.0;
      for (int a = 0; a < q; ++a) {
        for (int b = 0; b < q; ++b) {
          const int i = a * q + b;
          o.x[i] = sensor.x_min + (column + (b + 0.5) / q) * sensor.cell_size;
          o.y[i] = sensor.y_min + (row + (a + 0.5) / q) * sensor.cell_size;
          o.vx[i] = o.vy[i] = 0.0;
          o.weight[i] = 1.0 / (q * q);
        }
      }
    }
  }
}

void draw_in_cell(const TbdProblem& problem, int cell, int particles, RandomStream& rng, ParticleObject& object) {
  const TbdSensor& sensor = problem.sensor;
  const double x0 = sensor.x_min + (cell % sensor.columns) * sensor.cell_size;
  const double y0 = sensor.y_min + (cell / sensor.columns) * sensor.cell_size;
  const double speed_sd = problem.filter.birth_speed_sd;
  object.resize(particles);
  for (int i = 0; i < particles; ++i) {
    object.x[i] = x0 + sensor.cell_size * rng.uniform();
    object.y[i] = y0 + sensor.cell_size * rng.uniform();
    object.vx[i] = speed_sd * rng.normal();
    object.vy[i] = speed_sd * rng.normal();
    object.weight[i] = 0.0;
  }
}

void settle_drawn(ParticleObject& object, double existence, int label, RandomStream& rng, ParticleObject& scratch) {
  const double top = *std::max_element(object.weight.begin(), object.weight.end());
  double sum = 0.0;
  for (double& w : object.weight) sum += w = std::exp(w - top);
  for (double& w : object.weight) w /= sum;
  object.existence = existence;
  object.label = label;
  resample(object, object.size(), rng, scratch);
}

}  // namespace dabench

#pragma once
// A frame of cell magnitudes |z_j| read from a text file: how the supplement's Fig. 1(a) (the
// toy example's frame, digitised into experiments/tbd/fig1a-frame.csv) enters a run.
//
// Format: lines starting with '#' are comments; then one line per row of cells, the bottom row
// (y = y_min + Δ/2) first, `columns` comma-separated magnitudes per line, left (x = x_min + Δ/2)
// first. A magnitude is a finite number ≥ 0, or `nan` for a cell that could not be read (the
// figure's legend covers some); nothing else is accepted.
//
// The figure shows |z_j| only, not the phase of z_j ∈ R². The frame is taken as z_j = (|z_j|, 0):
// under D1 (μ_j = 0, isotropic covariance) every likelihood depends on ‖z_j‖ alone, so nothing is
// lost; under D2 and D3 (a mean along e₁) this is the reading that the measured magnitude lies
// along the objects' mean [R]. An unread cell gets `unread` (the caller passes the background's
// median, σ√(2 ln 2), unless told otherwise): its evidence is then that of a typical noise cell.
#include <string>

#include <Eigen/Core>

namespace dabench {

struct MagnitudeFrame {
  Eigen::Matrix2Xd z;   // 2 × (columns · rows), column j = row · columns + column
  int unread_cells = 0; // cells that were `nan` in the file
};

// Throws InputError naming the file, and the line where there is one, if the path is not a
// regular file of at most 1 MiB, or the table is not `rows` lines of `columns` magnitudes.
MagnitudeFrame read_magnitude_frame(const std::string& path, int columns, int rows, double unread);

}  // namespace dabench

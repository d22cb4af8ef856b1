#pragma once
// TBD-IEMB's cell model (tbd_iemb.hpp, "The measurement" and "Window"): a Bernoulli's window of
// data cells, its measurement moments there, the field of every Bernoulli's terms per cell from
// which the information exchange takes the others' part, and the measurement one IPLF update sees.
#include <vector>

#include <Eigen/Core>

#include "algorithms/tbd/iplf.hpp"
#include "harness/tbd/problem.hpp"

namespace dabench {

// ---- the cell model over windows ---------------------------------------------------------------

enum class IembMeasurementKind { complex, power };

// The Gaussian approximation of a cell power y_j = ‖z_j‖²/2 under D1 (see the header): `own` =
// c_j(x) of the Bernoulli (0 if absent), zc = z_corr,j, sc = S_corr,j, σ² = noise variance.
struct PowerMoments {
  double mean = 0.0;
  double variance = 0.0;
};
PowerMoments power_moments(double noise_variance, double own, double zc, double sc);

// A rectangle of data cells, [begin, end); window cell c = (row − row_begin)·columns() +
// (column − column_begin).
struct IembWindow {
  int column_begin = 0, column_end = 0;
  int row_begin = 0, row_end = 0;
  int grid_columns = 0;  // the sensor's columns (cell j = row · grid_columns + column)
  int columns() const { return column_end - column_begin; }
  int rows() const { return row_end - row_begin; }
  int cells() const { return columns() * rows(); }
  int cell(int c) const;  // the data cell j of window cell c
};
// Cells whose centre lies within margin + position_sigmas·√P_aa of the mean along each axis,
// clipped to the grid, at most max_cells per side (centred on the mean's cell).
IembWindow iemb_window(const TbdSensor& sensor, const Eigen::Vector4d& mean, const Eigen::Matrix4d& covariance,
                       double margin, double position_sigmas, int max_cells);

// Per window cell: ȳ = E[h_j] and Y = E[h_j h_jᵀ + Cov(h_j | x)] (power: E[c_j], E[c_j²] in
// the first entries).
struct CellMoments {
  std::vector<Eigen::Vector2d> mean;
  std::vector<Eigen::Matrix2d> second;
};

// μ_j(x) and c_j(x) of harness/tbd/problem.hpp (readings D1, D2), evaluated over a window as
// g_j(p) = g_x(column) g_y(row).
class IembCellModel {
 public:
  static constexpr int kMaxSide = 64;  // window cells per side at most
  IembCellModel() = default;
  IembCellModel(const TbdSensor& sensor, double amplitude, IembMeasurementKind kind);
  int rows_per_cell() const { return kind_ == IembMeasurementKind::power ? 1 : 2; }
  IembMeasurementKind kind() const { return kind_; }
  // At each sigma point s and window cell c: h rows (q per cell) = the own mean contribution
  // (complex: μ_j; power: c_j) and variance(c, s) = c_j. Both need ≥ q·cells and cells rows.
  void evaluate(const SigmaPoints& sigma, const IembWindow& window, SigmaMatrix& h, SigmaMatrix& variance) const;
  // The same at one state: h[0 .. q·cells), variance[0 .. cells).
  void evaluate_at(const Eigen::Vector4d& state, const IembWindow& window, double* h, double* variance) const;
  // ȳ and Y per window cell from evaluate()'s output.
  void moments(const SigmaPoints& sigma, int cells, const SigmaMatrix& h, const SigmaMatrix& variance,
               CellMoments& out) const;

 private:
  const TbdSensor* sensor_ = nullptr;
  IembMeasurementKind kind_ = IembMeasurementKind::complex;
  double mean_per_spread_ = 0.0;       // μ_j = (mean_per_spread · g, 0)
  double variance_per_spread_ = 0.0;   // c_j = variance_per_spread · g + variance_per_spread2 · g²
  double variance_per_spread2_ = 0.0;
};

// Per data cell of the frame: M_j = Σ_u r_u ȳ_u,j and V_j = Σ_u (r_u Y_u,j − r_u² ȳ ȳᵀ).
class IembField {
 public:
  void reset(int cells);
  void add(const IembWindow& window, const CellMoments& own, double existence);
  void remove(const IembWindow& window, const CellMoments& own, double existence);  // undoes add()
  // The others' terms for a Bernoulli whose own term is in the field: per window cell
  // z_corr = M_j − r ȳ, S_corr = V_j − (r Y − r² ȳ ȳᵀ).
  void exchange(const IembWindow& window, const CellMoments& own, double existence, std::vector<Eigen::Vector2d>& zc,
                std::vector<Eigen::Matrix2d>& sc) const;

 private:
  std::vector<Eigen::Vector2d> mean_;
  std::vector<Eigen::Matrix2d> covariance_;
};

// One Bernoulli's measurement over its window, for the IPLF: z_j (complex, q = 2) or y_j (power,
// q = 1), with the others' exchange terms z_corr, S_corr per window cell (see the header).
class IembCellMeasurement final : public IplfMeasurement {
 public:
  // `frame` is the step's 2 × J frame; `powers` its y_j (read for power only). zc, sc per window
  // cell (IembField::exchange); they and `model` must outlive the update.
  void prepare(const IembCellModel& model, double noise_variance, const IembWindow& window,
               const Eigen::Matrix2Xd& frame, const std::vector<double>& powers,
               const std::vector<Eigen::Vector2d>& zc, const std::vector<Eigen::Matrix2d>& sc);
  void evaluate(const SigmaPoints& sigma, SigmaMatrix& h, std::vector<Eigen::Matrix2d>& noise) override;
  // Power only: Σ_j log Gamma(y_j; shape μ²/v, scale v/μ) with (μ, v) of power_moments() given
  // the Bernoulli at `state`, or absent (nullptr).
  double gamma_log_likelihood(const Eigen::Vector4d* state);

 private:
  const IembCellModel* model_ = nullptr;
  const std::vector<double>* powers_ = nullptr;
  IembWindow window_;
  double noise_variance_ = 1.0;
  const std::vector<Eigen::Vector2d>* zc_ = nullptr;
  const std::vector<Eigen::Matrix2d>* sc_ = nullptr;
  SigmaMatrix variance_;
  Eigen::VectorXd at_state_;  // c_j at one state
};

}  // namespace dabench

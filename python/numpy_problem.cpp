// numpy arrays in and out of the single-scan problem (python/bindings.hpp).
#include <cstring>
#include <string>

#include <fmt/format.h>

#include "harness/core/errors.hpp"
#include "python/bindings.hpp"

namespace dabench::python {

SingleScanProblem problem_from_array(const py::handle& weights, const WeightsFormat& format, const std::string& where) {
  const py::array array = py::array::ensure(weights);
  if (!array) throw InputError(fmt::format("{}: not an array of numbers", where));
  const char kind = array.dtype().kind();
  if (kind != 'f' && kind != 'i' && kind != 'u') {
    throw InputError(fmt::format("{}: dtype {} is not real numbers (give float64)", where,
                                 py::str(static_cast<const py::object&>(array.dtype())).cast<std::string>()));
  }
  if (array.ndim() != 2) {
    throw InputError(fmt::format("{}: a {}-dimensional array, not a matrix (the {} layout is {})", where, array.ndim(),
                                 weights_layout_name(format.layout), weights_layout_shape(format.layout)));
  }
  // No copy for a C-contiguous float64 array: the map reads the caller's memory.
  const auto values = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(array);
  const Eigen::Map<const RowMatrix> matrix(values.data(), values.shape(0), values.shape(1));
  return problem_from_weights(matrix, format, where);
}

py::array_t<double> marginals_array(const MarginalTable& marginals) {
  const py::ssize_t rows = marginals.targets(), columns = marginals.measurements() + 1;
  py::array_t<double> out({rows, columns});
  if (rows > 0) std::memcpy(out.mutable_data(), marginals.row(0), sizeof(double) * static_cast<std::size_t>(rows * columns));
  return out;
}

}  // namespace dabench::python

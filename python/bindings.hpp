#pragma once
// The pieces of the Python extension dabench._core (python/module.cpp binds them): each file
// binds one part of the API that python/dabench/__init__.py presents.
#include <string>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "harness/core/marginal_table.hpp"
#include "harness/single_scan/problem.hpp"
#include "harness/single_scan/weights_layout.hpp"

namespace dabench::python {

namespace py = pybind11;

// A single-scan problem refused by its algorithm: dabench.SkippedError (a RuntimeError).
class SkippedError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The ψ problem of a 2-D array of real numbers in `format` (harness/single_scan/weights_layout.hpp).
// A C-contiguous float64 array is read in place; another real dtype or order is converted first.
// InputError (ValueError) for another dtype or shape, or a bad entry, in the command line's words
// with `where` for the file name ("weights:2: column 3: weight -1 is negative").
SingleScanProblem problem_from_array(const py::handle& weights, const WeightsFormat& format, const std::string& where);
// The marginals as a new n × (m+1) float64 array.
py::array_t<double> marginals_array(const MarginalTable& marginals);

void bind_catalogue(py::module_& module);     // algorithms(), scenarios()
void bind_single_scan(py::module_& module);   // marginals(), marginals_batch(), time_solver(), draw()
void bind_runs(py::module_& module);          // start_run(): the handle behind dabench.run()
void bind_registration(py::module_& module);  // register(), unregister()

// Whether dabench.run() has a run going (the registry is then read by its threads: register()
// waits for no run and refuses instead).
bool run_in_progress();

// Counts register() and unregister() calls: a solver cached under a SPEC is stale once it changes.
int registration_generation();

}  // namespace dabench::python

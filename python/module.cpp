// dabench._core, the C++ extension of the Python package dabench (python/dabench/__init__.py).
// Every algorithm and scenario of the dabench library is linked in and registered. Errors the
// command line reports as "dabench: MESSAGE" raise ValueError(MESSAGE) (OSError for a failed
// write); a refused problem raises dabench.SkippedError.
#include <pybind11/pybind11.h>

#include "harness/core/build_info.hpp"
#include "harness/core/errors.hpp"
#include "python/bindings.hpp"

namespace py = pybind11;

PYBIND11_MODULE(_core, module) {
  using namespace dabench;
  module.doc() = "dabench's C++ core; use the package dabench";
  py::register_exception<python::SkippedError>(module, "SkippedError", PyExc_RuntimeError);
  py::register_exception_translator([](std::exception_ptr error) {
    try {
      if (error) std::rethrow_exception(error);
    } catch (const WriteError& failed) {
      PyErr_SetString(PyExc_OSError, failed.what());
    } catch (const InputError& bad) {
      PyErr_SetString(PyExc_ValueError, bad.what());
    }
  });
  module.attr("__version__") = std::string(build_info().version);
  module.attr("git_commit") = std::string(build_info().git_commit);
  python::bind_catalogue(module);
  python::bind_single_scan(module);
  python::bind_runs(module);
  python::bind_registration(module);
}

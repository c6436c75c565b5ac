// boxgen._core: the compiled part of the Python package boxgen (python/boxgen/__init__.py
// re-exports it). Errors: every bad argument is a ValueError or TypeError carrying the one-line
// message the CLI prints after "boxrecon: error: " or "boxgen: error: "; never a crash.
#include <pybind11/pybind11.h>

#include <exception>
#include <stdexcept>

#include "frontend/commands.h"
#include "generator/error.h"
#include "python/bindings.h"
#include "runtime/nrrd_io.h"
#include "support/output_file.h"

PYBIND11_MODULE(_core, m) {
  m.doc() = "boxgen: exact box-spline analysis and fast reconstruction (docs/python.md)";
  // Bad input, as boxrecon and boxgen classify it (exit code 1 or 2), is a ValueError.
  // pybind11 passes the exception_ptr by value.
  pybind11::register_exception_translator(
      [](std::exception_ptr p) {  // NOLINT(performance-unnecessary-value-param)
        try {
          if (p) std::rethrow_exception(p);
        } catch (const boxgen::generator::InputError& e) {
          PyErr_SetString(PyExc_ValueError, e.what());
        } catch (const boxgen::frontend::UsageError& e) {
          PyErr_SetString(PyExc_ValueError, e.what());
        } catch (const boxgen::runtime::NrrdError& e) {
          PyErr_SetString(PyExc_ValueError, e.what());
        } catch (const boxgen::support::OutputFileError& e) {
          PyErr_SetString(PyExc_ValueError, e.what());
        } catch (const std::out_of_range& e) {  // a point outside the volume: the caller's input
          PyErr_SetString(PyExc_ValueError, e.what());
        }
      });
  boxgen::python::bind_analysis(m);
  boxgen::python::bind_runtime(m);
}

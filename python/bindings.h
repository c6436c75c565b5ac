// The parts of the Python module boxgen._core (docs/python.md): the analysis functions over the
// generator's front end (analysis_bindings.cpp) and volumes, filters, evaluation and resampling
// over the runtime (runtime_bindings.cpp). module.cpp joins them and maps the C++ errors onto
// ValueError (bad input: the CLI's one-line messages) and RuntimeError (internal).
#pragma once
#include <pybind11/pybind11.h>

#include <nlohmann/json.hpp>

namespace boxgen::python {

// A JSON value as Python objects: objects -> dict, arrays -> list, numbers -> int or float.
pybind11::object to_python(const nlohmann::json& j);

void bind_analysis(pybind11::module_& m);
void bind_runtime(pybind11::module_& m);

}  // namespace boxgen::python

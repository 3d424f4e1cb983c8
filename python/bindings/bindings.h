// The pieces of the _kintsugi module, one file per area (python/bindings/*.cpp).
#pragma once

#include <nlohmann/json.hpp>
#include <pybind11/pybind11.h>

namespace kintsugi::python {

namespace py = pybind11;

// A JSON document as plain Python objects (dict, list, str, float, int, bool, None):
// json.loads of its text, so the dict is exactly what the CLI prints.
py::object to_python(const nlohmann::json& j);
nlohmann::json from_python(const py::handle& o);

void bind_model(py::module_& m);
void bind_repair(py::module_& m);
void bind_batch(py::module_& m);

}  // namespace kintsugi::python

// check, detect, beautify: the same documents as `kintsugi check --json`,
// `detect --json` and `beautify --report`, as dicts.
#include "apps/api.h"
#include "bindings/bindings.h"

#include <pybind11/stl.h>

namespace kintsugi::python {

void bind_repair(py::module_& m) {
  using api::Model;
  m.def(
      "check",
      [](const Model& model, std::optional<double> tol, bool occt) {
        nlohmann::json j;
        {
          py::gil_scoped_release unlocked;
          j = api::check(model, tol, occt);
        }
        return to_python(j);
      },
      py::arg("model"), py::arg("tol") = py::none(), py::arg("occt") = false,
      "Topological and geometric invariants: {valid, counts, violations, max_deviation, ...}.");
  m.def(
      "detect",
      [](const Model& model, std::optional<double> tol) {
        nlohmann::json j;
        {
          py::gil_scoped_release unlocked;
          j = api::detect(model, tol);
        }
        return to_python(j);
      },
      py::arg("model"), py::arg("tol") = py::none(),
      "The eleven problem types: {tolerance, units, problems: [{type, elements, measure, ...}], counts}.");
  m.def(
      "beautify",
      [](Model& model, std::optional<double> tol, bool check_topology_each_repair) {
        nlohmann::json j;
        {
          py::gil_scoped_release unlocked;
          j = api::beautify(model, tol, {check_topology_each_repair});
        }
        return to_python(j);
      },
      py::arg("model"), py::arg("tol") = py::none(), py::arg("check_topology_each_repair") = false,
      "Repair `model` in place; returns the report (the CLI's --report; seconds.read/write are 0).");
  m.def(
      "beautify_file",
      [](const std::string& in, const std::string& out, std::optional<double> tol) {
        nlohmann::json j;
        {
          py::gil_scoped_release unlocked;
          j = api::beautify_file(in, out, tol);
        }
        return to_python(j);
      },
      py::arg("input"), py::arg("output"), py::arg("tol") = py::none(),
      "`kintsugi beautify IN -o OUT --report`: read, repair, write; returns the report.");
}

}  // namespace kintsugi::python

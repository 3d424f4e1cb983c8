// Models: read, write, and the Model object (body, meta, units, format).
#include "apps/api.h"
#include "apps/report_json.h"
#include "bindings/bindings.h"

#include <pybind11/stl.h>

namespace kintsugi::python {

void bind_model(py::module_& m) {
  using api::Model;
  py::class_<Model>(m, "Model", "A B-rep model read from a file: its body, meta, units and format.")
      .def_property_readonly("units", [](const Model& x) { return x.units; })
      .def_property_readonly("format", [](const Model& x) { return x.format; }, "json, step or brep: what it was read from")
      .def_property(
          "meta", [](const Model& x) { return to_python(x.meta); },
          [](Model& x, const py::dict& d) { x.meta = from_python(d); }, "the native file's meta object, as a dict")
      .def_property_readonly("counts", [](const Model& x) { return to_python(cli::counts_json(x.body.counts())); },
                             "vertices, edges, faces, loops, shells, border_cycles")
      .def("copy", [](const Model& x) { return Model(x); }, "an independent copy (beautify changes a model in place)")
      .def("__repr__", [](const Model& x) {
        Counts c = x.body.counts();
        return "<kintsugi.Model " + std::to_string(c.faces) + " faces, " + std::to_string(c.edges) + " edges, " +
               std::to_string(c.vertices) + " vertices, " + x.units + (x.format.empty() ? "" : ", from " + x.format) + ">";
      });
  m.def(
      "read",
      [](const std::string& path) {
        py::gil_scoped_release unlocked;
        return api::read_model(path);
      },
      py::arg("path"), "Read a model: .json (native), .step/.stp, .brep. Raises kintsugi.Error.");
  m.def(
      "write",
      [](const Model& model, const std::string& path, const std::string& input) {
        py::gil_scoped_release unlocked;
        api::write_model(model, path, input);
      },
      py::arg("model"), py::arg("path"), py::arg("input") = "",
      "Write a model atomically, by the path's extension; never over `input`.");
}

}  // namespace kintsugi::python

// _kintsugi: the compiled half of the `kintsugi` Python package (python/kintsugi/).
#include "apps/api.h"
#include "bindings/bindings.h"

namespace kintsugi::python {

py::object to_python(const nlohmann::json& j) { return py::module_::import("json").attr("loads")(j.dump()); }

nlohmann::json from_python(const py::handle& o) {
  return nlohmann::json::parse(py::module_::import("json").attr("dumps")(o).cast<std::string>());
}

}  // namespace kintsugi::python

PYBIND11_MODULE(_kintsugi, m) {
  using namespace kintsugi::python;
  m.doc() = "kintsugi: repair the topology of B-rep solid models (bindings of apps/api.h)";
  py::register_exception<kintsugi::api::Error>(m, "Error", PyExc_RuntimeError);
  bind_model(m);
  bind_repair(m);
  bind_batch(m);
}

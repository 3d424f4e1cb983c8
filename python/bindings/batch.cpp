// The batch runner's pieces (apps/batch.h), for the Dask runner: the same file list, the
// same child process per file, the same manifest lines and summary as `kintsugi batch`.
#include "apps/api.h"
#include "apps/batch.h"
#include "bindings/bindings.h"

#include <pybind11/stl.h>

namespace kintsugi::python {

void bind_batch(py::module_& m) {
  namespace b = cli::batch;
  auto s = m.def_submodule("batch", "pieces of `kintsugi batch` (apps/batch.h)");
  s.def(
      "find_inputs",
      [](const std::string& in_dir) {
        std::string error;
        auto files = b::find_inputs(in_dir, &error);
        if (!error.empty()) throw api::Error(error);
        return files;
      },
      py::arg("in_dir"), "Every .step/.stp/.brep/.json under in_dir, relative, sorted.");
  s.def(
      "parse_size",
      [](const std::string& text) {
        auto v = b::parse_size(text);
        if (!v) throw py::value_error("'" + text + "' is not a size (e.g. 2G, 512M)");
        return *v;
      },
      py::arg("text"));
  s.def(
      "recorded_inputs",
      [](const std::string& manifest, bool drop_torn_tail) {
        std::string error;
        auto done = b::recorded_inputs(manifest, drop_torn_tail, &error);
        if (!error.empty()) throw api::Error(error);
        return done;
      },
      py::arg("manifest"), py::arg("drop_torn_tail") = true);
  s.def(
      "run_job",
      [](const std::string& exe, const std::string& in_dir, const std::string& out_dir, const std::string& input,
         std::optional<double> tol, double timeout, std::uint64_t max_memory) {
        py::gil_scoped_release unlocked;
        b::Job job{in_dir, out_dir, input, tol};
        return b::run_job(exe, job, {timeout, max_memory}).dump();
      },
      py::arg("exe"), py::arg("in_dir"), py::arg("out_dir"), py::arg("input"), py::arg("tol") = py::none(),
      py::arg("timeout") = 600.0, py::arg("max_memory") = 0,
      "Beautify one file in a child process `exe batch-file` under the limits; returns its manifest line.");
  s.def(
      "finish_run",
      [](const std::string& manifest, double wall_seconds, int jobs, std::size_t files_this_run) {
        std::string error;
        b::Summary sum = b::finish_run(manifest, wall_seconds, jobs, files_this_run, &error);
        if (!error.empty() && sum.table.empty()) throw api::Error(error);
        return py::make_tuple(sum.table, to_python(sum.json), sum.exit_code);
      },
      py::arg("manifest"), py::arg("wall_seconds"), py::arg("jobs"), py::arg("files_this_run"),
      "Write the summary beside the manifest; returns (table, summary, exit code 0 or 3).");
  s.def("summary_path_for", [](const std::string& manifest) { return b::summary_path_for(manifest).string(); });
}

}  // namespace kintsugi::python

#include "apps/model_files.h"

#include "io/native_json.h"
#include "apps/bounded_read.h"
#ifdef KINTSUGI_HAVE_OCCT
#include "geometry/occt/freeform_occt.h"
#include "geometry/tolerance.h"
#include "invariants/element_geometry.h"
#endif

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <unistd.h>

namespace kintsugi::cli {

namespace {

std::string extension(const std::string& path) {
  std::string e = std::filesystem::path(path).extension().string();
  std::transform(e.begin(), e.end(), e.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return e;
}

std::optional<std::string> format_of(const std::string& path, std::string* error) {
  std::string e = extension(path);
  if (e == ".json") return "json";
  if (e == ".step" || e == ".stp") return "step";
  if (e == ".brep") return "brep";
  if (e == ".iges" || e == ".igs") return "iges";
  *error = path + ": unknown file type '" + e + "' (use .json, .step, .stp, .iges, .igs or .brep)";
  return std::nullopt;
}

#ifdef KINTSUGI_HAVE_OCCT
io::CadFormat cad_format(const std::string& fmt) {
  if (fmt == "step") return io::CadFormat::step;
  if (fmt == "iges") return io::CadFormat::iges;
  return io::CadFormat::brep;
}
#endif

}  // namespace

std::string formats_supported() {
#ifdef KINTSUGI_HAVE_OCCT
  return ".json (native), .step/.stp (STEP), .iges/.igs (IGES), .brep (OpenCASCADE)";
#else
  return ".json (native); this build has no OpenCASCADE, so .step/.stp/.iges/.igs/.brep are refused";
#endif
}

std::optional<Model> load_model(const std::string& path, std::string* error) {
#ifdef KINTSUGI_HAVE_OCCT
  // Free-form faces (a .json holding them, or the native document a bounded STEP/BREP
  // read hands back) need the backend in this process too: the Python package and batch
  // load models without going through run_kintsugi.
  geo::occt::register_freeform_backend();
#endif
  auto fmt = format_of(path, error);
  if (!fmt) return std::nullopt;
  if (*fmt == "json") {
    auto doc = io::read_native_file(path, error);
    if (!doc) return std::nullopt;
    Model m{std::move(doc->body), std::move(doc->meta), doc->units, "json"};
    return m;
  }
#ifdef KINTSUGI_HAVE_OCCT
  auto imp = import_cad_bounded(path, cad_format(*fmt), error);
  if (!imp) return std::nullopt;
  Model m;
  m.body = std::move(imp->body);
  m.units = imp->units;
  m.format = *fmt;
  return m;
#else
  *error = path + ": this build of kintsugi has no OpenCASCADE, so it cannot read " + *fmt + " files";
  return std::nullopt;
#endif
}

bool save_model(const Model& m, const std::string& path, const std::string& input, std::string* error) {
  auto fmt = format_of(path, error);
  if (!fmt) return false;
  if (*fmt == "json") return io::write_native_file(path, m.body, m.meta, m.units, error, input);  // streamed
#ifdef KINTSUGI_HAVE_OCCT
  std::error_code ec;
  if (!input.empty() && std::filesystem::exists(path, ec) && std::filesystem::equivalent(path, input, ec)) {
    *error = path + ": refusing to overwrite the input file";
    return false;
  }
  // Export to a temporary file beside the target, then rename: never a partial output.
  std::filesystem::path target(path);
  std::filesystem::path tmp = target.parent_path() / ("." + target.filename().string() + ".tmp" + std::to_string(::getpid()) + target.extension().string());
  // The shape's tolerances are the model's modelling precision when its tolerance is known
  // (beautify records it in meta): the precision the model is consistent to.
  double precision = 0;
  if (auto t = m.meta.find("tolerance"); t != m.meta.end() && t->is_number() && t->get<double>() > 0)
    precision = geo::Tolerances::for_model(t->get<double>(), model_size(m.body)).precision;
  if (!io::export_cad(m.body, tmp.string(), cad_format(*fmt), error, m.units, precision)) {
    std::filesystem::remove(tmp, ec);
    return false;
  }
  std::filesystem::rename(tmp, target, ec);
  if (ec) {
    std::filesystem::remove(tmp, ec);
    *error = path + ": cannot write: " + ec.message();
    return false;
  }
  return true;
#else
  *error = path + ": this build of kintsugi has no OpenCASCADE, so it cannot write " + *fmt + " files";
  return false;
#endif
}

}  // namespace kintsugi::cli

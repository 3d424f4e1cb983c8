#include "apps/api.h"

#include "apps/report_json.h"
#include "apps/tolerance_choice.h"
#include "invariants/region_validity.h"
#include "invariants/topology_check.h"
#include "kernel/transaction.h"
#include "repair/beautify.h"
#include "repair/detect.h"
#include "repair/suggest_tolerance.h"
#ifdef KINTSUGI_HAVE_OCCT
#include "io/occt/exchange.h"
#endif

#include <chrono>
#include <cmath>
#include <sstream>

namespace kintsugi::api {

namespace {

using clock = std::chrono::steady_clock;
double seconds_since(clock::time_point t) { return std::chrono::duration<double>(clock::now() - t).count(); }

// `suggest`: without --tol or meta.tolerance, the tolerance the model suggests
// (repair/suggest_tolerance.h) rather than the size default; detect and beautify ask for
// it, check (which only needs the precision) does not.
cli::ToleranceChoice tolerance_for(const Model& m, std::optional<double> tol, std::string* note, bool suggest = false) {
  if (tol && !(std::isfinite(*tol) && *tol > 0)) throw Error("--tol must be a positive number");
  std::string error;
  auto choice = cli::choose_tolerance(m, tol, &error, suggest);
  if (!choice) throw Error(error);
  if (note) {
    note->clear();
    if (choice->source != "--tol") {
      std::ostringstream s;
      s << "tolerance " << choice->tol.length << " " << m.units << " from " << choice->source;
      *note = s.str();
    }
  }
  return *choice;
}

nlohmann::json beautify_timed(Model& m, std::optional<double> tol, const BeautifyOptions& options, std::string* note,
                              cli::BeautifyTimes& times, BeautifyDetail* detail = nullptr) {
  const auto chosen = clock::now();
  cli::ToleranceChoice choice = tolerance_for(m, tol, note, /*suggest=*/true);
  times.tolerance = seconds_since(chosen);
  kintsugi::BeautifyOptions o;
  o.check_topology_each_repair = options.check_topology_each_repair;
  if (detail) detail->before = m.body.clone();
  auto t = clock::now();
  BeautifyReport r;
  if (choice.trusted) {
#ifdef KINTSUGI_HAVE_OCCT
    // The validity gate also asks OpenCASCADE about every repaired region: the model must
    // still convert, and BRepCheck must pass on each repaired face that passed it on the
    // input (or is new).
    io::register_occt_region_check(m.body, choice.tol.precision);
    // Registered for this beautify only: the next caller in this process (the Python
    // package, batch) registers its own input's verdict.
    struct Unregister {
      ~Unregister() { set_external_region_check(nullptr); }
    } unregister;
#endif
    // One transaction around the run, so that it can be undone whole if the final
    // whole-body check finds what no repair's own checks did.
    Transaction whole(m.body);
    r = kintsugi::beautify(m.body, choice.tol, o);
    if (!o.check_topology_each_repair) {
      if (std::vector<Violation> v = check_topology(m.body); !v.empty()) {
        whole.rollback();
        o.check_topology_each_repair = true;
        if (note)
          *note += (note->empty() ? "" : "; ") + std::string("the whole-body check after the run found ") +
                   to_string(v.front()) + ": the run was repeated with the check after every repair";
        r = kintsugi::beautify(m.body, choice.tol, o);
      }
    }
    whole.commit();
    m.meta["tolerance"] = choice.tol.length;
    m.meta.erase("defects");  // the injector's record no longer describes the model
  } else {
    // No tolerance to trust: nothing destructive; the model is written as it was read.
    r.counts_before = r.counts_after = m.body.counts();
    if (note)
      *note += (note->empty() ? "" : "; ") +
               std::string("no repair made: without a tolerance the model's features do not separate into spurious and "
                           "intended ones (give --tol)");
  }
  times.beautify = seconds_since(t);
  // Recorded now; beautify_file fills in the write time after writing.
  nlohmann::json j = cli::beautify_json(r, choice, m.units, times);
  if (detail) {
    detail->report = std::move(r);
    detail->tol = choice.tol;
  }
  return j;
}

int count_action(const nlohmann::json& report, const char* action) {
  int n = 0;
  for (const auto& p : report.at("problems")) n += p.at("action") == action;
  return n;
}

}  // namespace

Model read_model(const std::string& path) {
  std::string error;
  auto m = cli::load_model(path, &error);
  if (!m) throw Error(error);
  return std::move(*m);
}

void write_model(const Model& model, const std::string& path, const std::string& input) {
  std::string error;
  if (!cli::save_model(model, path, input, &error)) throw Error(error);
}

nlohmann::json check(const Model& model, std::optional<double> tol, bool with_occt) {
#ifndef KINTSUGI_HAVE_OCCT
  if (with_occt) throw Error("this build has no OpenCASCADE, so --occt is not available");
#endif
  cli::ToleranceChoice choice = tolerance_for(model, tol, nullptr);
  return cli::check_json(cli::check_body(model.body, choice.tol, with_occt), choice);
}

nlohmann::json detect(const Model& model, std::optional<double> tol, std::string* tolerance_note, bool with_suggestion) {
  cli::ToleranceChoice choice = tolerance_for(model, tol, tolerance_note, /*suggest=*/true);
  nlohmann::json j = cli::detect_json(kintsugi::detect(model.body, choice.tol), choice, model.units);
  if (with_suggestion)
    j["suggested_tolerance"] = cli::suggestion_json(choice.suggestion ? *choice.suggestion : suggest_tolerance(model.body));
  return j;
}

nlohmann::json beautify(Model& model, std::optional<double> tol, const BeautifyOptions& options,
                        std::string* tolerance_note) {
  cli::BeautifyTimes times;
  return beautify_timed(model, tol, options, tolerance_note, times);
}

nlohmann::json beautify_file(const std::string& in, const std::string& out, std::optional<double> tol,
                             const BeautifyOptions& options, std::string* tolerance_note, BeautifyDetail* detail) {
  cli::BeautifyTimes times;
  auto t = clock::now();
  Model m = read_model(in);
  times.read = seconds_since(t);
  nlohmann::json report = beautify_timed(m, tol, options, tolerance_note, times, detail);
  t = clock::now();
  write_model(m, out, in);
  report["seconds"]["write"] = seconds_since(t);
  if (detail) detail->after = std::move(m.body);
  return report;
}

int repaired_count(const nlohmann::json& report) { return count_action(report, "repaired"); }
int not_repaired_count(const nlohmann::json& report) { return count_action(report, "not repaired"); }

}  // namespace kintsugi::api

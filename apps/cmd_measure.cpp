#include "apps/args.h"
#include "apps/commands.h"
#include "apps/model_files.h"
#include "apps/tolerance_choice.h"
#include "geometry/types.h"
#include "invariants/element_geometry.h"

#include <iomanip>
#include <ostream>

namespace kintsugi::cli {

namespace {
const char* kHelp =
    "usage: kintsugi measure FILE [--json] [--tol T]\n\n"
    "Prints, per face, its surface type, area, bounding-box diagonal and centroid; per\n"
    "edge, its length; and the body's total area. Curved boundaries are sampled with a\n"
    "chordal error of 1e-3 x the tolerance (--tol, else meta.tolerance, else 1e-3 x the\n"
    "model size), so areas of curved faces are exact to about that relative amount;\n"
    "edge lengths are exact for lines and circles.\n\n"
    "  --json   one JSON document: {\"area\", \"faces\": [{\"id\", \"surface\", \"area\",\n"
    "           \"bbox_diagonal\", \"centroid\"}], \"edges\": [{\"id\", \"length\"}]}\n"
    "Exit: 0 measured, 2 unreadable input, bad usage, or a face that cannot be measured.\n";
}

int cmd_measure(const std::vector<std::string>& argv, std::ostream& out, std::ostream& err) {
  Args args;
  std::string error;
  if (!args.parse(argv, {"--tol"}, {"--json", "--help"}, &error)) {
    err << "kintsugi measure: " << error << "\n" << kHelp;
    return kExitBadInput;
  }
  if (args.has("--help")) {
    out << kHelp;
    return kExitOk;
  }
  if (args.positional().size() != 1) {
    err << "kintsugi measure: expected one FILE\n" << kHelp;
    return kExitBadInput;
  }
  auto given = args.number("--tol", 0, &error);
  if (!given || (args.has("--tol") && *given <= 0)) {
    err << "kintsugi measure: " << (error.empty() ? "--tol must be positive" : error) << "\n";
    return kExitBadInput;
  }
  auto model = load_model(args.positional()[0], &error);
  if (!model) {
    err << "kintsugi measure: " << error << "\n";
    return kExitBadInput;
  }
  auto choice = choose_tolerance(*model, args.has("--tol") ? given : std::nullopt, &error);
  if (!choice) {
    err << "kintsugi measure: " << error << "\n";
    return kExitBadInput;
  }
  const Body& b = model->body;
  // Far finer than any decision needs, far coarser than the precision (which would make
  // tens of thousands of points per circle).
  double chordal = choice->tol.measure_chordal();
  nlohmann::json faces = nlohmann::json::array(), edges = nlohmann::json::array();
  double total = 0;
  int failed = 0;
  for (FaceH f : b.faces()) {
    geo::RegionMeasure m = face_measure(b, f, chordal);
    nlohmann::json j = {{"id", f.str()}, {"surface", geo::surface_type_name(b.surface(f))}};
    if (m.ok()) {
      j["area"] = m.area;
      j["bbox_diagonal"] = m.bounds.diagonal();
      j["centroid"] = {m.centroid.x(), m.centroid.y(), m.centroid.z()};
      total += m.area;
    } else {
      j["problem"] = m.problem;
      ++failed;
    }
    faces.push_back(j);
  }
  for (EdgeH e : b.edges()) edges.push_back({{"id", e.str()}, {"length", edge_length(b, e)}});
  if (args.has("--json")) {
    nlohmann::json j = {{"area", total}, {"faces", faces}, {"edges", edges}, {"units", model->units}};
    out << j.dump(2) << "\n";
  } else {
    out << std::setprecision(10);
    out << "faces (" << model->units << "):\n";
    for (const auto& f : faces) {
      out << "  " << f["id"].get<std::string>() << "  " << f["surface"].get<std::string>();
      if (f.contains("area"))
        out << "  area " << f["area"].get<double>() << "  bbox diagonal " << f["bbox_diagonal"].get<double>()
            << "  centroid (" << f["centroid"][0].get<double>() << ", " << f["centroid"][1].get<double>() << ", "
            << f["centroid"][2].get<double>() << ")\n";
      else
        out << "  not measured: " << f["problem"].get<std::string>() << "\n";
    }
    out << "edges:\n";
    for (const auto& e : edges) out << "  " << e["id"].get<std::string>() << "  length " << e["length"].get<double>() << "\n";
    out << "total area " << total << "\n";
  }
  if (failed) {
    err << "kintsugi measure: " << failed << " face(s) could not be measured\n";
    return kExitBadInput;
  }
  return kExitOk;
}

}  // namespace kintsugi::cli

#include "apps/args.h"
#include "apps/commands.h"
#include "apps/model_files.h"
#include "invariants/element_geometry.h"
#include "problems/problem_type.h"
#include "zoo/zoo.h"

#include <algorithm>
#include <ostream>

namespace kintsugi::cli {

namespace {

std::string type_names() {
  std::string s;
  for (ProblemType t : kAllProblemTypes) s += std::string(s.empty() ? "" : ", ") + problem_name(t);
  return s;
}

void help(std::ostream& os) {
  os << "usage: kintsugi inject IN --type NAME [--seed S] [--at HANDLE] [--tol T] -o OUT\n\n"
        "Reads the model IN, inserts one defect of type NAME the way reverse engineering makes it\n"
        "(Euler operators, vertices where the fitted surfaces meet; spec/defects.md), and writes\n"
        "OUT with the defect appended to meta.defects ({type, elements, size}).\n\n"
        "  --type NAME   one of: "
     << type_names()
     << "\n"
        "  --seed S      0 .. 2^63-1 (default 1): picks the place and the sizes; same seed, same result\n"
        "  --at HANDLE   put the defect at this element: a face (fN), edge (eN) or vertex (vN),\n"
        "                whichever the type needs (a face also offers its edges and vertices)\n"
        "  --tol T       the tolerance; the defect's size is below it. Default: meta.tolerance of\n"
        "                IN, else 1% of the model size (then written to meta.tolerance)\n"
        "  -o OUT        output file (never the input). Formats: "
     << formats_supported()
     << "\n\n"
        "Most types need planar faces and straight edges near the place; short_edge needs a\n"
        "vertex of degree 4 or more with a triangular face (e.g. a pyramid apex).\n"
        "Exit: 0 done, 2 bad usage, unreadable input, unknown type, or no suitable place.\n";
}

}  // namespace

int cmd_inject(const std::vector<std::string>& argv, std::ostream& out, std::ostream& err) {
  Args args;
  std::string error;
  if (!args.parse(argv, {"--type", "--seed", "--at", "--tol", "-o"}, {"--help"}, &error)) {
    err << "kintsugi inject: " << error << "\n";
    help(err);
    return kExitBadInput;
  }
  if (args.has("--help")) {
    help(out);
    return kExitOk;
  }
  if (args.positional().size() != 1) {
    err << "kintsugi inject: expected one input file\n";
    help(err);
    return kExitBadInput;
  }
  auto type_name = args.value("--type");
  if (!type_name) {
    err << "kintsugi inject: --type NAME is required (" << type_names() << ")\n";
    return kExitBadInput;
  }
  auto type = problem_from_name(*type_name);
  if (!type) {
    err << "kintsugi inject: unknown defect type '" << *type_name << "' (known: " << type_names() << ")\n";
    return kExitBadInput;
  }
  auto path = args.value("-o");
  if (!path) {
    err << "kintsugi inject: -o OUT is required\n";
    return kExitBadInput;
  }
  auto seed = args.integer("--seed", 1, 0, (1LL << 62) + ((1LL << 62) - 1), &error);
  if (!seed) {
    err << "kintsugi inject: " << error << "\n";
    return kExitBadInput;
  }
  const std::string& in = args.positional()[0];
  auto model = load_model(in, &error);
  if (!model) {
    err << "kintsugi inject: " << error << "\n";
    return kExitBadInput;
  }
  if (!model->meta.is_object()) model->meta = nlohmann::json::object();
  double tol;
  if (args.has("--tol")) {
    auto t = args.number("--tol", 0, &error);
    if (!t || !(*t > 0)) {
      err << "kintsugi inject: " << (t ? "--tol must be positive" : error) << "\n";
      return kExitBadInput;
    }
    tol = *t;
  } else if (model->meta.contains("tolerance") && model->meta["tolerance"].is_number()) {
    tol = model->meta["tolerance"].get<double>();
  } else {
    tol = 0.01 * model_size(model->body);
    err << "kintsugi inject: " << in << " has no meta.tolerance; using 1% of the model size, " << tol
        << " (written to meta.tolerance)\n";
    model->meta["tolerance"] = tol;
  }
  if (!(tol > 0)) {
    err << "kintsugi inject: the tolerance must be positive (the model is empty?)\n";
    return kExitBadInput;
  }
  std::string why;
  auto made = zoo::inject(model->body, *type, std::uint64_t(*seed), args.value("--at"), tol, &why);
  if (!made) {
    err << "kintsugi inject: " << why << "\n";
    return kExitBadInput;
  }
  if (!model->meta.contains("defects") || !model->meta["defects"].is_array()) model->meta["defects"] = nlohmann::json::array();
  model->meta["defects"].push_back(zoo::defect_json(made->defect));
  if (!save_model(*model, *path, in, &error)) {
    err << "kintsugi inject: " << error << "\n";
    return kExitBadInput;
  }
  out << made->description << "\n";
  return kExitOk;
}

}  // namespace kintsugi::cli

// kintsugi-bench occt-heal: our beautify against the OpenCASCADE healing a user would
// otherwise run, side by side in one run on the same STEP file (issue 18).
//
// The scalable family (zoo::family) is written to STEP once. Then, each in a child
// process of its own (so each peak memory is its own):
//   kintsugi:     io::import_cad (STEP → our body), beautify as `kintsugi beautify` runs it
//                 (the OpenCASCADE half of the validity gate registered, the whole-body
//                 topology check once at the end);
//   OpenCASCADE:  STEPControl_Reader (read and transfer), ShapeFix_Shape, then
//                 ShapeUpgrade_UnifySameDomain (faces, edges, concatenated B-splines off).
// Writing is left out: both would write through OpenCASCADE's STEPControl_Writer, which
// is quadratic in a face's edges (TopoDSToStep_MakeStepEdge takes the face's UV bounds,
// over all its edges, for each edge): the family's plate made the 10,000-face export
// take minutes. The STEP file is therefore kept in D and reused by the next run with the
// same faces, rate and seed.
// The two heal steps are compared as a ratio. They do not do the same work: ShapeFix fixes
// what makes a shape invalid (tolerances, wires, orientation) and UnifySameDomain merges
// faces and edges on one surface or curve; neither removes a small face, a sliver, a
// short edge or a gap. The face, edge and vertex counts after each say what each left.
#include "bench/bench_child.h"
#include "bench/occt_heal_bench.h"
#include "invariants/element_geometry.h"
#include "invariants/topology_check.h"
#include "io/occt/exchange.h"
#include "repair/beautify.h"
#include "zoo/zoo.h"

#include <BRepCheck_Analyzer.hxx>
#include <STEPControl_Reader.hxx>
#include <ShapeFix_Shape.hxx>
#include <ShapeUpgrade_UnifySameDomain.hxx>
#include <Standard_Failure.hxx>
#include <TopExp.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopoDS_Shape.hxx>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <sstream>
#include <string>

namespace kintsugi::bench {

namespace {

nlohmann::ordered_json shape_counts(const TopoDS_Shape& s) {
  TopTools_IndexedMapOfShape f, e, v;
  TopExp::MapShapes(s, TopAbs_FACE, f);
  TopExp::MapShapes(s, TopAbs_EDGE, e);
  TopExp::MapShapes(s, TopAbs_VERTEX, v);
  return {{"faces", f.Extent()}, {"edges", e.Extent()}, {"vertices", v.Extent()}};
}

nlohmann::ordered_json body_counts(const Body& b) {
  const auto c = b.counts();
  return {{"faces", c.faces}, {"edges", c.edges}, {"vertices", c.vertices}};
}

nlohmann::ordered_json ours(const std::string& step, double tolerance) {
  using clock = std::chrono::steady_clock;
  nlohmann::ordered_json j;
  auto t0 = clock::now();
  std::string error;
  auto in = io::import_cad(step, io::CadFormat::step, &error);
  if (!in) return {{"error", error}};
  j["read_seconds"] = seconds_since(t0);
  j["before"] = body_counts(in->body);
  t0 = clock::now();
  const geo::Tolerances tol = geo::Tolerances::for_model(tolerance, model_size(in->body));
  io::register_occt_region_check(in->body, tol.precision);
  BeautifyOptions o;
  o.check_topology_each_repair = false;
  const BeautifyReport r = beautify(in->body, tol, o);
  const bool valid = check_topology(in->body).empty();
  j["heal_seconds"] = seconds_since(t0);
  j["repaired"] = r.repaired();
  j["not_repaired"] = r.not_repaired();
  if (!valid) j["error"] = "the beautified body fails the topology check";
  j["after"] = body_counts(in->body);
  return j;
}

nlohmann::ordered_json occt(const std::string& step) {
  using clock = std::chrono::steady_clock;
  nlohmann::ordered_json j;
  try {
    auto t0 = clock::now();
    STEPControl_Reader reader;
    if (reader.ReadFile(step.c_str()) != IFSelect_RetDone) return {{"error", step + ": OpenCASCADE cannot read it"}};
    reader.TransferRoots();
    TopoDS_Shape s = reader.OneShape();
    j["read_seconds"] = seconds_since(t0);
    j["before"] = shape_counts(s);
    t0 = clock::now();
    Handle(ShapeFix_Shape) fix = new ShapeFix_Shape(s);
    fix->Perform();
    s = fix->Shape();
    j["shapefix_seconds"] = seconds_since(t0);
    auto t1 = clock::now();
    ShapeUpgrade_UnifySameDomain unify(s, true, true, false);
    unify.Build();
    s = unify.Shape();
    j["unify_seconds"] = seconds_since(t1);
    j["heal_seconds"] = seconds_since(t0);
    j["after"] = shape_counts(s);
    BRepCheck_Analyzer check(s);
    j["valid"] = bool(check.IsValid());
  } catch (const Standard_Failure& e) {
    return {{"error", std::string("OpenCASCADE: ") + e.GetMessageString()}};
  }
  return j;
}

void print(const std::string& who, const nlohmann::ordered_json& r) {
  std::cout << who << ": ";
  if (r.contains("error")) {
    std::cout << r["error"].get<std::string>() << "\n";
    return;
  }
  std::cout << "read " << r["read_seconds"] << " s, heal " << r["heal_seconds"] << " s; faces " << r["before"]["faces"] << " -> " << r["after"]["faces"] << ", edges "
            << r["before"]["edges"] << " -> " << r["after"]["edges"] << ", vertices " << r["before"]["vertices"]
            << " -> " << r["after"]["vertices"] << "; peak RSS " << r["peak_rss_bytes"].get<double>() / 1e6 << " MB\n";
}

}  // namespace

int bench_occt_heal(long long faces, double rate, long long seed, const std::string& dir) {
  std::ostringstream name;
  name << dir << "/kintsugi-bench-family-" << faces << "-" << rate << "-" << seed << ".step";
  const std::string step = name.str();
  nlohmann::ordered_json made = json_in_child([&]() -> nlohmann::ordered_json {
    zoo::ZooModel m = zoo::family(std::size_t(faces), rate, std::uint64_t(seed));
    std::error_code ec;
    if (!std::filesystem::exists(step, ec)) {
      std::cerr << "kintsugi-bench occt-heal: writing the family with " << faces << " faces to " << step
                << " (OpenCASCADE's STEP writer: minutes at 10,000 faces; kept for the next run)...\n";
      std::string error;
      if (!io::export_cad(m.body, step, io::CadFormat::step, &error)) return {{"error", error}};
    }
    return {{"faces", m.body.counts().faces}, {"tolerance", m.tolerance}, {"defects", m.defects.size()}};
  });
  if (made.contains("error")) {
    std::cout << "making the model: " << made["error"].get<std::string>() << "\n";
    return 1;
  }
  const double tolerance = made["tolerance"].get<double>();
  std::cerr << "kintsugi-bench occt-heal: kintsugi...\n";
  const nlohmann::ordered_json a = json_in_child([&] { return ours(step, tolerance); });
  std::cerr << "kintsugi-bench occt-heal: OpenCASCADE...\n";
  const nlohmann::ordered_json b = json_in_child([&] { return occt(step); });
  std::cout << made["faces"] << " faces, " << made["defects"] << " defects, tolerance " << tolerance << ", "
            << std::filesystem::file_size(step) / 1e6 << " MB of STEP (" << step << ")\n";
  print("kintsugi   ", a);
  print("OpenCASCADE", b);
  nlohmann::ordered_json j = {{"model", made}, {"kintsugi", a}, {"opencascade", b}};
  int code = 0;
  if (!a.contains("error") && !b.contains("error")) {
    const double ratio = a["heal_seconds"].get<double>() / b["heal_seconds"].get<double>();
    j["heal_ratio"] = ratio;
    std::cout << "heal time, kintsugi / OpenCASCADE (ShapeFix_Shape + UnifySameDomain): " << ratio << "\n";
  } else {
    code = 1;
  }
  std::cout << j.dump() << "\n";
  return code;
}

}  // namespace kintsugi::bench

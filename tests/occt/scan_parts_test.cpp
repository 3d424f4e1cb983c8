// An external-style score of beautification: designer parts built with OpenCASCADE's own
// modelling operators (tests/support/occt_parts.h), defects injected the way scans make
// them (zoo::inject, each of the eleven types in turn, and some cases with 2-3 defects), a
// random rigid motion, a STEP round trip, beautify, and an honest judgement against the
// designer's part moved the same way:
//   - the output is a valid closed solid (check_topology, one shell, no border cycle, its
//     faces' loops neither crossing nor touching (loop_violations), OpenCASCADE's BRepCheck);
//   - its vertex, edge, face and loop counts are the designer's;
//   - its faces match the designer's one to one (each output face to the designer face its
//     tessellation lies nearest to on average) and the matched faces share edges exactly
//     where the designer's do;
//   - the two-sided distance to the designer's part is within the tolerance;
//   - written as STEP the way the command line writes it, OpenCASCADE's reader finds one
//     valid closed solid in the file, and ours reads back the same counts ("step" if not).
// The table printed per problem type says how many cases passed and why the others failed.
// KINTSUGI_SCAN_CASES=N runs N cases instead of the default (scripts/scan_parts_score.sh).
#include "geometry/tolerance.h"
#include "invariants/element_geometry.h"
#include "invariants/topology_check.h"
#include "invariants/region_validity.h"
#include "io/native_json.h"
#include "io/occt/exchange.h"
#include "repair/beautify.h"
#include "repair/detect.h"
#include "tests/occt/compare.h"
#include "tests/support/occt_parts.h"
#include "tests/support/two_sided_distance.h"
#include "zoo/random.h"
#include "zoo/zoo.h"

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Simple_cartesian.h>
#include <Message.hxx>
#include <Message_Messenger.hxx>
#include <BRepCheck_Analyzer.hxx>
#include <BRep_Tool.hxx>
#include <STEPControl_Reader.hxx>
#include <STEPControl_Writer.hxx>
#include <TopExp.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopoDS.hxx>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <memory>
#include <set>
#include <sstream>
#include <tuple>

namespace kintsugi {
namespace {

using K = CGAL::Simple_cartesian<double>;
using Triangle = K::Triangle_3;
using Primitive = CGAL::AABB_triangle_primitive<K, std::vector<Triangle>::iterator>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<K, Primitive>>;

K::Point_3 pt(const geo::Vec3& v) { return K::Point_3(v.x(), v.y(), v.z()); }

struct FaceMesh {
  std::vector<Triangle> tris;
  std::unique_ptr<Tree> tree;
};

std::vector<FaceMesh> face_meshes(const Body& b, double chordal) {
  std::vector<FaceMesh> out;
  for (FaceH f : b.faces()) {
    FaceMesh fm;
    geo::RegionMeasure m = face_measure(b, f, chordal);
    for (const auto& t : m.mesh.triangles)
      fm.tris.emplace_back(pt(m.mesh.vertices[std::size_t(t[0])]), pt(m.mesh.vertices[std::size_t(t[1])]),
                           pt(m.mesh.vertices[std::size_t(t[2])]));
    if (!fm.tris.empty()) {
      fm.tree = std::make_unique<Tree>(fm.tris.begin(), fm.tris.end());
      fm.tree->accelerate_distance_queries();
    }
    out.push_back(std::move(fm));
  }
  return out;
}

// Each face of `out` matched to the face of `designer` its tessellation lies nearest to
// (mean distance of its triangles' centroids); empty and *why set when a face cannot be
// tessellated. Indices are positions in faces().
std::vector<int> match_faces(const std::vector<FaceMesh>& out, const std::vector<FaceMesh>& designer, std::string* why) {
  std::vector<int> match;
  for (std::size_t i = 0; i < out.size(); ++i) {
    const FaceMesh& f = out[i];
    if (f.tris.empty()) return *why = "output face " + std::to_string(i) + " has no tessellation", std::vector<int>{};
    std::size_t stride = std::max<std::size_t>(1, f.tris.size() / 64);
    int best = -1;
    double best_d = 1e300;
    for (std::size_t j = 0; j < designer.size(); ++j) {
      if (!designer[j].tree) continue;
      double sum = 0;
      int n = 0;
      for (std::size_t k = 0; k < f.tris.size(); k += stride) {
        K::Point_3 c = CGAL::centroid(f.tris[k]);
        sum += std::sqrt(designer[j].tree->squared_distance(c)), ++n;
      }
      if (sum / n < best_d) best_d = sum / n, best = int(j);
    }
    match.push_back(best);
  }
  return match;
}

std::set<std::pair<int, int>> adjacency(const Body& b, const std::vector<int>& face_index) {
  std::map<FaceH, int> pos;
  std::vector<FaceH> fs = b.faces();
  for (std::size_t i = 0; i < fs.size(); ++i) pos[fs[i]] = face_index.empty() ? int(i) : face_index[i];
  std::set<std::pair<int, int>> out;
  for (EdgeH e : b.edges()) {
    FaceH f0 = b.face(halfedge_of(e, 0)), f1 = b.face(halfedge_of(e, 1));
    if (!f0.valid() || !f1.valid()) continue;
    int a = pos[f0], c = pos[f1];
    out.insert({std::min(a, c), std::max(a, c)});
  }
  return out;
}

std::string str(const Counts& c) {
  return "V" + std::to_string(c.vertices) + " E" + std::to_string(c.edges) + " F" + std::to_string(c.faces) + " L" +
         std::to_string(c.loops) + " S" + std::to_string(c.shells) + " B" + std::to_string(c.border_cycles);
}

// Failure categories, in the order a case is judged (the first that applies is counted).
enum class Verdict { pass, step, refused, invalid, counts, adjacency, far, count_ };
const char* verdict_name(Verdict v) {
  switch (v) {
    case Verdict::pass: return "pass";
    case Verdict::step: return "step";
    case Verdict::refused: return "refused";
    case Verdict::invalid: return "invalid";
    case Verdict::counts: return "counts";
    case Verdict::adjacency: return "adjacency";
    case Verdict::far: return "far";
    case Verdict::count_: break;
  }
  return "?";
}

struct CaseResult {
  std::string label;  // problem type name, or "multi"
  Verdict verdict = Verdict::pass;
  std::string detail;
};

struct Designer {
  std::string name;
  Body body;
  double size = 0;
};

Eigen::Matrix3d random_rotation(zoo::Rng& rng) {
  Eigen::Quaterniond q;
  do {
    q = Eigen::Quaterniond(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1));
  } while (q.norm() < 0.1 || q.norm() > 1);
  return q.normalized().toRotationMatrix();
}

std::string describe_left(const BeautifyReport& r) {
  std::string s;
  for (const RepairEntry& e : r.problems)
    if (e.left()) {
      s += std::string(problem_name(e.problem.type)) + ": " + e.reason;
      break;
    }
  if (s.empty() && !r.left.empty()) s = std::string(problem_name(r.left[0].type)) + " left";
  return s;
}

// A written STEP file as OpenCASCADE's reader sees it: "" when it holds one solid with one
// closed shell that BRepCheck finds valid, else what is wrong.
std::string written_step_problem(const std::string& path) {
  STEPControl_Reader reader;
  if (reader.ReadFile(path.c_str()) != IFSelect_RetDone) return "unreadable";
  if (reader.TransferRoots() == 0) return "no shape transferred";
  const TopoDS_Shape shape = reader.OneShape();
  TopTools_IndexedMapOfShape solids, shells;
  TopExp::MapShapes(shape, TopAbs_SOLID, solids);
  TopExp::MapShapes(shape, TopAbs_SHELL, shells);
  if (solids.Extent() != 1 || shells.Extent() != 1)
    return std::to_string(solids.Extent()) + " solids, " + std::to_string(shells.Extent()) + " shells";
  if (!BRep_Tool::IsClosed(shells(1))) return "the shell is open";
  if (!BRepCheck_Analyzer(shape).IsValid()) return "BRepCheck_Analyzer: invalid";
  return "";
}

// One case: the defects, the motion, the STEP round trip, beautify, the judgement.
// nullopt when the case cannot be made (no place for the defect in this part, or the
// designer's part has problems of its own at this tolerance); *skip says which.
// What beautify made of a case (for ScanParts.ShortcutsChangeNothing).
ExternalRegionCheck g_wrapped_gate = nullptr;
geo::Tolerances g_case_tol{1.0, 1e-6};

struct Beautified {
  Body body;
  BeautifyReport report;
};

std::optional<CaseResult> run_case(const Designer& d, const std::vector<ProblemType>& types, std::uint64_t seed,
                                   std::string* skip, bool occt_gate = false, bool shortcuts = true,
                                   Beautified* kept = nullptr, double tol_factor = 1.0,
                                   ExternalRegionCheck wrap_gate = nullptr) {
  zoo::Rng rng(seed);
  const double t = std::exp(rng.uniform(std::log(0.05), std::log(2.0)));
  CaseResult res;
  res.label = types.size() == 1 ? problem_name(types[0]) : "multi";
  std::ostringstream id;
  id << d.name << " seed " << seed << " tol " << t << " [";
  for (ProblemType ty : types) id << problem_name(ty) << " ";
  id << "]";

  // The designer's model: the part, except that a pinch's block is a feature the designer
  // made flush with the edge it nearly touches (zoo::inject's clean twin). A pinch is
  // therefore injected first, into the designer's part itself.
  Body designer = d.body;
  Body b = d.body;
  std::vector<ProblemType> order = types;
  std::stable_partition(order.begin(), order.end(), [](ProblemType ty) { return ty == ProblemType::pinched_face; });
  for (std::size_t k = 0; k < order.size(); ++k) {
    std::string err;
    Body twin;
    const std::uint64_t inject_seed = rng.raw();
    // A face fitted twice is split planar faces by the injector's choice (it tries curved
    // ones only where no planar face suits); every other such case splits a cylinder or a
    // cone of the part along a ruling instead (a fillet or a hole in two pieces on one
    // surface), where the part has one that suits.
    std::optional<zoo::Injected> made;
    if (order[k] == ProblemType::same_geometry_faces) {
      zoo::Rng pick(inject_seed ^ 0xc0ffee);
      std::vector<FaceH> curved;
      for (FaceH f : b.faces())
        if (std::holds_alternative<geo::Cylinder>(b.surface(f)) || std::holds_alternative<geo::Cone>(b.surface(f)))
          curved.push_back(f);
      if (pick.below(2) == 0)
        for (std::size_t n = curved.size(); n > 0 && !made; --n) {
          std::swap(curved[n - 1], curved[pick.below(n)]);
          made = zoo::inject(b, order[k], inject_seed, curved[n - 1].str(), t, &err, &twin);
        }
    }
    if (!made) made = zoo::inject(b, order[k], inject_seed, std::nullopt, t, &err, &twin);
    if (!made) return *skip = id.str() + ": no place for " + problem_name(order[k]) + ": " + err, std::nullopt;
    if (!twin.faces().empty()) {
      if (k > 0) return *skip = id.str() + ": a second pinch (no designer's model for it)", std::nullopt;
      designer = std::move(twin);
    }
  }
  geo::Tolerances dtol = geo::Tolerances::for_model(t, d.size);
  if (Detection det = detect(designer, dtol); !det.problems.empty())
    return *skip = id.str() + ": designer part has " + std::to_string(det.problems.size()) + " problems", std::nullopt;
  Eigen::Matrix3d r = random_rotation(rng);
  Eigen::Vector3d tr(rng.uniform(-300, 300), rng.uniform(-300, 300), rng.uniform(-300, 300));
  test::transform(b, r, tr);
  test::transform(designer, r, tr);

  auto fail = [&](Verdict v, const std::string& why) {
    res.verdict = v;
    res.detail = id.str() + ": " + why;
    return res;
  };
  std::string path = test::temp_path("scan_" + std::to_string(seed) + ".step"), err;
  if (!io::export_cad(b, path, io::CadFormat::step, &err)) return fail(Verdict::step, "write: " + err);
  if (std::getenv("KINTSUGI_SCAN_KEEP"))  // the defective model as made, beside the STEP file
    io::write_native_file(path + ".json", b, nlohmann::json::object(), "mm", &err);
  std::optional<io::CadImport> in = io::import_cad(path, io::CadFormat::step, &err);
  if (!std::getenv("KINTSUGI_SCAN_KEEP")) std::remove(path.c_str());  // kept: to look at one case
  if (!in) return fail(Verdict::step, "read: " + err);
  Body out = std::move(in->body);

  BeautifyOptions opt;
  opt.check_topology_each_repair = false;
  opt.shortcuts = shortcuts;
  // occt_gate or KINTSUGI_SCAN_OCCT_GATE=1: with the OpenCASCADE half of the validity gate,
  // as the CLI runs it (io::register_occt_region_check), to see what it refuses.
  // tol_factor > 1 (ShortcutsChangeNothing): beautify at a tolerance above the case's, at
  // which the part's own features read as problems too, most of them refused.
  const geo::Tolerances run_tol = geo::Tolerances::for_model(tol_factor * t, model_size(out));
  if (occt_gate || std::getenv("KINTSUGI_SCAN_OCCT_GATE")) io::register_occt_region_check(out, run_tol.precision);
  // `wrap_gate`: a test's own external check, which may call the registered one (as
  // g_wrapped_gate) and the case's tolerance (g_case_tol).
  if (wrap_gate) {
    g_wrapped_gate = external_region_check();
    g_case_tol = run_tol;
    set_external_region_check(wrap_gate);
  }
  BeautifyReport rep = beautify(out, run_tol, opt);
  set_external_region_check(nullptr);
  if (kept) *kept = {out, rep};
  const std::string left = describe_left(rep);
  if (std::getenv("KINTSUGI_SCAN_KEEP")) {
    io::export_cad(out, path + ".out.step", io::CadFormat::step, &err, "mm", run_tol.precision);
    std::printf("case files: %s and %s.out.step\n", path.c_str(), path.c_str());
    io::OcctVerdict iv = io::occt_check(b);
    std::printf("  injected model: BRepCheck %s %s\n", iv.valid ? "valid" : "invalid",
                iv.problems.empty() ? "" : iv.problems[0].c_str());
    for (const RepairEntry& e : rep.problems)
      std::printf("  %s %s %s%s%s\n", problem_name(e.problem.type), outcome_name(e.outcome), e.reason.c_str(),
                  e.note.empty() ? "" : " | note: ", e.note.c_str());
    for (const std::string& o : zoo::geometry_offences(out, 1e-6 * t)) std::printf("  offence: %s\n", o.c_str());
    io::OcctVerdict ov = io::occt_check(out, run_tol.precision);
    for (const std::string& o : ov.problems) std::printf("  BRepCheck: %s\n", o.c_str());
  }

  // Judged in order; a failing case whose repair was refused or left problems counts as
  // "refused" (the reason is the first refusal), whatever else is wrong with it.
  auto judged = [&](Verdict v, const std::string& why) {
    return left.empty() ? fail(v, why) : fail(Verdict::refused, left + " (then " + verdict_name(v) + ": " + why + ")");
  };
  Counts c = out.counts(), want = designer.counts();
  std::vector<Violation> vs = check_topology(out);
  if (!vs.empty()) return judged(Verdict::invalid, to_string(vs[0]));
  if (c.shells != 1 || c.border_cycles != 0) return judged(Verdict::invalid, "not one closed shell: " + str(c));
  // Our own check of the faces' loops (what `kintsugi check` reports): crossing, touching.
  {
    const std::vector<FaceH> fs = out.faces();
    std::vector<Violation> lv = loop_violations(out, std::set<FaceH>(fs.begin(), fs.end()), run_tol);
    if (!lv.empty()) return judged(Verdict::invalid, to_string(lv[0]));
  }
  if (io::OcctVerdict ov = io::occt_check(out, run_tol.precision); !ov.valid)
    return judged(Verdict::invalid, "BRepCheck: " + (ov.problems.empty() ? std::string() : ov.problems[0]));
  if (!(c == want)) return judged(Verdict::counts, str(c) + " want " + str(want));

  // Tessellations within 0.1 t of the surfaces: the distances below are then exact to
  // about 0.1 t either way, small against the tolerance they are compared with.
  const double chordal = 0.1 * t;
  std::vector<FaceMesh> om = face_meshes(out, chordal), dm = face_meshes(designer, chordal);
  std::string why;
  std::vector<int> match = match_faces(om, dm, &why);
  if (match.empty()) return judged(Verdict::adjacency, why);
  if (std::set<int>(match.begin(), match.end()).size() != match.size())
    return judged(Verdict::adjacency, "two output faces nearest the same designer face");
  if (adjacency(out, match) != adjacency(designer, {})) return judged(Verdict::adjacency, "faces meet differently");

  test::TwoSided ts = test::two_sided_distance(designer, out, chordal);
  if (!ts.problem.empty()) return judged(Verdict::far, ts.problem);
  if (ts.max() > t) {
    std::ostringstream o;
    o << "two-sided distance " << ts.max() << " > " << t;
    return judged(Verdict::far, o.str());
  }
  // What a user gets is the file: written as the command line writes it (the shape's
  // tolerances the precision), read back by OpenCASCADE's reader as another program
  // would, it must be one valid closed solid, and read by us, the same counts.
  const std::string written = test::temp_path("scan_" + std::to_string(seed) + ".out.step");
  if (!io::export_cad(out, written, io::CadFormat::step, &err, "mm", run_tol.precision))
    return judged(Verdict::step, "output not written: " + err);
  std::string unread = written_step_problem(written);
  std::optional<io::CadImport> back = io::import_cad(written, io::CadFormat::step, &err);
  if (!std::getenv("KINTSUGI_SCAN_KEEP")) std::remove(written.c_str());
  if (!unread.empty()) return judged(Verdict::step, "output as read by OpenCASCADE: " + unread);
  if (!back) return judged(Verdict::step, "output read back: " + err);
  if (!(back->body.counts() == c)) return judged(Verdict::step, "output read back: " + str(back->body.counts()) + " written " + str(c));
  if (!left.empty()) res.detail = id.str() + ": passed although " + left;
  return res;
}

std::vector<Designer> designers() {
  Message::DefaultMessenger()->ChangePrinters().Clear();  // OpenCASCADE's transfer statistics
  std::vector<std::string> dropped;
  std::vector<Designer> out;
  for (test::OcctPart& p : test::occt_parts(&dropped)) {
    // Written and read as STEP once, as the designer's part would reach us.
    std::string path = test::temp_path("designer_" + p.name + ".step"), err;
    STEPControl_Writer w;
    bool ok = w.Transfer(p.shape, STEPControl_AsIs) == IFSelect_RetDone && w.Write(path.c_str()) == IFSelect_RetDone;
    std::optional<io::CadImport> in = ok ? io::import_cad(path, io::CadFormat::step, &err) : std::nullopt;
    if (!in) {
      dropped.push_back(p.name + ": " + (ok ? err : "OpenCASCADE could not write it"));
      continue;
    }
    // A part OpenCASCADE's own operators left invalid (a fillet between two cones is a
    // B-spline 3e-6 off its edges) is no designer's model to score repairs against.
    if (io::OcctVerdict v = io::occt_check(in->body); !v.valid) {
      dropped.push_back(p.name + ": not valid as read: " + (v.problems.empty() ? "" : v.problems[0]));
      continue;
    }
    Designer d{p.name, std::move(in->body), 0};
    d.size = model_size(d.body);
    out.push_back(std::move(d));
  }
  for (const std::string& s : dropped) std::printf("dropped part %s\n", s.c_str());
  return out;
}

// Case i of the run with seed base `base`: its part, its defect types, its seed. Slots
// 0-10 of every twelve cases are the eleven types in turn, slot 11 two or three random
// types; the parts rotate so that each type meets every part.
// `rotation`: how many of the parts (from the first) the cases rotate through; the
// regression cases below were found when there were kFirstParts. `all_multi`: every case
// two or three random types (KINTSUGI_SCAN_MULTI=1: defects together are where repairs
// meet each other's results).
std::tuple<const Designer*, std::vector<ProblemType>, std::uint64_t> plan(const std::vector<Designer>& parts,
                                                                         std::uint64_t base, int i,
                                                                         std::size_t rotation = 0,
                                                                         bool all_multi = false) {
  const std::uint64_t seed = base * 1000003ull + std::uint64_t(i);
  const int slot = all_multi ? 11 : i % 12;
  if (rotation == 0 || rotation > parts.size()) rotation = parts.size();
  const Designer* d = &parts[std::size_t(i / 12 + i) % rotation];
  std::vector<ProblemType> types;
  if (slot < 11) {
    types = {kAllProblemTypes[std::size_t(slot)]};
  } else {
    zoo::Rng pick(seed ^ 0x5ca9);
    for (std::size_t k = 0, m = 2 + pick.below(2); k < m; ++k) types.push_back(kAllProblemTypes[pick.below(11)]);
  }
  return {d, types, seed};
}

// The parts before the tee and the filleted post (session 22): the cases found then
// rotate through these.
constexpr std::size_t kFirstParts = 12;
// The parts before session 35 added thirteen: cases chosen then rotate through these.
constexpr std::size_t kPartsBeforeSession35 = 24;

// Regression cases the score found, each one case of a run (seed base, index), with the
// parts the run had.
void expect_case_passes(std::uint64_t base, int i, std::size_t rotation = kFirstParts) {
  std::vector<Designer> parts = designers();
  ASSERT_GE(parts.size(), rotation) << "a designer part could not be built";
  auto [d, types, seed] = plan(parts, base, i, rotation);
  std::string skip;
  std::optional<CaseResult> r = run_case(*d, types, seed, &skip);
  ASSERT_TRUE(r) << skip;
  EXPECT_EQ(r->verdict, Verdict::pass) << r->detail;
  EXPECT_EQ(r->detail, "") << "passed only despite a refusal";
}

// A chain of small faces notched into a fillet's edge (filleted_block, small_face_chain)
// is also, by the letter of the definition, a pinch of the face beside it (its boundary
// comes within the tolerance of itself across the notch), and pass 4 runs before pass 5.
// Closing that "pinch" would cut through the chain and turn the face inside out: the
// face-sense gate refuses it, and pass 5 then merges the chain, which removes the pinch.
// The report must say "resolved by a later repair", not "not repaired" (it did, until
// refused problems the output no longer has were relabelled). Excluding such pinches from
// detection instead was tried and reverted: pass 5 then *created* pinches (Table 1 audit,
// pyramid5, `kintsugi audit --trials 15 --seed 11 --pass small_face_chain`).
TEST(ScanParts, SmallFaceNotchPinchIsResolvedByTheChainRepair) { expect_case_passes(2, 64); }

// A pinch beside a spherical pocket: the repair refits the plate's plane, the pocket's
// rim vertex moves round the sphere's axis, and the sphere's seam (a meridian from the
// pole to that vertex) must follow it (detail::align_seams; refused before with "v11 from
// the curve of e17 is 1.92e-05 away").
TEST(ScanParts, SphereSeamFollowsItsRimVertex) { expect_case_passes(29, 15); }

// A gap at a fillet's tangent edge closes into one vertex: the edge between the plane
// and the fillet's cylinder is a ruling, which intersect() finds only to about 1e-5 (a
// double root); the chord through its vertices lies on both (refused before with "v13
// from the curve of e27 is 2.97e-05 away").
TEST(ScanParts, GapAtAFilletsTangentEdgeClosesOnTheRuling) { expect_case_passes(31, 86); }

// Edge gaps on a circular edge (a grooved ring's bore, a shaft's shoulder): the new
// edge is an arc of the circle where plane and cylinder meet, and it must be the arc the
// gap spans, not the rest of the circle. Its present curve (the gap's joined border) left
// the junction across the circle, so orienting by its tangent took the long way round:
// a loop crossing itself, a face inside out, or (without OpenCASCADE's gate) an output
// BRepCheck called unorientable. Now judged by the present curve's middle.
TEST(ScanParts, EdgeGapOnACircleClosesAlongTheShortArc) {
  expect_case_passes(29, 49);
  expect_case_passes(37, 169);
  expect_case_passes(37, 193);
}

// A bracket's boss zipped against the plate's long side: the two planes are tied into one
// in the region solve, and the long side must not tilt towards the small boss side (the
// samples of tied faces weigh by area; before, the plate's far corners moved 1.3
// tolerances and the pinch was refused).
TEST(ScanParts, ATiedPlaneFollowsTheLargerFace) {
  expect_case_passes(41, 111);
  expect_case_passes(47, 111);
}

// A countersink's rim 3.6e-7 off its cone after a pinch repair turned the top plane, within
// the precision of the tolerance: valid, and OpenCASCADE's check (now at the precision,
// not 1e-7) agrees; it called the cone face unorientable (session 18).
TEST(ScanParts, ARimWithinThePrecisionIsValidForOpenCascadeToo) { expect_case_passes(67, 51); }

// A multiple-face gap where a fillet ends on a side plane tangent to it: the three faces
// meet in one point, but two of them touch, so the meeting-point solve called it
// "underdetermined"; the gap was filled with a new face, inside out, and refused.
TEST(ScanParts, GapWhereAFilletEndsClosesInOneVertex) { expect_case_passes(67, 86); }

// A post's fillet (a torus) meets the top plane along a circle where they are tangent,
// and a pinch beside it zips a boss's side to that plane. Solved freely, the plane tilted
// by about 2e-8 rad with the boss's side tied to it: their circle left the torus by
// 5.7e-7 (precision 6.4e-8), and the seam vertex on it slid off its seam. The region
// solve now holds a seam's vertices on the seam and tangent faces tangent along their
// edge, and the plane stays where the fillet holds it.
TEST(ScanParts, APlaneTangentToAFilletStaysTangentThroughARepair) { expect_case_passes(131, 219); }

// A bracket's pinch (seed base 509, 14 parts): the region solve tilted a plane by a hair
// against a cylinder's axis (radius 8) that it met along a ruling, and their meeting line
// became an ellipse of major radius 3e5 with the edge's vertex at its tip. There the
// start tangent is square to the edge, and the arc taken ran the whole ellipse round: the
// plane's face turned inside out and the repair was refused. A derived piece that strays
// from where the edge was now goes the other way round.
TEST(ScanParts, AnEdgeAtAFlatEllipsesTipTakesTheArcAlongTheEdge) { expect_case_passes(509, 207, 14); }

// Keeps the parts named in `names` (comma-separated).
void keep_only(std::vector<Designer>& parts, const std::string& names) {
  const std::string only = "," + names + ",";
  std::erase_if(parts, [&](const Designer& d) { return only.find("," + d.name + ",") == std::string::npos; });
}

// Case i of seed base `base` among the named parts alone (KINTSUGI_SCAN_PARTS=names), on
// part `name`; with OpenCASCADE's checker in the gate when `occt_gate`.
void expect_case_of_parts_passes(const std::string& names, std::uint64_t base, int i, const std::string& name,
                                 bool occt_gate = false) {
  std::vector<Designer> parts = designers();
  keep_only(parts, names);
  ASSERT_EQ(parts.size(), std::size_t(std::count(names.begin(), names.end(), ',') + 1))
      << "a designer part could not be built";
  auto [d, types, seed] = plan(parts, base, i);
  ASSERT_EQ(d->name, name);
  std::string skip;
  std::optional<CaseResult> r = run_case(*d, types, seed, &skip, occt_gate);
  ASSERT_TRUE(r) << skip;
  EXPECT_EQ(r->verdict, Verdict::pass) << r->detail;
  EXPECT_EQ(r->detail, "") << "passed only despite a refusal";
}
// Among the five parts added in session 30.
void expect_session30_case_passes(std::uint64_t base, int i, const std::string& name) {
  expect_case_of_parts_passes("rounded_box,slotted_plate,stepped_shaft,hole_plate,cone_boss", base, i, name);
}

// Case i of seed base `base`, the cases rotating through the first `rotation` parts, run
// as the command line runs it (OpenCASCADE's checker in the gate); `all_multi`: every case
// two or three defects (KINTSUGI_SCAN_MULTI=1).
void expect_gated_case_passes(std::uint64_t base, int i, std::size_t rotation, const std::string& name,
                              bool all_multi) {
  std::vector<Designer> parts = designers();
  ASSERT_GE(parts.size(), rotation) << "a designer part could not be built";
  auto [d, types, seed] = plan(parts, base, i, rotation, all_multi);
  ASSERT_EQ(d->name, name);
  std::string skip;
  std::optional<CaseResult> r = run_case(*d, types, seed, &skip, /*occt_gate=*/true);
  ASSERT_TRUE(r) << skip;
  EXPECT_EQ(r->verdict, Verdict::pass) << r->detail;
  EXPECT_EQ(r->detail, "") << "passed only despite a refusal";
}

// A repair that leaves a face's loop touching itself is kept provisionally: a later repair
// must remove the touch, or the run is undone. OpenCASCADE's checker, the gate's other
// half, calls such a face unorientable, and refused the repair that a later one would
// have completed: spherical_pocket (a pinch, a sliver and a small-face chain: pass 8's
// merge leaves the spike the sliver's repair then removes) and filleted_post (a face gap,
// a sliver and a pinch). The external check now sees a provisional face once its touch
// is gone (Region::provisional, beautify's settle), and these pass as they did without it.
TEST(ScanParts, ATouchKeptProvisionallyIsPutToOpenCascadeOnceItIsGone) {
  expect_gated_case_passes(14, 159, 24, "spherical_pocket", /*all_multi=*/true);
  expect_gated_case_passes(8, 57, 24, "filleted_post", /*all_multi=*/true);
}

// The other way: a face kept from the checker while it touched, and refused by it once
// the touch is gone, leaves its repair unsettled, and the run is undone. The checker here
// is OpenCASCADE's made stricter: a face whose loop has touched itself is refused the
// second time it is asked about after the touch is gone (the first is the gate of the
// repair that removed the touch, which lets that repair through; the second is beautify
// settling the repair that made the touch), once. The repair that made the touch is
// refused with that reason in the run done again, and the model comes out valid.
std::map<std::uint32_t, int> g_asked_since_touch;  // faces that have touched: times asked since
std::string refuses_what_touched(const Body& b, const Region& r) {
  for (FaceH f : r.faces) {
    bool touches = false;
    for (const Violation& v : loop_violations(b, {f}, g_case_tol))
      touches = touches || v.invariant == "loop_touches_itself" || v.invariant == "loops_touch";
    if (touches) {
      g_asked_since_touch[f.idx()] = 0;
    } else if (auto it = g_asked_since_touch.find(f.idx()); it != g_asked_since_touch.end() && ++it->second == 2) {
      return f.str() + " has touched itself";
    }
  }
  return g_wrapped_gate ? g_wrapped_gate(b, r) : "";
}

TEST(ScanParts, AFaceTheCheckerRefusesOnceItsTouchIsGoneUndoesItsRepair) {
  std::vector<Designer> parts = designers();
  ASSERT_GE(parts.size(), 24u) << "a designer part could not be built";
  auto [d, types, seed] = plan(parts, 14, 159, 24, /*all_multi=*/true);
  ASSERT_EQ(d->name, "spherical_pocket");
  g_asked_since_touch.clear();
  std::string skip;
  Beautified kept;
  std::optional<CaseResult> r =
      run_case(*d, types, seed, &skip, /*occt_gate=*/true, /*shortcuts=*/true, &kept, 1.0, &refuses_what_touched);
  ASSERT_TRUE(r) << skip;
  EXPECT_FALSE(g_asked_since_touch.empty()) << "no repair left a loop touching: the test no longer reaches its path";
  bool undone = false;
  for (const RepairEntry& e : kept.report.problems)
    undone = undone || (e.outcome == Outcome::refused &&
                        e.reason.find("once later repairs had removed the touch they were not valid") != std::string::npos);
  std::string all;
  for (const RepairEntry& e : kept.report.problems) all += std::string(problem_name(e.problem.type)) + " " + outcome_name(e.outcome) + ": " + e.reason + " / " + e.note + "\n";
  EXPECT_TRUE(undone) << r->detail << "\n" << all;
  EXPECT_NE(r->verdict, Verdict::invalid) << r->detail;
  EXPECT_NE(r->verdict, Verdict::step) << r->detail;
}

// A cone (cone_boss) and a cylinder (tee) each fitted twice, split along two rulings, one
// of them also cut by a gap (cone_boss) or by a vertex a mergeable-edges defect put on it
// (tee). Pass 8 keeps as the merged face's seam the ruling whose ends carry more edges,
// but counted the ends of each piece: the gap's closed edge, whose own ends lay on two
// edges each, was killed first and its whole ruling with it — the one where the fillet's
// torus seam (the stub's circle) met the circle. The kept ruling met the circle elsewhere,
// and the circle came out with a vertex too many. The ends are now those of the run of
// common edges (pass_same_geometry.cpp).
TEST(ScanParts, AMergedFaceKeepsAsItsSeamTheRulingWhoseRunEndsCarryMoreEdges) {
  expect_gated_case_passes(2, 17, 24, "cone_boss", /*all_multi=*/true);
  expect_gated_case_passes(2, 78, 24, "tee", /*all_multi=*/true);
}

// A thin cone band scanned round the shaft's shoulder circle (a ring sliver) whose circle
// on the cylinder's side a short-edge chain has cut into five pieces. Pass 6 took a band
// only when both its closed edges were single edges; this one fell through to the general
// collapse, which stops at its seam ("f8 meets itself along e17"), and pass 7 comes too
// late. The pieces (vertices on two edges between the band and one face) are now joined
// first (ring_sliver, pass_sliver_face.cpp).
TEST(ScanParts, ARingSliverWhoseCircleAChainCutIntoPiecesIsStillARing) {
  expect_gated_case_passes(10, 3, 24, "shaft", /*all_multi=*/true);
}

// The shaft's cylinder fitted twice, with a multiple-face gap where one of the two rulings
// between its pieces meets the circle under the cone, and an edge gap elsewhere. Pass 3
// cannot close the gap (its faces include both pieces, whose surfaces do not intersect);
// pass 8 merges them and keeps that ruling as the seam, which leaves an edge gap whose
// border on the cylinder's side passes the seam's end. Closing it needed each side to be
// one edge ("v12 inside the gap's border lies on 3 edges"); the other side is now split
// to match and the two zipped at that vertex (zip_at, repair/gap_closing.cpp).
TEST(ScanParts, AnEdgeGapWhoseBorderPassesASeamsEndClosesThroughIt) {
  expect_gated_case_passes(1, 3, 24, "shaft", /*all_multi=*/true);
}

// A multiple-face gap at a corner of a box rounded on every edge, where its flat face, two
// fillet cylinders and the corner's sphere all touch (one normal for the four): meet_point
// found a point within 2e-10 of every surface but 3.8e-5 off their contact curves (at a
// tangent contact the distance grows with the square of the offset), and the validity gate
// refused the vertex. Where the surfaces are nearly tangent the gap's vertex is now where
// the curves of the edges running into it cross (`where_edges_meet`, repair/gap_closing.cpp).
TEST(ScanParts, AGapWhereFourTangentFacesMeetClosesWhereTheirEdgesCross) {
  expect_session30_case_passes(1, 47, "rounded_box");
}

// A pinch, a short-edge chain and a chain of five small faces along the roofed block's
// boss, the chain on the edge between the side the pinch moves and its neighbour. The
// pinch's solve moves that side 0.046, and the chain's end faces grow: one stays small,
// one becomes a sliver, so pass 5 gets the middle three. Where their vertex meets the
// sliver's plane (fitted to a few points, nearly parallel to the edge) was 0.49 down the
// edge at a tolerance of 0.069: refused, and the sliver's repair after it left a loop
// touching itself, which OpenCASCADE's checker refuses (as the command line runs it, with
// that checker in the gate; without it the case passed by later repairs). Pass 5 now places its vertices
// without the small faces and slivers beside it when the whole set does not meet near.
TEST(ScanParts, AChainBesideASliverOfTheSameStripIsPlacedWithoutTheSliversPlane) {
  expect_gated_case_passes(1201, 11, 19, "roofed_block", /*all_multi=*/false);  // among the first 19 parts
}

// A pinch on the side of a block with a capsule pocket in its top: the repair ties the
// boss's face to the top plane, which moves by a hair, and with it the pocket's rim
// vertices. One of them is where the cylinder meets a sphere end, tangent along a circle;
// both are fixed in the solve, so nothing held the vertex on that circle rather than
// within the precision of both surfaces (a band sqrt(2 r precision) wide): 3e-7 off it
// at a precision of 1.2e-7, and the gate refused the pinch. Tangency is now held at
// every variable vertex of a tangent edge, whether or not its faces vary.
TEST(ScanParts, ARimVertexMovedWithAPlaneStaysOnTheContactCircleOfTwoFixedFaces) {
  expect_case_of_parts_passes("bent_rod,capsule_block", 1, 99, "capsule_block");
  expect_case_of_parts_passes("bent_rod,capsule_block", 1, 147, "capsule_block");
}

// An edge gap across the circle where the bent rod's vertical cylinder meets the torus of
// its bend, tangent to it. The closed edge was given the two surfaces' intersection, a
// double root there, found only to 1e-3 off the torus: the gate refused it at a precision
// of 1.2e-6. The closed edge now takes the curve of its neighbour between the same two
// faces (the rest of the contact circle) when that lies on both (derive_edge_curve).
TEST(ScanParts, AGapAcrossATangentCircleClosesOnTheCircle) {
  expect_case_of_parts_passes("bent_rod,capsule_block", 4, 13, "bent_rod");
}

// A chamfer's cone fitted three times round its axis (pieces split along rulings, one of
// them the cone's seam, which meets the shaft cylinder's seam at one vertex of their
// circle). Pass 8's second merge shares two rulings with the first, kills one and keeps
// the other as the seam: it kept the wrong one, and the circle between cone and cylinder
// kept a vertex for each seam (V7 E11, the designer's V6 E10). The ruling whose ends carry
// more edges is now kept (pass_same_geometry.cpp).
TEST(ScanParts, MergedPiecesOfAConeKeepTheSeamThatMeetsTheShaftsSeam) {
  expect_session30_case_passes(3, 35, "stepped_shaft");
}

// The same bracket's pinch on other seed bases: its plate's plane is tangent to a rounded
// end's cylinder along a straight edge. The solve held tangent faces tangent only along
// curved edges (a straight one is its two ends, no inner points to hold), so it tilted the
// plane by 2e-4 rad: their ruling became an ellipse of major radius 4e4 with the edge's
// vertices on its two arms (613), the face turned inside out (131) or a vertex was forced
// 0.083 at a tolerance of 0.061 (601). A straight edge's inner points are now taken on its
// chord.
// Bracket 71000252 (a boss inset 0.07-0.11 from the plate's side, once thought a defect
// partly above the tolerance) passes since this change too (not traced further).
TEST(ScanParts, APlaneTangentToACylinderAlongARulingStaysTangent) {
  expect_case_passes(613, 207, 14);
  expect_case_passes(131, 207, 14);
  expect_case_passes(601, 207, 14);
  expect_case_passes(71, 39, 14);
}

// Measured 2026-12-02 with `build/bin/scan_parts_tests --gtest_filter=ScanParts.ScoreTable`
// (36 cases, seed base 1; the same as `ctest --test-dir build -R ScanParts`): 25 of 26
// judged cases passed (0.962; 10 skipped: no place for the defect). It was 23 of 26 before
// the face-sense gate, the tied planes of the region solve and the pipeline's rounds.
// Other seed bases, 96 cases each: 71/73 (base 5), 75/75 (base 7). A drop below 0.92
// (two failures) means a repair got worse on these parts.
// 2026-12-04 (session 17), 200 cases per seed base (scripts/scan_parts_score.sh 200 B):
// base 23 went 143/150 -> 150/150 and base 29 141/150 -> 149/150 over the session
// (docs/scan-parts-score.md).
// 2026-12-06 (session 30), with 19 parts: 29 of 29 judged cases of the default 36;
// (session 31), with 21 parts: 29 of 29, each output also read back from its STEP file.
constexpr double kPassRateFloor = 0.92;

// A vertex on the tee's stub-bar edge (a B-spline), split in two curves by the STEP
// round trip: the joined edge's curve is the two cylinders' intersection, marched as a
// closed polyline. Written whole between two distinct vertices, OpenCASCADE could not
// make the edge ("different points on a closed curve"), and this harness, which runs
// beautify without OpenCASCADE's half of the gate, wrote an invalid model. The edge now
// gets its own piece of the polyline, which is 0.01 tol off the surfaces between its
// points (a file holds it as the curve), so the gate refuses it at the precision; the
// backend's exact intersection (a B-spline through both vertices) takes its place and the
// case passes. Never an invalid output.
TEST(ScanParts, AJoinedEdgeOnAMarchedIntersectionIsNeverWrittenInvalid) {
  std::vector<Designer> parts = designers();
  ASSERT_GE(parts.size(), 14u);
  auto [d, types, seed] = plan(parts, 71, 141, 14);
  std::string skip;
  std::optional<CaseResult> r = run_case(*d, types, seed, &skip);
  ASSERT_TRUE(r) << skip;
  EXPECT_EQ(r->verdict, Verdict::pass) << r->detail;
  EXPECT_EQ(r->detail.find("invalid"), std::string::npos) << r->detail;
}

// Beautify's shortcuts (BeautifyOptions::shortcuts: refusals taken over where the attempt
// would meet them again, in a later run or round; edges whose ends a repair put at one
// point refused before their geometry is computed) change nothing: with and without them,
// the same problems meet the same outcomes and the output is the same to the bit. The
// parts have analytic faces only, so nothing depends on the history of projections (a
// free-form face's starts from the last answer). Defects together, with OpenCASCADE's
// checker in the gate: where repairs meet each other's results, are refused and tried
// again in later rounds and runs.
// Among the eight parts added in session 35.
void expect_session35_case_passes(std::uint64_t base, int i, const std::string& name) {
  expect_case_of_parts_passes(
      "inclined_bore_block,knob,oring_plate,chamfered_hex_prism,spindle,filleted_pocket_plate,leaning_bracket,"
      "tapered_pin",
      base, i, name, /*occt_gate=*/true);
}

// A pinch of a bar along the top edge of a plate's side, the plate's top cut by an O-ring
// groove: the bar's top, one plane with the plate's, tied it into the solve, which turned
// the plate's top by 0.005; its edge with the groove's (fixed) torus then met it in no
// circle, a marched polyline 0.0018 off the torus, and the gate refused the repair. The
// solve is tried again with the plate's top held where it is and the bar's top taking
// its plane.
TEST(ScanParts, AFaceWhoseMoveWouldLoseAnExactEdgeIsHeldAndItsPlaneTaken) {
  expect_session35_case_passes(3001, 231, "oring_plate");
}

TEST(ScanParts, ShortcutsChangeNothing) {
  std::vector<Designer> parts = designers();
  ASSERT_GE(parts.size(), kPartsBeforeSession35);
  int compared = 0, refused = 0, taken_over = 0;
  for (int i = 0; i < 48; ++i) {
    auto [d, types, seed] = plan(parts, 33, i, kPartsBeforeSession35, /*all_multi=*/true);
    // Two cases in three at four or ten times their tolerance: the part's own small
    // features read as problems, many of them refused, some tried again in later rounds
    // and runs.
    const double factor = i % 3 == 0 ? 1.0 : i % 3 == 1 ? 4.0 : 10.0;
    std::string skip;
    Beautified with, without;
    if (!run_case(*d, types, seed, &skip, true, true, &with, factor)) continue;
    ASSERT_TRUE(run_case(*d, types, seed, &skip, true, false, &without, factor)) << skip;
    ++compared;
    const std::string at = d->name + " seed " + std::to_string(seed);
    ASSERT_EQ(with.report.problems.size(), without.report.problems.size()) << at;
    for (std::size_t k = 0; k < with.report.problems.size(); ++k) {
      const RepairEntry &a = with.report.problems[k], &b = without.report.problems[k];
      EXPECT_EQ(a.problem.type, b.problem.type) << at << " entry " << k;
      EXPECT_EQ(a.problem.elements, b.problem.elements) << at << " entry " << k;
      EXPECT_EQ(a.outcome, b.outcome) << at << " entry " << k << ": " << a.reason << " | " << b.reason;
      // A repair refused as soon as it put an edge's ends at one point may have been
      // refused later for another reason without the shortcut.
      if (a.reason.find("degenerate_edge") == std::string::npos) {
        EXPECT_EQ(a.reason, b.reason) << at << " entry " << k;
      }
      refused += a.outcome == Outcome::refused;
    }
    std::string why;
    EXPECT_TRUE(with.body.equals(without.body, &why)) << at << ": " << why;
    EXPECT_EQ(without.report.refusals_taken_over, 0) << at;
    taken_over += with.report.refusals_taken_over;
  }
  std::printf("compared %d cases, %d refusals, %d taken over\n", compared, refused, taken_over);
  EXPECT_GE(compared, 24);
  EXPECT_GE(taken_over, 1) << "no refusal taken over: the shortcuts were not tried";
}

TEST(ScanParts, ScoreTable) {
  std::vector<Designer> parts = designers();
  ASSERT_GE(parts.size(), 8u) << "fewer than 8 designer parts could be built and read";
  // KINTSUGI_SCAN_PARTS=a,b,...: only those parts (to look at a few closely).
  if (const char* e = std::getenv("KINTSUGI_SCAN_PARTS")) {
    keep_only(parts, e);
    ASSERT_FALSE(parts.empty()) << "KINTSUGI_SCAN_PARTS names no part that could be built: " << e;
  }
  for (const Designer& d : parts)
    std::printf("part %-18s %s size %.0f\n", d.name.c_str(), str(d.body.counts()).c_str(), d.size);

  int n = 36;
  if (const char* e = std::getenv("KINTSUGI_SCAN_CASES")) n = std::max(1, std::atoi(e));
  std::uint64_t base = 1;
  if (const char* e = std::getenv("KINTSUGI_SCAN_SEED")) base = std::strtoull(e, nullptr, 10);

  // KINTSUGI_SCAN_FIRST=k starts at case k (with KINTSUGI_SCAN_CASES=1: one case again).
  int first = 0;
  if (const char* e = std::getenv("KINTSUGI_SCAN_FIRST")) first = std::max(0, std::atoi(e));

  const char* multi = std::getenv("KINTSUGI_SCAN_MULTI");
  const bool all_multi = multi && std::string(multi) == "1";

  // KINTSUGI_SCAN_ROTATION=k: the cases rotate through the first k parts only, as they did
  // when there were k (24 before session 35): a seed written down then names its case.
  std::size_t rotation = 0;
  if (const char* e = std::getenv("KINTSUGI_SCAN_ROTATION")) rotation = std::size_t(std::max(0, std::atoi(e)));

  std::vector<CaseResult> results;
  std::vector<std::string> skipped;
  for (int i = first; i < first + n; ++i) {
    auto [d, types, seed] = plan(parts, base, i, rotation, all_multi);
    std::string skip;
    std::optional<CaseResult> r = run_case(*d, types, seed, &skip);
    if (r)
      results.push_back(*r);
    else
      skipped.push_back(skip);
  }

  std::vector<std::string> labels;
  for (ProblemType ty : kAllProblemTypes) labels.push_back(problem_name(ty));
  labels.push_back("multi");
  std::map<std::string, std::array<int, std::size_t(Verdict::count_)>> table;
  for (const CaseResult& r : results) table[r.label][std::size_t(r.verdict)]++;
  std::printf("\n%-20s %5s %5s", "type", "cases", "pass");
  for (int v = 1; v < int(Verdict::count_); ++v) std::printf(" %9s", verdict_name(Verdict(v)));
  std::printf("\n");
  std::array<int, std::size_t(Verdict::count_)> total{};
  for (const std::string& l : labels) {
    auto row = table[l];
    int cases = 0;
    for (int v = 0; v < int(Verdict::count_); ++v) cases += row[std::size_t(v)], total[std::size_t(v)] += row[std::size_t(v)];
    std::printf("%-20s %5d %5d", l.c_str(), cases, row[0]);
    for (int v = 1; v < int(Verdict::count_); ++v) std::printf(" %9d", row[std::size_t(v)]);
    std::printf("\n");
  }
  int cases = 0;
  for (int v : total) cases += v;
  std::printf("%-20s %5d %5d", "total", cases, total[0]);
  for (int v = 1; v < int(Verdict::count_); ++v) std::printf(" %9d", total[std::size_t(v)]);
  std::printf("\nskipped (no place for the defect, or designer not clean at the tolerance): %zu\n", skipped.size());
  for (const std::string& s : skipped) std::printf("  skipped %s\n", s.c_str());
  for (const CaseResult& r : results)
    if (r.verdict != Verdict::pass || !r.detail.empty())
      std::printf("  %-9s %s\n", verdict_name(r.verdict), r.detail.c_str());
  std::fflush(stdout);

  ASSERT_GT(cases, 0);
  const double rate = double(total[0]) / cases;
  std::printf("pass rate %.3f (floor %.3f)\n", rate, kPassRateFloor);
  EXPECT_GE(rate, kPassRateFloor) << "the scan-parts pass rate dropped below the measured floor";
}

}  // namespace
}  // namespace kintsugi

// Detection against models whose defects are known (zoo/): clean models report nothing,
// injected defects are reported as their type at the place the injector names, the
// tolerance boundary is sharp, and scaling model and tolerance together changes nothing.
#include "invariants/element_geometry.h"
#include "invariants/region_validity.h"
#include "kernel/builders.h"
#include "kernel/euler.h"
#include "repair/detect.h"
#include "repair/detect_detail.h"
#include "repair/detect_threads.h"
#include "zoo/defects.h"
#include "zoo/defects_slivers.h"
#include "zoo/zoo.h"

#include <gtest/gtest.h>
#include <rapidcheck.h>
#include <rapidcheck/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <random>
#include <set>

namespace kintsugi {
namespace {

// Uniform scaling by k of curves and surfaces (frames' origins and every length).
geo::Frame scaled(geo::Frame f, double k) {
  f.origin *= k;
  return f;
}
geo::Curve scaled(const geo::Curve& c, double k) {
  if (auto* l = std::get_if<geo::Line>(&c)) return geo::Line{l->origin * k, l->direction};
  if (auto* ci = std::get_if<geo::Circle>(&c)) return geo::Circle{scaled(ci->frame, k), ci->radius * k};
  if (auto* e = std::get_if<geo::Ellipse>(&c))
    return geo::Ellipse{scaled(e->frame, k), e->major_radius * k, e->minor_radius * k};
  if (auto* p = std::get_if<geo::Polyline>(&c)) {
    geo::Polyline q = *p;
    for (auto& x : q.points) x *= k;
    q.chordal_error *= k;
    return q;
  }
  return c;
}
geo::Surface scaled(const geo::Surface& s, double k) {
  if (auto* p = std::get_if<geo::Plane>(&s)) return geo::Plane{scaled(p->frame, k)};
  if (auto* c = std::get_if<geo::Cylinder>(&s)) return geo::Cylinder{scaled(c->frame, k), c->radius * k};
  if (auto* c = std::get_if<geo::Cone>(&s)) return geo::Cone{scaled(c->frame, k), c->radius * k, c->half_angle};
  if (auto* c = std::get_if<geo::Sphere>(&s)) return geo::Sphere{scaled(c->frame, k), c->radius * k};
  if (auto* c = std::get_if<geo::Torus>(&s)) return geo::Torus{scaled(c->frame, k), c->major_radius * k, c->minor_radius * k};
  return s;
}

geo::Tolerances tol_for(const Body& b, double t) { return geo::Tolerances::for_model(t, model_size(b)); }

std::string describe_one(const Problem& p) {
  std::string s = std::string(problem_name(p.type)) + " [";
  for (auto& e : element_names(p)) s += e + " ";
  return s + "] " + std::to_string(p.measure) + " " + subcase_name(p);
}

std::string describe(const Detection& d) {
  std::string s;
  for (const Problem& p : d.problems) s += describe_one(p) + "\n";
  return s;
}

std::vector<std::pair<std::string, Body>> clean_solids() {
  return {{"box", build::box(1, 2, 3)},
          {"prism", build::prism(build::regular_polygon(6, 1), 2)},
          {"pyramid", build::pyramid(build::regular_polygon(4, 1), 1)},
          {"cylinder", build::cylinder(1, 2)},
          {"cone", build::cone(1, 2)},
          {"sphere", build::sphere(1)},
          {"torus", build::torus(3, 1)}};
}

TEST(Detect, CleanBuilderSolidsReportNothing) {
  for (auto& [name, b] : clean_solids()) {
    Detection d = detect(b, tol_for(b, 0.01));
    EXPECT_TRUE(d.problems.empty()) << name << ":\n" << describe(d);
  }
}

TEST(Detect, GridBoxReportsItsCoplanarNeighboursOnly) {
  Body b = build::grid_box(24);  // k = 2: each side in 4 coplanar quads
  Detection d = detect(b, tol_for(b, 0.01));
  EXPECT_EQ(d.count(ProblemType::same_geometry_faces), 24);  // 6 sides x 4 adjacent pairs
  EXPECT_EQ(int(d.problems.size()), d.count(ProblemType::same_geometry_faces)) << describe(d);
}

// Pairs every recorded defect with a distinct reported problem of the same type at the
// same place (a bipartite matching, so two defects cannot both claim one report).
// Returns what could not be paired.
std::string unmatched(const std::vector<zoo::KnownDefect>& known, const Detection& d) {
  // The report's first element (the gap's border cycle, the face, the edge) must be one
  // the defect names; a pinch must also name one of the defect's edges, since two
  // pinches can share their face.
  auto fits = [&](const zoo::KnownDefect& k, const Problem& p) {
    auto named = [&](const std::string& e) { return std::find(k.elements.begin(), k.elements.end(), e) != k.elements.end(); };
    const std::vector<std::string> pe = element_names(p);
    if (p.type != k.type || pe.empty() || !named(pe[0])) return false;
    if (p.type == ProblemType::pinched_face) return pe.size() == 3 && (named(pe[1]) || named(pe[2]));
    return true;
  };
  std::vector<int> owner(d.problems.size(), -1);  // problem -> known defect
  std::function<bool(std::size_t, std::vector<bool>&)> augment = [&](std::size_t i, std::vector<bool>& seen) {
    for (std::size_t j = 0; j < d.problems.size(); ++j) {
      if (seen[j] || !fits(known[i], d.problems[j])) continue;
      seen[j] = true;
      if (owner[j] < 0 || augment(std::size_t(owner[j]), seen)) {
        owner[j] = int(i);
        return true;
      }
    }
    return false;
  };
  std::string out;
  for (std::size_t i = 0; i < known.size(); ++i) {
    std::vector<bool> seen(d.problems.size(), false);
    if (!augment(i, seen)) {
      out += "not reported where it was made: " + std::string(problem_name(known[i].type)) + " [ ";
      for (const auto& e : known[i].elements) out += e + " ";
      out += "]\n";
    }
  }
  for (std::size_t j = 0; j < d.problems.size(); ++j)
    if (owner[j] < 0) out += "reported but not made: " + std::string(problem_name(d.problems[j].type)) + "\n";
  return out;
}

// Each paper object reports exactly the defects it was built with, at the places they
// were made, and its clean version reports nothing.
TEST(Detect, PaperObjectsReportExactlyTheirDefects) {
  for (int n = 1; n <= 10; ++n) {
    zoo::ZooModel m = zoo::paper_object(n, false);
    Detection d = detect(m.body, tol_for(m.body, m.tolerance));
    std::array<int, 11> expected{};
    for (const auto& k : m.defects) expected[std::size_t(problem_order(k.type) - 1)]++;
    EXPECT_EQ(d.counts, expected) << "object " << n << ":\n" << describe(d);
    EXPECT_EQ(unmatched(m.defects, d), "") << "object " << n << ":\n" << describe(d);
    zoo::ZooModel clean = zoo::paper_object(n, true);
    Detection dc = detect(clean.body, tol_for(clean.body, clean.tolerance));
    EXPECT_TRUE(dc.problems.empty()) << "object " << n << " clean:\n" << describe(dc);
  }
}

// Detection measures planar faces from their boundary polylines alone; that must agree
// with the triangulated measure, rings, circles, gaps and struts included.
TEST(Detect, PlanarFaceAreasAgreeWithTheTriangulatedMeasure) {
  std::vector<zoo::ZooModel> models;
  for (int n = 1; n <= 10; ++n)
    for (bool clean : {false, true}) models.push_back(zoo::paper_object(n, clean));
  models.push_back(zoo::family(400, 0.3, 7));
  int planar = 0;
  for (const zoo::ZooModel& m : models)
    for (FaceH f : m.body.faces()) {
      if (!std::holds_alternative<geo::Plane>(m.body.surface(f))) continue;
      const double chordal = 1e-3 * m.tolerance;
      geo::RegionMeasure full = face_measure(m.body, f, chordal);
      std::optional<AreaAndBounds> fast = face_area_and_bounds(m.body, f, chordal);
      ASSERT_TRUE(full.ok()) << m.source << " " << f << ": " << full.problem;
      ASSERT_TRUE(fast.has_value()) << m.source << " " << f;
      EXPECT_NEAR(fast->area, full.area, 1e-9 * (1 + full.area)) << m.source << " " << f;
      EXPECT_NEAR(fast->bounds.diagonal(), full.bounds.diagonal(), 1e-9 * (1 + full.bounds.diagonal())) << m.source << " " << f;
      ++planar;
    }
  EXPECT_GT(planar, 500);
}

// The scalable family: without defects it reports nothing; with them, exactly the
// defects it records, at their places, whatever the seed and size.
RC_GTEST_PROP(Detect, FamilyReportsExactlyItsDefects, ()) {
  const std::size_t faces = *rc::gen::inRange<std::size_t>(60, 900);
  const double rate = *rc::gen::element(0.0, 0.05, 0.2);
  const std::uint64_t seed = *rc::gen::arbitrary<std::uint32_t>();
  zoo::ZooModel m = zoo::family(faces, rate, seed);
  Detection d = detect(m.body, tol_for(m.body, m.tolerance));
  std::array<int, 11> expected{};
  for (const auto& k : m.defects) expected[std::size_t(problem_order(k.type) - 1)]++;
  RC_ASSERT(d.counts == expected);
  const std::string missing = unmatched(m.defects, d);
  RC_ASSERT(missing == "");
  if (rate == 0.0) RC_ASSERT(d.problems.empty());
}

// An injected defect of type k is reported as type k, at an element the injector names.
RC_GTEST_PROP(Detect, InjectedDefectIsFoundWhereItWasPut, ()) {
  const ProblemType type = *rc::gen::elementOf(std::vector<ProblemType>(kAllProblemTypes.begin(), kAllProblemTypes.end()));
  const int which = *rc::gen::inRange(0, 4);
  const std::uint64_t seed = *rc::gen::arbitrary<std::uint32_t>();
  Body b = which == 0 ? build::box(1, 1, 1)
         : which == 1 ? build::prism(build::regular_polygon(6, 1), 1)
         : which == 2 ? build::pyramid(build::regular_polygon(4, 1), 1)
                      : build::prism(build::regular_polygon(5, 1), 2);
  const double t = 0.02;
  std::string error;
  auto inj = zoo::inject(b, type, seed, std::nullopt, t, &error);
  RC_PRE(inj.has_value());  // not every solid has a place for every type
  Detection d = detect(b, tol_for(b, t));
  std::set<std::string> named(inj->defect.elements.begin(), inj->defect.elements.end());
  bool found = false;
  for (const Problem& p : d.problems)
    if (p.type == type)
      for (const auto& e : element_names(p)) found = found || named.count(e);
  if (!found) RC_FAIL(std::string("injected ") + problem_name(type) + " (" + inj->description + ") not reported:\n" + describe(d));
}

// Detection measures each face coarsely first and finely only where the coarse measure,
// widened by its error bound, cannot decide (DetectContext::measure). Its decisions must
// be the fine measure's, above all near the thresholds: the tolerance is taken at one of
// the face's own thresholds (√area: small; area / diagonal: sliver) times 1 ± 10^-x, or
// halfway between the fine and the coarse measure's threshold (where they disagree),
// on curved bases with a defect injected (small faces, slivers, gaps' new faces, ...).
// (Paper object 10 as a base made it 1.7 times as long for no face kind these lack.)
RC_GTEST_PROP(Detect, CoarseFirstMeasureDecidesAsTheFineOne, ()) {
  const int which = *rc::gen::inRange(0, 4);
  Body b = which == 0 ? build::cylinder(1, 2)
         : which == 1 ? build::cone(1, 2)
         : which == 2 ? build::sphere(1)
                      : build::torus(3, 1);
  const ProblemType type = *rc::gen::elementOf(std::vector<ProblemType>(kAllProblemTypes.begin(), kAllProblemTypes.end()));
  std::string error;
  RC_PRE(zoo::inject(b, type, *rc::gen::arbitrary<std::uint32_t>(), std::nullopt, 0.02, &error).has_value());
  const std::vector<FaceH> faces = b.faces();
  const FaceH f = faces[*rc::gen::inRange<std::size_t>(0, faces.size())];
  const detail::FaceInfo at = detail::measure_face(b, f, tol_for(b, 0.02), tol_for(b, 0.02).measure_chordal());
  RC_PRE(at.measured && at.area > 0 && at.bbox_diagonal > 0);
  const bool small = *rc::gen::arbitrary<bool>();
  const double threshold = small ? std::sqrt(at.area) : at.area / at.bbox_diagonal;
  double t = 0;
  if (*rc::gen::arbitrary<bool>()) {
    // 1 ± 10^-x, x in [1, 4].
    const double offset = std::pow(10.0, -(1.0 + 3.0 * *rc::gen::inRange(0, 1001) / 1000.0));
    t = threshold * (*rc::gen::arbitrary<bool>() ? 1 + offset : 1 - offset);
  } else {
    // Where the coarse and the fine measure disagree: the threshold between the two
    // (the coarse one taken at the chordal error detection would use there).
    const std::optional<AreaAndBounds> coarse =
        face_area_and_bounds(b, f, tol_for(b, threshold).coarse_measure_chordal());
    RC_PRE(coarse.has_value() && coarse->bounds.diagonal() > 0);
    const double c_threshold = small ? std::sqrt(coarse->area) : coarse->area / coarse->bounds.diagonal();
    t = 0.5 * (threshold + c_threshold);
  }
  const geo::Tolerances tol = tol_for(b, t);
  const detail::FaceInfo fine = detail::measure_face(b, f, tol, tol.measure_chordal());
  const detail::DetectContext c(b, tol, detail::Scope{{f}, {}, {}, {}}, false);
  const detail::FaceInfo& got = c.face(f);
  RC_LOG() << "face " << f.str() << " of " << faces.size() << ", " << problem_name(type) << " injected, t " << t
           << "; fine area " << fine.area << " diagonal " << fine.bbox_diagonal << " small " << fine.small << " sliver "
           << fine.sliver << "; got small " << got.small << " sliver " << got.sliver << "\n";
  RC_ASSERT(got.measured == fine.measured);
  RC_ASSERT(got.small == fine.small);
  RC_ASSERT(got.sliver == fine.sliver);
}

// The same model and tolerance scaled by k: the same report, measures scaled by k (or k²).
RC_GTEST_PROP(Detect, ScalingModelAndToleranceChangesNothing, ()) {
  const ProblemType type = *rc::gen::elementOf(std::vector<ProblemType>(kAllProblemTypes.begin(), kAllProblemTypes.end()));
  const double k = *rc::gen::element(1e-3, 0.1, 10.0, 1e3);
  const std::uint64_t seed = *rc::gen::arbitrary<std::uint32_t>();
  const double t = 0.02;
  Body a = build::prism(build::regular_polygon(6, 1), 1);
  std::string error;
  RC_PRE(zoo::inject(a, type, seed, std::nullopt, t, &error).has_value());
  Body b = a.clone();
  for (VertexH v : b.vertices()) b.set_point(v, b.point(v) * k);
  for (EdgeH e : b.edges()) b.set_curve(e, scaled(b.curve(e), k));
  for (FaceH f : b.faces()) b.set_surface(f, scaled(b.surface(f), k), b.same_sense(f));
  Detection da = detect(a, tol_for(a, t)), db = detect(b, tol_for(b, t * k));
  RC_LOG() << "injected " << problem_name(type) << ", scale " << k << "\nfound at scale 1:\n"
           << describe(da) << "found scaled:\n" << describe(db);
  RC_ASSERT(da.counts == db.counts);
  RC_ASSERT(da.problems.size() == db.problems.size());
  for (std::size_t i = 0; i < da.problems.size(); ++i) {
    RC_ASSERT(da.problems[i].elements == db.problems[i].elements);
    double p = da.problems[i].measure_kind == Measure::area ? k * k : k;
    RC_ASSERT(std::abs(db.problems[i].measure - p * da.problems[i].measure) <= 1e-6 * p * (1 + da.problems[i].measure));
  }
}

// A short edge at a pyramid's apex, just below and just above the tolerance.
Body pyramid_with_apex_edge(double length) {
  Body b = build::pyramid(build::regular_polygon(4, 1), 1);
  VertexH apex;
  for (VertexH v : b.vertices())
    if (b.degree(v) == 4) apex = v;
  auto outs = b.outgoing(apex);
  geo::Vec3 p = b.point(apex) + geo::Vec3(length, 0, 0);
  auto r = euler::mev_split(b, outs[0], outs[2], p);
  EXPECT_TRUE(r);
  return b;
}

TEST(Detect, ToleranceBoundaryIsSharp) {
  const double t = 0.01;
  Body below = pyramid_with_apex_edge(0.99 * t), above = pyramid_with_apex_edge(1.01 * t);
  Detection d1 = detect(below, tol_for(below, t)), d2 = detect(above, tol_for(above, t));
  EXPECT_EQ(d1.count(ProblemType::short_edge), 1) << describe(d1);
  EXPECT_EQ(d1.problems.size(), 1u) << describe(d1);  // its neighbours are not a pinch
  EXPECT_EQ(d2.count(ProblemType::short_edge), 0) << describe(d2);
  EXPECT_TRUE(d2.problems.empty()) << describe(d2);
}

// A box corner cut off by a triangle of area just below and just above tol² (paper 4.6:
// small means area < tol²). Below, the triangle is a small face and nothing else is
// reported. Above, it is no longer small; a triangle of about tol² is still thin for its
// size (area / bbox diagonal ≈ 0.54 tol < tol), so it is reported as a sliver instead —
// the same face, the other side of the threshold. Its edges are ≈ 1.5 tol: none short.
TEST(Detect, SmallFaceThresholdIsSharp) {
  const double t = 0.01;
  for (double k : {0.99, 1.01}) {
    Body b = build::box();
    zoo::KnownDefect made = zoo::make::small_face(b, b.vertices().back(), k * t * t, nullptr);
    ASSERT_NEAR(made.size, k * t * t, 1e-9 * t * t);
    Detection d = detect(b, tol_for(b, t));
    ASSERT_EQ(d.problems.size(), 1u) << "area " << k << " tol²\n" << describe(d);
    const Problem& p = d.problems[0];
    EXPECT_EQ(p.type, k < 1 ? ProblemType::small_face : ProblemType::sliver_face) << describe(d);
    EXPECT_EQ(element_names(p), made.elements) << describe(d);
    if (k < 1) {
      EXPECT_EQ(p.measure_kind, Measure::area);
      EXPECT_NEAR(p.measure, k * t * t, 1e-6 * t * t) << describe(d);
    }
  }
}

// Long thin faces: a box 0.99 tol thick has four sides of area/diagonal below tol.
TEST(Detect, ThinBoxSidesAreSlivers) {
  const double t = 0.01;
  Body thin = build::box(0.99 * t, 1, 1);
  Detection d = detect(thin, tol_for(thin, t));
  EXPECT_EQ(d.count(ProblemType::sliver_face), 4) << describe(d);
  EXPECT_EQ(d.count(ProblemType::small_face), 0) << describe(d);
}

// A spike is two sides running nearly side by side, joined through a short stretch (paper
// 4.2); a designed acute corner whose tip a short edge cuts is not one. A prism on a
// triangle with its tip cut by an edge of 0.3 t: at 30°, 45° and 60° the sides, t from the
// short edge, are 0.82 t, 1.07 t and 1.3 t apart, and before sides had to be near parallel
// the 30° corner read as a spike on the top and the bottom (the Table 1 audit found a
// pyramid's 60° corner so, after a sliver's removal left a short edge there). At 8° the
// sides stay within t for 7 t: a spike on both.
TEST(Detect, AnAcuteCornerCutByAShortEdgeIsASpikeOnlyWhenItsSidesRunSideBySide) {
  const double t = 0.01, pi = std::acos(-1.0);
  for (double degrees : {8.0, 30.0, 45.0, 60.0}) {
    const double half = degrees * pi / 360, d = 0.15 * t / std::sin(half);
    const geo::Vec2 dir_up(std::cos(half), std::sin(half)), dir_down(std::cos(half), -std::sin(half));
    Body b = build::prism({d * dir_down, dir_down, dir_up, d * dir_up}, 0.5);
    Detection found = detect(b, tol_for(b, t));
    EXPECT_EQ(found.count(ProblemType::pinched_face), degrees < 20 ? 2 : 0) << degrees << "°\n" << describe(found);
    for (const Problem& p : found.problems)
      if (p.type == ProblemType::pinched_face) {
        EXPECT_EQ(p.subcase.location, PinchLocation::spiking) << describe(found);
      }
  }
}

// A scanned fillet or chamfer of a cylinder's circle far narrower than the tolerance is
// one sliver: the band (zoo::make::ring_fillet, ring_chamfer), measured by its mean
// circumference. Each circle of the cylinder in turn, in a fresh body (the band's making
// once read the cylinder through a pointer its own new face left dangling: AddressSanitizer).
TEST(Detect, ARingBandOnACylinderIsOneSliver) {
  const double t = 0.05;
  for (bool round : {true, false})
    for (int k = 0; k < 2; ++k) {
      // A copy: its storage is as large as its contents, so the band's new face moves it.
      const Body made_by_builder = build::cylinder(1.0, 2.0);
      Body b = made_by_builder;
      std::vector<EdgeH> circles;
      for (EdgeH e : b.edges())
        if (std::holds_alternative<geo::Circle>(b.curve(e))) circles.push_back(e);
      ASSERT_EQ(circles.size(), 2u);
      zoo::KnownDefect made = round ? zoo::make::ring_fillet(b, circles[std::size_t(k)], 0.2 * t)
                                    : zoo::make::ring_chamfer(b, circles[std::size_t(k)], 0.2 * t, 0.3 * t);
      Detection d = detect(b, tol_for(b, t));
      EXPECT_EQ(d.count(ProblemType::sliver_face), 1) << describe(d);
      EXPECT_EQ(d.problems.size(), 1u) << describe(d);
      if (!d.problems.empty()) {
        EXPECT_EQ(element_names(d.problems[0]), made.elements) << describe(d);
      }
    }
}

TEST(Detect, ShortEdgeChainAndMergeableVertex) {
  const double t = 0.01;
  Body b = pyramid_with_apex_edge(0.8 * t);
  // Split the apex edge: two short edges joined by a vertex on exactly two edges.
  EdgeH shortest;
  double best = 1e9;
  for (EdgeH e : b.edges())
    if (edge_length(b, e) < best) best = edge_length(b, e), shortest = e;
  HalfedgeH h = halfedge_of(shortest, 0);
  ASSERT_TRUE(euler::semv(b, h, (b.point(b.origin(h)) + b.point(b.target(h))) / 2));
  Detection d = detect(b, tol_for(b, t));
  EXPECT_EQ(d.count(ProblemType::short_edge_chain), 1) << describe(d);
  EXPECT_EQ(d.count(ProblemType::mergeable_edges), 0) << describe(d);
  EXPECT_EQ(d.count(ProblemType::short_edge), 0) << describe(d);
  // A long edge cut in the middle: a mergeable vertex, nothing short.
  Body box = build::box();
  HalfedgeH g = box.halfedges()[0];
  ASSERT_TRUE(euler::semv(box, g, (box.point(box.origin(g)) + box.point(box.target(g))) / 2));
  Detection dm = detect(box, tol_for(box, t));
  EXPECT_EQ(dm.count(ProblemType::mergeable_edges), 1) << describe(dm);
  EXPECT_EQ(dm.problems.size(), 1u) << describe(dm);
}

TEST(Detect, GapsByHowManyFacesTheySpan) {
  Body b = build::box();
  ASSERT_TRUE(euler::kfmb(b, b.faces()[0]));  // a whole side missing: a gap across 4 faces
  Detection d = detect(b, tol_for(b, 0.01));
  EXPECT_EQ(d.count(ProblemType::multi_face_gap), 1) << describe(d);
  EXPECT_EQ(d.problems.size(), 1u) << describe(d);
}

// detect_near_of_type runs one detector; what it finds must be exactly detect_near's
// problems of that type, in the same order, on random zoo models around random touched
// elements (the pass loop re-detects each repair's own type with it).
RC_GTEST_PROP(Detect, NearOfOneTypeIsNearFilteredToIt, ()) {
  const int which = *rc::gen::inRange(0, 4);
  Body b = which == 0 ? build::box(1, 1, 1)
         : which == 1 ? build::cylinder(1, 2)
         : which == 2 ? build::pyramid(build::regular_polygon(4, 1), 1)
                      : build::grid_box(24);
  const double t = 0.02;
  const int n = *rc::gen::inRange(1, 4);
  for (int i = 0; i < n; ++i) {
    std::string error;
    zoo::inject(b, *rc::gen::elementOf(std::vector<ProblemType>(kAllProblemTypes.begin(), kAllProblemTypes.end())),
                *rc::gen::arbitrary<std::uint32_t>(), std::nullopt, t, &error);
  }
  Touched touched;
  const std::vector<VertexH> vs = b.vertices();
  const std::vector<EdgeH> es = b.edges();
  const std::vector<FaceH> fs = b.faces();
  for (int i = *rc::gen::inRange(1, 4); i-- > 0;) touched.vertices.insert(vs[*rc::gen::inRange<std::size_t>(0, vs.size())]);
  for (int i = *rc::gen::inRange(0, 3); i-- > 0;) touched.edges.insert(es[*rc::gen::inRange<std::size_t>(0, es.size())]);
  for (int i = *rc::gen::inRange(0, 2); i-- > 0;) touched.faces.insert(fs[*rc::gen::inRange<std::size_t>(0, fs.size())]);
  const geo::Tolerances tol = tol_for(b, t);
  const Neighbourhood near = neighbourhood(b, touched, tol);
  const Detection all = detect_near(b, tol, near);
  for (ProblemType type : kAllProblemTypes) {
    std::vector<std::string> expected, got;
    for (const Problem& p : all.problems)
      if (p.type == type) expected.push_back(describe_one(p));
    for (const Problem& p : detect_near_of_type(b, tol, near, type)) got.push_back(describe_one(p));
    RC_ASSERT(got == expected);
  }
}

// A repair that makes a middle face of a chain of small faces large — here merging it
// into the big side face beside it (kef), which touches only that side face — cuts the
// chain in two. The pieces meet the merged face across edges nothing touched, so the
// repair's neighbourhood (the merged face, its edges and vertices) holds none of them:
// they are found again from the dropped chain's own faces (drop_anchored grows the
// neighbourhood by them). Replacing what is anchored by what detect_near finds must give
// exactly what a whole-body detection finds.
TEST(Detect, AChainCutByARepairIsFoundAgainInItsPieces) {
  Body b = build::pyramid(build::regular_polygon(6, 1), 1);
  VertexH apex;
  for (VertexH v : b.vertices())
    if (b.outgoing(v).size() == 6) apex = v;
  ASSERT_TRUE(apex.valid());
  zoo::Rng rng(3);
  zoo::make::small_face_chain(b, apex, 0.02, rng);
  const geo::Tolerances tol = tol_for(b, 0.05);
  std::vector<Problem> known = detect(b, tol).problems;
  const Problem* chain = nullptr;
  for (const Problem& p : known)
    if (p.type == ProblemType::small_face_chain) chain = &p;
  ASSERT_NE(chain, nullptr) << describe(detect(b, tol));
  const std::vector<FaceH> faces = chain->all<FaceH>();
  ASSERT_EQ(faces.size(), 4u);
  // A face of the chain with two chain neighbours, and its edge to a face off the chain.
  HalfedgeH cut;
  for (FaceH f : faces) {
    int in_chain = 0;
    HalfedgeH off;
    for (HalfedgeH h : b.loop_halfedges(b.outer_loop(f))) {
      FaceH g = b.face(twin(h));
      if (std::find(faces.begin(), faces.end(), g) != faces.end())
        ++in_chain;
      else
        off = twin(h);
    }
    if (in_chain == 2 && off.valid()) cut = off;
  }
  ASSERT_TRUE(cut.valid());
  const FaceH side = b.face(cut);
  ASSERT_FALSE(euler::can_kef(b, cut).has_value());
  ASSERT_TRUE(euler::kef(b, cut).ok());
  Touched touched;
  touched.faces.insert(side);
  Neighbourhood n = neighbourhood(b, touched, tol);
  drop_anchored(b, n, {&known});
  for (Problem& p : detect_near(b, tol, n).problems) known.push_back(std::move(p));
  std::vector<std::string> want, got;
  for (const Problem& p : detect(b, tol).problems) want.push_back(describe_one(p));
  for (const Problem& p : known) got.push_back(describe_one(p));
  std::sort(want.begin(), want.end());
  std::sort(got.begin(), got.end());
  EXPECT_EQ(got, want);
  // The cut left a single small face and a chain of two, neither touching the core.
  EXPECT_EQ(std::count_if(want.begin(), want.end(), [](const std::string& s) { return s.rfind("small_face ", 0) == 0; }), 1);
}

// A whole-body detection measures faces and edges ahead on several threads
// (repair/detect_threads.h) and then finds pinches and same-geometry pairs on them, in
// blocks of faces and edges: the problems, their order, their elements and their
// measures to the last bit are those of one thread. Models above the size where threads
// start (512 faces), with same-geometry defects; at 20 times their tolerance too, where
// the bosses' rings pinch the plate everywhere.
std::string exact_listing(const Detection& d) {
  std::string s;
  char buf[64];
  for (const Problem& p : d.problems) {
    s += describe_one(p);
    std::snprintf(buf, sizeof buf, " %a\n", p.measure);
    s += buf;
  }
  return s;
}

TEST(Detect, OneAndTwoThreadsFindTheSame) {
  std::vector<std::pair<std::string, zoo::ZooModel>> models;
  models.emplace_back("family 3000", zoo::family(3000, 0.1, 5));
  models.emplace_back("family 2000", zoo::family(2000, 0.3, 9));
  for (auto& [name, m] : models)
    for (double t : {m.tolerance, 20 * m.tolerance}) {
      const geo::Tolerances tol = tol_for(m.body, t);
      set_detect_threads(1);
      const std::string one = exact_listing(detect(m.body, tol));
      set_detect_threads(2);
      const std::string two = exact_listing(detect(m.body, tol));
      set_detect_threads(3);
      const std::string three = exact_listing(detect(m.body, tol));
      set_detect_threads(0);
      EXPECT_FALSE(one.empty()) << name;
      EXPECT_EQ(one, two) << name << " at " << t;
      EXPECT_EQ(one, three) << name << " at " << t;
      // Both detectors that run in blocks have something to find.
      EXPECT_NE(one.find(t > m.tolerance ? "pinched_face" : "same_geometry_faces"), std::string::npos) << name;
    }
}

TEST(Detect, DetectTypesIsDetectOfThoseTypes) {
  std::vector<std::pair<std::string, zoo::ZooModel>> models;
  models.emplace_back("family 1500", zoo::family(1500, 0.5, 3));
  for (int n : {1, 4, 7, 10}) models.emplace_back("paper object " + std::to_string(n), zoo::paper_object(n, false));
  const std::vector<std::vector<ProblemType>> choices = {
      {ProblemType::pinched_face, ProblemType::same_geometry_faces},  // the tolerance suggestion's
      {ProblemType::sliver_face},
      {ProblemType::short_edge, ProblemType::short_edge_chain, ProblemType::mergeable_edges},
      {ProblemType::face_gap, ProblemType::small_face}};
  for (auto& [name, m] : models) {
    // At the model's tolerance and at a coarse one, where every detector finds more.
    for (double t : {m.tolerance, 20 * m.tolerance}) {
      const geo::Tolerances tol = tol_for(m.body, t);
      const Detection all = detect(m.body, tol);
      for (const auto& types : choices) {
        Detection only;
        for (const Problem& p : all.problems)
          if (std::find(types.begin(), types.end(), p.type) != types.end()) only.problems.push_back(p);
        EXPECT_EQ(exact_listing(detect_types(m.body, tol, types)), exact_listing(only)) << name << " at " << t;
      }
    }
  }
}

// Faces measured beforehand (the tolerance suggestion's, finer than detection's own) stand
// in for detection's measures: the same problems are found, at the model's tolerance and
// at the coarse ones where small faces and slivers keep faces out of the pinch and
// same-geometry searches. Measures taken at the wrong tolerance's decision, or given to
// the wrong faces, would change them.
TEST(Detect, DetectTypesTakesFacesMeasuredBefore) {
  std::vector<std::pair<std::string, zoo::ZooModel>> models;
  models.emplace_back("family 1500", zoo::family(1500, 0.5, 3));
  for (int n : {1, 4, 7, 10}) models.emplace_back("paper object " + std::to_string(n), zoo::paper_object(n, false));
  const std::vector<ProblemType> types = {ProblemType::pinched_face, ProblemType::same_geometry_faces};
  int telling = 0;  // cases where measures matter: faces given as unmeasurable change the result
  for (auto& [name, m] : models) {
    const double size = model_size(m.body);
    std::vector<std::optional<AreaAndBounds>> measured(m.body.face_slots()), none(m.body.face_slots());
    for (FaceH f : m.body.faces()) measured[f.idx()] = face_area_and_bounds(m.body, f, 1e-5 * size);
    // 19, not 20, times the family's tolerance: at 20 (4 mm) a boss's side, 4 mm high, is
    // a band exactly the tolerance wide (sliver_length), and whether it is a sliver then
    // depends on the last bits of an area measured at two chordal errors.
    for (double t : {m.tolerance, 19 * m.tolerance, 0.05 * size}) {
      const geo::Tolerances tol = tol_for(m.body, t);
      const std::string alone = exact_listing(detect_types(m.body, tol, types));
      EXPECT_EQ(exact_listing(detect_types(m.body, tol, types, measured)), alone) << name << " at " << t;
      telling += exact_listing(detect_types(m.body, tol, types, none)) != alone;
    }
  }
  EXPECT_GE(telling, 5);
}

}  // namespace
}  // namespace kintsugi

namespace kintsugi {
namespace {

// A repair on the boundary of a face with many loops (the family's plate) brings into the
// neighbourhood the face itself and the edges of its loops near the change only, unless
// it set the face's surface (spec/problems.md, "A face with many loops").
TEST(Neighbourhood, APlateBringsItsLoopsNearTheChangeOnly) {
  zoo::ZooModel m = zoo::family(400, 0.0, 5);
  const Body& b = m.body;
  FaceH plate;
  std::size_t most = 0;
  for (FaceH f : b.faces())
    if (std::size_t k = b.loops_of(f).size(); k > most) most = k, plate = f;
  ASSERT_GT(most, 4 * kManyLoops);
  std::vector<LoopH> rings;
  for (LoopH l : b.loops_of(plate))
    if (!b.is_outer(l) && !b.is_lone(l)) rings.push_back(l);
  const LoopH changed = rings.front();
  auto centre = [&](LoopH l) {
    geo::Vec3 c = geo::Vec3::Zero();
    for (VertexH v : b.loop_vertices(l)) c += b.point(v);
    return geo::Vec3(c / double(b.loop_vertices(l).size()));
  };
  LoopH far = rings.back(), next = rings.back();
  for (LoopH l : rings) {
    if ((centre(l) - centre(changed)).norm() > (centre(far) - centre(changed)).norm()) far = l;
    if (l != changed && (centre(l) - centre(changed)).norm() < (centre(next) - centre(changed)).norm()) next = l;
  }
  // A tolerance at which the next ring is near the change (the distance of the centres:
  // the changed ring's box holds its centre, the next ring's box its own).
  const geo::Tolerances tol = geo::Tolerances::for_model((centre(next) - centre(changed)).norm(), model_size(b));

  Touched t;
  t.vertices.insert(b.loop_vertices(changed).front());
  const Neighbourhood n = neighbourhood(b, t, tol);
  EXPECT_TRUE(n.faces.count(plate));
  EXPECT_TRUE(n.partial.count(plate));
  std::size_t plate_edges = 0, plate_edges_in = 0;
  for (LoopH l : b.loops_of(plate))
    for (HalfedgeH h : b.loop_halfedges(l)) ++plate_edges, plate_edges_in += n.edges.count(edge_of(h));
  EXPECT_LT(plate_edges_in * 4, plate_edges);
  for (LoopH l : loops_near(b, plate, *near_change(b, t.vertices, t.edges, plate, tol)))
    for (HalfedgeH h : b.loop_halfedges(l)) EXPECT_TRUE(n.edges.count(edge_of(h))) << edge_of(h).str();
  for (HalfedgeH h : b.loop_halfedges(b.outer_loop(plate))) EXPECT_TRUE(n.edges.count(edge_of(h)));
  for (HalfedgeH h : b.loop_halfedges(next)) EXPECT_TRUE(n.edges.count(edge_of(h))) << edge_of(h).str();
  for (HalfedgeH h : b.loop_halfedges(far)) EXPECT_FALSE(n.edges.count(edge_of(h))) << edge_of(h).str();

  // With a memo the plate is measured once; each later change shrinks the bounds by what
  // fits in its box, and when they no longer decide it is measured again.
  FaceBoundsMemo memo;
  neighbourhood(b, t, tol, &memo);
  ASSERT_TRUE(memo.faces.count(plate));
  const FaceBoundsMemo::Bounds first = memo.faces.at(plate);
  const double d = near_change(b, t.vertices, t.edges, plate, tol)->diagonal();
  EXPECT_TRUE(neighbourhood(b, t, tol, &memo).partial.count(plate));
  EXPECT_NEAR(memo.faces.at(plate).area_lo, first.area_lo - d * d, 1e-9 * first.area_lo);
  EXPECT_NEAR(memo.faces.at(plate).diagonal_hi, first.diagonal_hi + d, 1e-9 * first.diagonal_hi);
  memo.faces.at(plate).area_lo = tol.length * tol.length;  // worn down to the limit by many changes
  EXPECT_TRUE(neighbourhood(b, t, tol, &memo).partial.count(plate));
  EXPECT_NEAR(memo.faces.at(plate).area_lo, first.area_lo, 1e-9 * first.area_lo);
  memo.faces.at(plate) = {tol.length * tol.length * 1e-3, first.diagonal_hi};  // said small: measured again
  EXPECT_TRUE(neighbourhood(b, t, tol, &memo).partial.count(plate));

  // The plate's surface set by the repair: all of it.
  t.reshaped.insert(plate);
  EXPECT_FALSE(neighbourhood(b, t, tol, &memo).partial.count(plate));
  EXPECT_FALSE(memo.faces.count(plate));
  const Neighbourhood whole = neighbourhood(b, t, tol);
  EXPECT_FALSE(whole.partial.count(plate));
  for (HalfedgeH h : b.loop_halfedges(far)) EXPECT_TRUE(whole.edges.count(edge_of(h)));
  // Added whole later (a known problem of the plate grows the neighbourhood): all of it.
  Neighbourhood grown = n;
  grown.add_face(b, plate);
  EXPECT_FALSE(grown.partial.count(plate));
  for (HalfedgeH h : b.loop_halfedges(far)) EXPECT_TRUE(grown.edges.count(edge_of(h)));
}

}  // namespace
}  // namespace kintsugi

namespace kintsugi {
namespace {

std::set<LoopH> as_set(const std::vector<LoopH>& v) { return {v.begin(), v.end()}; }

// The index of a plate's loops (invariants/loop_index.h) answers as loops_near does, on
// random boxes, before and after a ring is moved: told of the change, it finds the ring
// where it is now; once the change is committed, without being told again.
TEST(LoopBoxIndex, AnswersAsTheScanDoesBeforeAndAfterAChange) {
  zoo::ZooModel m = zoo::family(600, 0.0, 9);
  Body b = m.body;
  FaceH plate;
  std::size_t most = 0;
  for (FaceH f : b.faces())
    if (std::size_t k = b.loops_of(f).size(); k > most) most = k, plate = f;
  ASSERT_GT(most, 4 * kManyLoops);
  const double chordal = 1e-3;
  LoopBoxIndex index;
  EXPECT_FALSE(index.has(plate));
  index.committed(b, plate, {}, {}, chordal);
  ASSERT_TRUE(index.has(plate));
  geo::Box all;
  for (VertexH v : b.vertices()) all.add(b.point(v));
  std::mt19937_64 rng(4);
  auto random_box = [&] {
    std::uniform_real_distribution<double> u(0, 1);
    const geo::Vec3 c = all.min + (all.max - all.min).cwiseProduct(geo::Vec3(u(rng), u(rng), u(rng)));
    return geo::Box::around(c, u(rng) * 0.1 * all.diagonal());
  };
  int nonempty = 0;
  for (int i = 0; i < 200; ++i) {
    const geo::Box box = random_box();
    const auto want = as_set(loops_near(b, plate, box));
    nonempty += want.size() > 1;
    EXPECT_EQ(as_set(index.near(b, plate, box, {}, {}, chordal)), want);
  }
  EXPECT_GT(nonempty, 20);

  // A square ring moved by half the plate, corner by corner.
  LoopH ring;
  for (LoopH l : b.loops_of(plate))
    if (!b.is_outer(l) && !b.is_lone(l) && b.loop_vertices(l).size() == 4) ring = l;
  ASSERT_TRUE(ring.valid());
  const std::vector<VertexH> corners = b.loop_vertices(ring);
  const geo::Box before = loop_box(b, ring, chordal);
  geo::Vec3 shift = 0.5 * (all.max - all.min);
  shift.z() = 0;
  if (std::abs(b.point(corners[0]).z() - b.point(corners[1]).z()) > 1e-9) GTEST_SKIP() << "the plate is not level";
  for (VertexH v : corners) b.set_point(v, b.point(v) + shift);
  for (HalfedgeH h : b.loop_halfedges(ring)) {
    EdgeH e = edge_of(h);
    const geo::Vec3 a = b.point(b.origin(halfedge_of(e, 0))), c = b.point(b.target(halfedge_of(e, 0)));
    b.set_curve(e, geo::Line{a, (c - a).normalized()});
  }
  const std::set<VertexH> moved(corners.begin(), corners.end());
  const geo::Box now = loop_box(b, ring, chordal);
  auto has_ring = [&](const std::vector<LoopH>& v) { return std::count(v.begin(), v.end(), ring) == 1; };
  EXPECT_TRUE(has_ring(index.near(b, plate, now, moved, {}, chordal)));
  EXPECT_FALSE(has_ring(index.near(b, plate, before, moved, {}, chordal)));
  index.committed(b, plate, moved, {}, chordal);
  EXPECT_TRUE(has_ring(index.near(b, plate, now, {}, {}, chordal)));
  EXPECT_FALSE(has_ring(index.near(b, plate, before, {}, {}, chordal)));
  for (int i = 0; i < 200; ++i) {
    const geo::Box box = random_box();
    EXPECT_EQ(as_set(index.near(b, plate, box, {}, {}, chordal)), as_set(loops_near(b, plate, box)));
  }
}

}  // namespace
}  // namespace kintsugi

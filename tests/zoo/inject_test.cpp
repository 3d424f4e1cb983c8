#include "invariants/element_geometry.h"
#include "invariants/region_validity.h"
#include "invariants/topology_check.h"
#include "kernel/builders.h"
#include "tests/zoo/measure.h"
#include "zoo/zoo.h"

#include <gtest/gtest.h>
#include <rapidcheck.h>
#include <rapidcheck/gtest.h>

#include <set>

namespace kintsugi::zoo {
namespace {

using test::element_alive;
using test::index_of;

struct Solid {
  std::string name;
  Body (*make)();
};

const std::vector<Solid>& solids() {
  static const std::vector<Solid> s = {
      {"box", [] { return build::box(1, 1, 1); }},
      {"prism6", [] { return build::prism(build::regular_polygon(6, 1), 1.5); }},
      {"pyramid4", [] { return build::pyramid(build::regular_polygon(4, 1), 1); }},
      {"pyramid5", [] { return build::pyramid(build::regular_polygon(5, 1), 1.2); }},
      {"cylinder", [] { return build::cylinder(1, 2); }},
      {"cone", [] { return build::cone(1, 2); }},
      {"sphere", [] { return build::sphere(1); }},
      {"torus", [] { return build::torus(3, 1); }},
  };
  return s;
}

// Which builder solids must accept each type (the others may refuse, cleanly).
bool must_accept(const std::string& solid, ProblemType t) {
  bool poly = solid == "box" || solid == "prism6" || solid == "pyramid4" || solid == "pyramid5";
  switch (t) {
    case ProblemType::short_edge: return solid == "pyramid4" || solid == "pyramid5";
    case ProblemType::mergeable_edges:
    case ProblemType::short_edge_chain: return poly || solid == "cylinder";
    default: return poly;
  }
}

// Measures the recorded defect on the body and checks it against the tolerance.
void check_defect(const Body& b, const KnownDefect& d, double tol) {
  SCOPED_TRACE(problem_name(d.type));
  ASSERT_FALSE(d.elements.empty());
  for (const std::string& s : d.elements) EXPECT_TRUE(element_alive(b, s)) << s;
  auto face = [&](std::size_t i) { return FaceH(index_of(d.elements[i])); };
  auto edge = [&](std::size_t i) { return EdgeH(index_of(d.elements[i])); };
  switch (d.type) {
    case ProblemType::face_gap:
    case ProblemType::edge_gap:
    case ProblemType::multi_face_gap: {
      LoopH l;
      for (const std::string& s : d.elements)
        if (s[0] == 'l') l = LoopH(index_of(s));
      ASSERT_TRUE(l.valid());
      EXPECT_TRUE(b.is_border(l));
      std::set<FaceH> across;
      for (HalfedgeH h : b.loop_halfedges(l)) across.insert(b.face(twin(h)));
      std::size_t want = d.type == ProblemType::face_gap ? 1 : d.type == ProblemType::edge_gap ? 2 : 3;
      if (d.type == ProblemType::multi_face_gap) EXPECT_GE(across.size(), want);
      else EXPECT_EQ(across.size(), want);
      EXPECT_LT(d.size, tol);
      break;
    }
    case ProblemType::short_edge:
      EXPECT_LT(test::edge_length(b, edge(0)), tol);
      EXPECT_GT(test::edge_length(b, edge(0)), 0.1 * tol);
      break;
    case ProblemType::short_edge_chain: {
      EXPECT_GE(d.elements.size(), 2u);
      for (std::size_t i = 0; i < d.elements.size(); ++i) EXPECT_LT(test::edge_length(b, edge(i)), tol);
      for (std::size_t i = 0; i + 1 < d.elements.size(); ++i) {
        VertexH m = b.target(halfedge_of(edge(i), 0));
        EXPECT_EQ(b.degree(m), 2u);
      }
      break;
    }
    case ProblemType::small_face: {
      geo::RegionMeasure m = test::face_region(b, face(0));
      ASSERT_TRUE(m.ok()) << m.problem;
      EXPECT_LT(m.area, tol * tol);
      EXPECT_GT(m.area, 0.0);
      break;
    }
    case ProblemType::small_face_chain: {
      EXPECT_GE(d.elements.size(), 2u);
      for (std::size_t i = 0; i < d.elements.size(); ++i) {
        geo::RegionMeasure m = test::face_region(b, face(i));
        ASSERT_TRUE(m.ok()) << m.problem;
        EXPECT_LT(m.area, tol * tol);
      }
      for (std::size_t i = 0; i + 1 < d.elements.size(); ++i) {
        bool adjacent = false;
        for (HalfedgeH h : b.loop_halfedges(b.outer_loop(face(i))))
          adjacent = adjacent || b.face(twin(h)) == face(i + 1);
        EXPECT_TRUE(adjacent) << d.elements[i] << " " << d.elements[i + 1];
      }
      break;
    }
    case ProblemType::sliver_face: {
      geo::RegionMeasure m = test::face_region(b, face(0));
      ASSERT_TRUE(m.ok()) << m.problem;
      double diag = (m.bounds.max - m.bounds.min).norm();
      EXPECT_LT(m.area / diag, tol);
      EXPECT_GT(diag, 5 * tol);
      break;
    }
    case ProblemType::same_geometry_faces: {
      FaceH a = face(0), c = face(1);
      double dev = geo::surface_deviation(b.surface(a), b.surface(c), test::face_vertices(b, a), test::face_vertices(b, c));
      EXPECT_LE(dev, tol);
      // A planar face is split and one half tilted; a curved one is split along a ruling,
      // both halves on the one surface.
      if (std::holds_alternative<geo::Plane>(b.surface(a)))
        EXPECT_GT(dev, 0.0);
      else
        EXPECT_TRUE(b.surface(a) == b.surface(c));
      bool adjacent = false;
      for (HalfedgeH h : b.loop_halfedges(b.outer_loop(a))) adjacent = adjacent || b.face(twin(h)) == c;
      EXPECT_TRUE(adjacent);
      break;
    }
    case ProblemType::mergeable_edges: {
      VertexH v(index_of(d.elements[0]));
      ASSERT_EQ(b.degree(v), 2u);
      std::vector<HalfedgeH> o = b.outgoing(v);
      std::set<FaceH> f1 = {b.face(o[0]), b.face(twin(o[0]))}, f2 = {b.face(o[1]), b.face(twin(o[1]))};
      EXPECT_EQ(f1, f2);
      break;
    }
    case ProblemType::pinched_face: {
      EdgeH e1 = edge(1), e2 = edge(2);
      auto ends = [&](EdgeH e) {
        HalfedgeH h = halfedge_of(e, 0);
        return std::pair{b.point(b.origin(h)), b.point(b.target(h))};
      };
      auto [p1, q1] = ends(e1);
      auto [p2, q2] = ends(e2);
      double dist = test::segment_distance(p1, q1, p2, q2);
      EXPECT_LT(dist, tol);
      EXPECT_GT(dist, 0.0);
      std::set<FaceH> fs;
      for (unsigned s = 0; s < 2; ++s) fs.insert(b.face(halfedge_of(e1, s))), fs.insert(b.face(halfedge_of(e2, s)));
      EXPECT_TRUE(fs.count(face(0)));
      break;
    }
  }
}

void inject_and_check(const Solid& s, ProblemType t, std::uint64_t seed, double tol) {
  Body b = s.make();
  Body before = b.clone();
  std::string err;
  auto r = inject(b, t, seed, std::nullopt, tol, &err);
  SCOPED_TRACE(s.name + " " + problem_name(t) + " seed " + std::to_string(seed));
  if (!r) {
    EXPECT_FALSE(must_accept(s.name, t)) << err;
    EXPECT_FALSE(err.empty());
    std::string why;
    EXPECT_TRUE(b.equals(before, &why)) << why;
    return;
  }
  EXPECT_EQ(r->defect.type, t);
  std::vector<Violation> v = check_topology(b);
  EXPECT_TRUE(v.empty()) << to_string(v[0]);
  std::vector<std::string> off = geometry_offences(b, tol * 1e-6);
  EXPECT_TRUE(off.empty()) << off[0];
  check_defect(b, r->defect, tol);
  EXPECT_LT(r->defect.size, t == ProblemType::small_face || t == ProblemType::small_face_chain ? tol * tol : tol);
}

TEST(Inject, EveryTypeOnEveryBuilderSolid) {
  for (const Solid& s : solids())
    for (ProblemType t : kAllProblemTypes) inject_and_check(s, t, 1, 0.02);
}

RC_GTEST_PROP(Inject, RandomSeedsGiveValidBodiesWithMeasuredDefects, ()) {
  const auto seed = *rc::gen::arbitrary<std::uint64_t>();
  const auto ti = *rc::gen::inRange<std::size_t>(0, kAllProblemTypes.size());
  const auto si = *rc::gen::inRange<std::size_t>(0, solids().size());
  const double tol = *rc::gen::element(0.005, 0.02, 0.05);
  inject_and_check(solids()[si], kAllProblemTypes[ti], seed, tol);
  RC_ASSERT(!::testing::Test::HasFailure());
}

// A pyramid's base edges end on slanted faces, where no fillet fits: the seed that drew a
// fillet for all four of them (17972913402085416, found by the property above) left the
// pyramid without a sliver. The draw falls back to a chamfer there.
TEST(Inject, EverySeedPutsASliverOnAPyramid) {
  for (std::uint64_t seed : {std::uint64_t(17972913402085416ull), std::uint64_t(1), std::uint64_t(2)})
    inject_and_check(solids()[2], ProblemType::sliver_face, seed, 0.02);
  for (std::uint64_t seed = 0; seed < 300; ++seed) {
    Body b = build::pyramid(build::regular_polygon(4, 1), 1);
    EXPECT_TRUE(inject(b, ProblemType::sliver_face, seed, std::nullopt, 0.02, nullptr)) << "seed " << seed;
  }
}

// A face split twice: the second split's corners are moved to where its tilted plane
// meets the first split's, nearly parallel, and one landed outside the face, its loop
// crossing itself (seeds 317267 then 6615 on a pyramid's base; the beautify property
// failed about once in twenty runs on such models). The injector keeps only a defect
// that adds no crossing loops.
TEST(Inject, ADefectNeverLeavesALoopCrossingItself) {
  Body b = build::pyramid(build::regular_polygon(4, 1), 1);
  const geo::Tolerances tol = geo::Tolerances::for_model(0.02, model_size(b));
  std::string err;
  ASSERT_TRUE(inject(b, ProblemType::same_geometry_faces, 317267, std::nullopt, 0.02, &err)) << err;
  ASSERT_TRUE(inject(b, ProblemType::same_geometry_faces, 6615, std::nullopt, 0.02, &err)) << err;
  const std::vector<FaceH> fs = b.faces();
  std::vector<Violation> v = loop_violations(b, std::set<FaceH>(fs.begin(), fs.end()), tol);
  EXPECT_TRUE(v.empty()) << to_string(v.front());
}

// A sliver is put on a real edge only: on the edge between a face and the piece of it
// fitted twice (within a degree of one plane) a chamfer came out 0.003 tolerances wide,
// a small face by area that no repair can turn into a vertex.
TEST(Inject, SliversAreAsWideAsAskedBesideAFaceFittedTwice) {
  Body base = build::box(1, 1, 1);
  std::string err;
  ASSERT_TRUE(inject(base, ProblemType::small_face_chain, 5252837, std::nullopt, 0.02, &err)) << err;
  ASSERT_TRUE(inject(base, ProblemType::same_geometry_faces, 47, std::nullopt, 0.02, &err)) << err;
  for (std::uint64_t seed : {std::uint64_t(10175907), std::uint64_t(1), std::uint64_t(2), std::uint64_t(3)}) {
    Body b = base.clone();
    auto r = inject(b, ProblemType::sliver_face, seed, std::nullopt, 0.02, &err);
    ASSERT_TRUE(r) << err;
    // The widths drawn are 0.1-0.4 tolerances, times 0.6-0.7.
    EXPECT_GT(r->defect.size, 0.05 * 0.02) << "seed " << seed << ": " << r->description;
  }
}

// The designer's twin of a pinch (the block made flush with the face across the edge)
// is a consistent model: on a face whose neighbour across the edge slopes (a pyramid's
// base), the flush block's side is not in that neighbour's plane, and the twin had a face
// off its own plane (the scan-parts score then counted the repair's correct extra face as
// a wrong count).
TEST(Inject, APinchsCleanTwinIsConsistent) {
  int made = 0;
  for (std::uint64_t seed = 1; seed <= 60; ++seed) {
    Body b = seed % 2 ? build::pyramid(build::regular_polygon(4, 2), 1) : build::box(2, 2, 1);
    Body twin;
    std::string err;
    if (!inject(b, ProblemType::pinched_face, seed, std::nullopt, 0.02, &err, &twin)) continue;
    if (twin.faces().empty()) continue;
    ++made;
    const geo::Tolerances tol = geo::Tolerances::for_model(0.02, model_size(twin));
    std::vector<std::string> off = geometry_offences(twin, tol.precision);
    EXPECT_TRUE(off.empty()) << "seed " << seed << ": " << off.front();
  }
  EXPECT_GT(made, 0);
}

TEST(Inject, DeterministicPerSeed) {
  for (ProblemType t : kAllProblemTypes) {
    Body a = build::pyramid(build::regular_polygon(4, 1), 1), c = a.clone();
    auto ra = inject(a, t, 42, std::nullopt, 0.02, nullptr);
    auto rc_ = inject(c, t, 42, std::nullopt, 0.02, nullptr);
    ASSERT_TRUE(ra && rc_) << problem_name(t);
    std::string why;
    EXPECT_TRUE(a.equals(c, &why)) << why;
    EXPECT_EQ(ra->defect.elements, rc_->defect.elements);
  }
}

TEST(Inject, AtNamedElementAndRefusals) {
  Body b = build::box(1, 1, 1);
  std::string err;
  auto r = inject(b, ProblemType::mergeable_edges, 3, std::string("e0"), 0.02, &err);
  ASSERT_TRUE(r) << err;
  EXPECT_EQ(r->defect.elements[1], "e0");
  Body c = build::box(1, 1, 1);
  EXPECT_FALSE(inject(c, ProblemType::short_edge, 3, std::nullopt, 0.02, &err));
  EXPECT_NE(err.find("short_edge"), std::string::npos) << err;
  EXPECT_FALSE(inject(c, ProblemType::face_gap, 3, std::string("f99"), 0.02, &err));
  EXPECT_NE(err.find("f99"), std::string::npos) << err;
  EXPECT_FALSE(inject(c, ProblemType::face_gap, 3, std::nullopt, 5.0, &err));  // tolerance larger than the box
}

TEST(Inject, InjectedDefectsAccumulate) {
  Body b = build::pyramid(build::regular_polygon(4, 2), 2);
  std::uint64_t seed = 7;
  std::vector<KnownDefect> made;
  for (ProblemType t : {ProblemType::face_gap, ProblemType::mergeable_edges, ProblemType::short_edge,
                        ProblemType::sliver_face, ProblemType::short_edge_chain}) {
    std::string err;
    auto r = inject(b, t, seed++, std::nullopt, 0.02, &err);
    ASSERT_TRUE(r) << problem_name(t) << ": " << err;
    made.push_back(r->defect);
  }
  EXPECT_TRUE(check_topology(b).empty());
  for (const KnownDefect& d : made)
    for (const std::string& s : d.elements) EXPECT_TRUE(element_alive(b, s)) << s;
}

}  // namespace
}  // namespace kintsugi::zoo

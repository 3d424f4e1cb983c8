// The topology validator is itself tested: for every violation code of check_topology
// (spec/invariants.md) there is a case that takes a valid body, breaks exactly that
// invariant with a raw edit below the operators (tests/invariants/raw_body.h), and
// expects a non-empty list of violations that all carry that code — the invariant is
// caught, and no other invariant is blamed for it.
#include "invariants/assemble.h"
#include "invariants/topology_check.h"
#include "kernel/assemble.h"
#include "kernel/builders.h"
#include "kernel/euler.h"
#include "tests/invariants/raw_body.h"
#include "tests/invariants/spec_codes.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <functional>
#include <string>
#include <vector>
#include <set>
#include <stdexcept>

namespace kintsugi {
namespace {

using geo::Vec3;

// ---- valid bodies to break -------------------------------------------------------

// Two bodies side by side in one body, each its own shell (assembled from their
// descriptions with the second one's ids shifted past the first one's).
Body side_by_side(const Body& a, const Body& c) {
  BodyDescription d = describe(a), e = describe(c);
  auto top = [](const auto& items) {
    std::uint32_t t = 0;
    for (const auto& x : items) t = std::max(t, x.id + 1);
    return t;
  };
  const std::uint32_t dv = top(d.vertices), de = top(d.edges), dl = top(d.loops), df = top(d.faces), ds = top(d.shells);
  for (VertexDesc v : e.vertices) {
    v.id += dv;
    v.point += Vec3(10, 0, 0);
    d.vertices.push_back(v);
  }
  for (EdgeDesc x : e.edges) {
    x.id += de;
    for (HalfedgeDesc& h : x.he) h = {h.origin + dv, h.next + 2 * de, h.loop + dl};
    // Curves are not moved with the vertices: these bodies are for the topology check.
    d.edges.push_back(x);
  }
  for (LoopDesc l : e.loops) {
    l.id += dl;
    if (l.face) *l.face += df;
    if (l.first) *l.first += 2 * de;
    if (l.lone) *l.lone += dv;
    d.loops.push_back(l);
  }
  for (FaceDesc f : e.faces) {
    f.id += df;
    f.shell += ds;
    for (std::uint32_t& l : f.loops) l += dl;
    d.faces.push_back(f);
  }
  for (ShellDesc s : e.shells) {
    s.id += ds;
    d.shells.push_back(s);
  }
  AssembleError err;
  std::optional<Body> b = assemble(d, &err);
  if (!b) throw std::logic_error("side_by_side: " + err.element + ": " + err.message);
  return *b;
}

// A box with its face f0 removed: a border cycle (an open shell).
Body box_with_gap() {
  Body b = build::box();
  if (!euler::kfmb(b, b.faces()[0])) throw std::logic_error("kfmb refused");
  return b;
}

// A single face whose only loop is a lone vertex (what mvfs makes).
Body lone_vertex_face() {
  Body b;
  if (!euler::mvfs(b, Vec3(0, 0, 0))) throw std::logic_error("mvfs refused");
  return b;
}

// ---- the cases -------------------------------------------------------------------

struct Case {
  std::string name;
  std::string code;  // the one invariant the edit breaks
  std::function<Body()> make;
  std::function<void(Body&)> breaks;
};

void PrintTo(const Case& c, std::ostream* os) { *os << c.name; }

// A half-edge of face f's outer loop, and the one after it.
HalfedgeH first_of(const Body& b, FaceH f) { return b.first(b.outer_loop(f)); }

std::vector<Case> cases() {
  return {
      {"ReferenceOutHalfedgeOutOfRange", "reference", [] { return build::box(); },
       [](Body& b) { RawBody::vertex(b, b.vertices()[0]).out = HalfedgeH(1u << 30); }},
      {"ReferenceLoopOfADeadFace", "reference", [] { return build::box(); },
       [](Body& b) {
         // The face is a tombstone (its shell no longer counts it) but its loop lives on.
         FaceH f = b.faces()[0];
         RawBody::kill(b, f);
         RawBody::shell(b, b.shell(f)).faces--;
       }},
      {"TwinNextPrevPrevNotReciprocal", "twin_next_prev", [] { return build::box(); },
       [](Body& b) {
         HalfedgeH h = first_of(b, b.faces()[0]);
         RawBody::halfedge(b, h).prev = b.next(h);  // a 4-cycle: prev is two steps back, not one ahead
       }},
      {"LoopMembershipHalfedgeNamesAnotherLoop", "loop_membership", [] { return build::box(); },
       [](Body& b) {
         HalfedgeH h = first_of(b, b.faces()[0]);
         LoopH other = b.outer_loop(b.faces()[1]);
         ASSERT_NE(other, b.loop(twin(h)));
         RawBody::halfedge(b, h).loop = other;
       }},
      {"VertexOrbitTwoFansAtOneVertex", "vertex_orbit",
       [] { return side_by_side(build::box(), build::box()); },
       [](Body& b) {
         // Glue a corner of the second box onto a corner of the first: a non-manifold
         // vertex whose rotation covers only one of its two fans.
         VertexH keep = b.vertices().front(), gone = b.vertices().back();
         for (HalfedgeH h : b.halfedges())
           if (b.origin(h) == gone) RawBody::halfedge(b, h).origin = keep;
         RawBody::kill(b, gone);
       }},
      {"VertexOrbitOutDoesNotLeaveTheVertex", "vertex_orbit", [] { return build::box(); },
       [](Body& b) {
         VertexH v = b.vertices()[0];
         RawBody::vertex(b, v).out = twin(b.out(v));
       }},
      {"LoneVertexIsDead", "lone_vertex", lone_vertex_face,
       [](Body& b) { RawBody::kill(b, b.vertices()[0]); }},
      {"LoneVertexHasEdges", "lone_vertex", [] { return build::box(); },
       [](Body& b) {
         // A lone-vertex ring of f0 whose vertex is a corner of the box.
         FaceH f = b.faces()[0];
         LoopH ring = RawBody::add_loop(b, LoopRec{f, HalfedgeH{}, b.loop_vertices(b.outer_loop(f))[0], LoopH{}});
         RawBody::loop(b, b.outer_loop(f)).next_in_face = ring;
       }},
      {"LoneVertexBorderCycle", "lone_vertex", [] { return build::box(); },
       [](Body& b) {
         VertexH v = RawBody::add_vertex(b, Vec3(5, 5, 5));
         RawBody::add_loop(b, LoopRec{FaceH{}, HalfedgeH{}, v, LoopH{}});
       }},
      {"EdgeWithoutFaceBorderOnBothSides", "edge_without_face", box_with_gap,
       [](Body& b) {
         // The face across an edge of the gap becomes a second border cycle.
         LoopH gap = b.border_cycles().at(0);
         FaceH f = b.face(twin(b.first(gap)));
         RawBody::shell(b, b.shell(f)).faces--;
         RawBody::loop(b, b.outer_loop(f)).face = FaceH{};
         RawBody::kill(b, f);
       }},
      {"DanglingDeadLoopNamedByHalfedges", "dangling", box_with_gap,
       [](Body& b) { RawBody::kill(b, b.border_cycles().at(0)); }},
      {"DanglingVertexWithoutEdgesOrLoop", "dangling", [] { return build::box(); },
       [](Body& b) { RawBody::add_vertex(b, Vec3(5, 5, 5)); }},
      {"FaceLoopsChainReachesAnotherFacesLoop", "face_loops", [] { return build::box(); },
       [](Body& b) { RawBody::loop(b, b.outer_loop(b.faces()[0])).next_in_face = b.outer_loop(b.faces()[1]); }},
      {"FaceLoopsLoopNamesAFaceThatDoesNotChainIt", "face_loops", [] { return build::box(); },
       [](Body& b) { RawBody::loop(b, b.outer_loop(b.faces()[1])).face = b.faces()[0]; }},
      {"FaceLoopsFaceWithoutLoops", "face_loops", [] { return build::box(); },
       [](Body& b) {
         ShellH s = b.shells()[0];
         RawBody::add_face(b, FaceRec{s, LoopH{}});
         RawBody::shell(b, s).faces++;
       }},
      {"ShellFacesCountOffByOne", "shell_faces", [] { return build::box(); },
       [](Body& b) { RawBody::shell(b, b.shells()[0]).faces++; }},
      {"ShellConnectedTwoComponents", "shell_connected",
       [] { return side_by_side(build::box(), build::torus(3, 1)); },
       [](Body& b) {
         // The torus's face moves into the box's shell. A box (χ = 2) and a torus (χ = 0)
         // together still satisfy Euler–Poincaré for genus 0: only connectivity is wrong.
         ShellH box = b.shells()[0], torus = b.shells()[1];
         for (FaceH f : b.faces())
           if (b.shell(f) == torus) {
             RawBody::face(b, f).shell = box;
             RawBody::shell(b, box).faces++;
           }
         RawBody::kill(b, torus);
       }},
      {"EulerPoincareWrongGenus", "euler_poincare", [] { return build::box(); },
       [](Body& b) { RawBody::shell(b, b.shells()[0]).genus = 1; }},
  };
}

// Which codes a list of violations names, for messages.
std::string codes(const std::vector<Violation>& vs) {
  std::string s;
  for (const Violation& v : vs) s += "\n  " + to_string(v);
  return s;
}

class BrokenInvariant : public ::testing::TestWithParam<Case> {};

TEST_P(BrokenInvariant, IsNamedAndNothingElseIs) {
  const Case& c = GetParam();
  Body b = c.make();
  ASSERT_TRUE(check_topology(b).empty()) << c.name << ": the body is not valid before the edit" << codes(check_topology(b));
  c.breaks(b);
  std::vector<Violation> got = check_topology(b);
  ASSERT_FALSE(got.empty()) << c.name << ": the broken " << c.code << " went unnoticed";
  for (const Violation& v : got) EXPECT_EQ(v.invariant, c.code) << c.name << codes(got);
}

INSTANTIATE_TEST_SUITE_P(Topology, BrokenInvariant, ::testing::ValuesIn(cases()),
                         [](const auto& info) { return info.param.name; });

// `loop_closed` cannot be broken alone: a walk that does not come back to where it
// started must pass a half-edge whose next does not name it as prev, and reciprocity
// is checked on every step before closure is. Such a cycle is named as twin_next_prev
// (and the vertex rotations it disturbs as vertex_orbit), never as valid.
const std::set<std::string> kCaughtByAnEarlierLayer = {"loop_closed"};

TEST(TopologyCheck, ACycleThatDoesNotCloseIsCaughtByReciprocity) {
  Body b = build::box();
  HalfedgeH a = first_of(b, b.faces()[0]);
  HalfedgeH last = b.prev(a);
  RawBody::halfedge(b, last).next = b.next(a);  // a -> x -> y -> last -> x: a rho, not a ring
  std::vector<Violation> got = check_topology(b);
  ASSERT_FALSE(got.empty());
  std::set<std::string> named;
  for (const Violation& v : got) named.insert(v.invariant);
  EXPECT_TRUE(named.count("twin_next_prev")) << codes(got);
  for (const std::string& n : named) EXPECT_TRUE(n == "twin_next_prev" || n == "vertex_orbit") << codes(got);
}

// A large body's loop and vertex walks run on two threads (invariants/topology_check.cpp):
// what they find, and its order, is what one thread finds, on a body broken in many places
// (loops and rotations both).
TEST(TopologyCheck, ALargeBodyIsJudgedTheSameOnOneThreadAndOnTwo) {
  Body b = build::grid_box(30000);
  ASSERT_GE(b.halfedge_slots(), 100000u);
  const std::vector<FaceH> faces = b.faces();
  for (std::size_t k = 0; k < faces.size(); k += 997) {
    HalfedgeH a = first_of(b, faces[k]);
    RawBody::halfedge(b, b.prev(a)).next = b.next(a);
  }
  RawBody::vertex(b, b.vertices()[12345]).out = HalfedgeH{};
  const char* was = std::getenv("KINTSUGI_THREADS");
  const std::string saved = was ? was : "";
  std::vector<std::vector<Violation>> got;
  for (const char* threads : {"1", "2"}) {
    setenv("KINTSUGI_THREADS", threads, 1);
    got.push_back(check_topology(b));
  }
  if (was) setenv("KINTSUGI_THREADS", saved.c_str(), 1); else unsetenv("KINTSUGI_THREADS");
  std::set<std::string> named;
  for (const Violation& v : got[0]) named.insert(v.invariant);
  EXPECT_TRUE(named.count("twin_next_prev") && named.count("vertex_orbit")) << codes(got[0]);
  ASSERT_EQ(got[0].size(), got[1].size());
  for (std::size_t i = 0; i < got[0].size(); ++i) EXPECT_EQ(to_string(got[0][i]), to_string(got[1][i])) << i;
}

// Every code in the spec's topology table has a case above (or is in kCaughtByAnEarlierLayer
// with its test), and every case's code is in the spec.
TEST(TopologyCheck, EverySpecCodeHasABreakingCase) {
  std::set<std::string> have = kCaughtByAnEarlierLayer;
  for (const Case& c : cases()) have.insert(c.code);
  std::set<std::string> spec = test::spec_codes(KINTSUGI_SPEC_DIR "/invariants.md", "", "## Local check");
  EXPECT_EQ(spec.size(), 12u);
  for (const std::string& code : spec) EXPECT_TRUE(have.count(code)) << code << " has no case that breaks it alone";
  for (const std::string& code : have) EXPECT_TRUE(spec.count(code)) << code << " is not in spec/invariants.md";
}

}  // namespace
}  // namespace kintsugi

// The whole-body topology check, built on the kernel's local walks (kernel/
// local_check.h): the same loop and rotation walks over every element, then the layers
// only a whole body can answer — each half-edge counted once, ownership, connected
// shells, Euler–Poincaré.
#include "invariants/topology_check.h"

#include "kernel/local_check.h"
#include "kernel/threads.h"

#include <iterator>

namespace kintsugi {

namespace {

// Half-edges from which the loop and vertex walks run on two threads.
constexpr std::size_t kWalksOnTwoThreadsFrom = 100000;

// The walks plus the list they fill, so the global layers below read as before.
struct Checker {
  Checker(const Body& body) : b(body), walk(body, out) {}
  const Body& b;
  std::vector<Violation> out;
  StructureWalk walk;
  void add(const char* inv, std::vector<std::string> els, std::string detail) { walk.add(inv, std::move(els), std::move(detail)); }
  long loop(LoopH l) { return walk.loop(l); }
  long vertex(VertexH v) { return walk.vertex(v); }
};

}  // namespace

std::vector<Violation> check_topology(const Body& b) {
  Checker c(b);
  // Loops: closed cycles, and every half-edge counted exactly once.
  auto check_loops = [&b](Checker& c) {
    std::vector<long> per_loop(b.loop_slots(), 0);
    for (HalfedgeH h : b.halfedges()) {
      LoopH l = b.loop(h);
      if (l.idx() < per_loop.size()) per_loop[l.idx()]++;
      else c.add("reference", {h.str()}, "loop " + l.str() + " out of range");
    }
    for (LoopH l : b.loops()) {
      long n = c.loop(l);
      if (n >= 0 && n != per_loop[l.idx()])
        c.add("loop_membership", {l.str()},
              std::to_string(per_loop[l.idx()]) + " half-edges name this loop but its cycle has " + std::to_string(n));
    }
    for (LoopH l = LoopH(0); l.idx() < b.loop_slots(); l = LoopH(l.idx() + 1))
      if (!b.alive(l) && per_loop[l.idx()] > 0) c.add("dangling", {l.str()}, "dead loop still named by half-edges");
  };

  // Vertices: rotations cover exactly the half-edges leaving each vertex; lone vertices
  // sit in exactly one loop; no vertex without edges or loop.
  auto check_vertices = [&b](Checker& c) {
    std::vector<long> per_vertex(b.vertex_slots(), 0), lone_in(b.vertex_slots(), 0);
    for (HalfedgeH h : b.halfedges())
      if (b.origin(h).idx() < per_vertex.size()) per_vertex[b.origin(h).idx()]++;
    for (LoopH l : b.loops())
      if (b.is_lone(l) && b.lone_vertex(l).idx() < lone_in.size()) lone_in[b.lone_vertex(l).idx()]++;
    for (VertexH v : b.vertices()) {
      long n = c.vertex(v);
      if (n > 0 && n != per_vertex[v.idx()])
        c.add("vertex_orbit", {v.str()},
              std::to_string(per_vertex[v.idx()]) + " half-edges leave it but its rotation has " + std::to_string(n) +
                  " (a non-manifold vertex)");
      if (n == 0 && per_vertex[v.idx()] > 0) c.add("vertex_orbit", {v.str()}, "has edges but no out half-edge");
      if (n == 0 && lone_in[v.idx()] != 1)
        c.add("dangling", {v.str()}, "a vertex without edges must be the lone vertex of exactly one loop");
      if (n > 0 && lone_in[v.idx()] != 0) c.add("lone_vertex", {v.str()}, "has edges but is a loop's lone vertex");
    }
  };

  // The two walks only read the body: on a large one, the vertices' on a second thread,
  // their findings after the loops' as on one thread.
  Checker at_vertices(b);
  {
    OtherThread vertices([&] { check_vertices(at_vertices); },
                         b.halfedge_slots() >= kWalksOnTwoThreadsFrom && threads_from_environment() >= 2);
    check_loops(c);
    vertices.join();
  }
  c.out.insert(c.out.end(), std::make_move_iterator(at_vertices.out.begin()),
               std::make_move_iterator(at_vertices.out.end()));

  // Faces: their loop chain holds exactly the loops that name them; one shell each.
  std::vector<long> loops_naming(b.face_slots(), 0);
  for (LoopH l : b.loops()) {
    FaceH f = b.face(l);
    if (f.valid() && f.idx() < loops_naming.size()) loops_naming[f.idx()]++;
  }
  std::vector<long> faces_in(b.shell_slots(), 0);
  for (FaceH f : b.faces()) {
    if (!b.alive(b.shell(f))) {
      c.add("reference", {f.str()}, "shell " + b.shell(f).str() + " is not live");
      continue;
    }
    faces_in[b.shell(f).idx()]++;
    long n = 0;
    bool ok = true;
    for (LoopH l = b.outer_loop(f); l.valid(); l = b.next_in_face(l)) {
      if (!b.alive(l) || b.face(l) != f || n > static_cast<long>(b.loop_slots())) {
        c.add("face_loops", {f.str(), l.str()}, "the face's loop chain reaches a loop that is not the face's");
        ok = false;
        break;
      }
      ++n;
    }
    if (ok && n != loops_naming[f.idx()])
      c.add("face_loops", {f.str()}, std::to_string(loops_naming[f.idx()]) + " loops name this face but its chain has " +
                                          std::to_string(n));
    if (ok && n == 0) c.add("face_loops", {f.str()}, "has no outer loop");
  }
  for (ShellH s : b.shells())
    if (faces_in[s.idx()] != static_cast<long>(b.shell_face_count(s)))
      c.add("shell_faces", {s.str()}, "records " + std::to_string(b.shell_face_count(s)) + " faces but has " +
                                          std::to_string(faces_in[s.idx()]));
  if (!c.out.empty()) return c.out;  // the structure is too broken for the global layers

  // Shells are connected: walk faces and border cycles across edges from one face.
  std::vector<std::uint8_t> seen_loop(b.loop_slots(), 0);
  std::vector<long> components(b.shell_slots(), 0);
  for (LoopH seed : b.loops()) {
    if (seen_loop[seed.idx()] || b.is_border(seed)) continue;
    ShellH s = b.shell(seed);
    components[s.idx()]++;
    std::vector<FaceH> stack{b.face(seed)};
    std::vector<LoopH> border_stack;
    auto visit_loop = [&](LoopH l) {
      if (seen_loop[l.idx()]) return;
      if (b.is_border(l)) {
        seen_loop[l.idx()] = 1;
        border_stack.push_back(l);
      } else {
        stack.push_back(b.face(l));
      }
    };
    while (!stack.empty() || !border_stack.empty()) {
      std::vector<LoopH> ls;
      if (!stack.empty()) {
        FaceH f = stack.back();
        stack.pop_back();
        if (seen_loop[b.outer_loop(f).idx()]) continue;
        if (b.shell(f) != s) c.add("shell_connected", {f.str(), s.str()}, "face of shell " + b.shell(f).str() + " is connected to shell " + s.str());
        ls = b.loops_of(f);
        for (LoopH l : ls) seen_loop[l.idx()] = 1;
      } else {
        ls = {border_stack.back()};
        border_stack.pop_back();
      }
      for (LoopH l : ls)
        for (HalfedgeH h : b.loop_halfedges(l)) visit_loop(b.loop(twin(h)));
    }
  }
  for (ShellH s : b.shells())
    if (components[s.idx()] != 1)
      c.add("shell_connected", {s.str()}, "has " + std::to_string(components[s.idx()]) + " connected components");

  // Euler–Poincaré per shell: V − E + F + B − R = 2(1 − genus), border cycles counted
  // as faces with one loop (spec/invariants.md).
  std::vector<long> chi(b.shell_slots(), 0);
  for (VertexH v : b.vertices()) {
    HalfedgeH o = b.out(v);
    ShellH s;
    if (o.valid()) {
      s = b.shell(b.loop(o));
      if (!s.valid()) s = b.shell(b.loop(twin(o)));
    } else {
      for (LoopH l : b.loops())  // lone vertices are rare (mvfs, kemr on a strut)
        if (b.is_lone(l) && b.lone_vertex(l) == v) s = b.shell(l);
    }
    if (s.valid()) chi[s.idx()] += 1;
  }
  for (EdgeH e : b.edges()) {
    HalfedgeH h = halfedge_of(e, 0);
    ShellH s = b.is_border(h) ? b.shell(b.face(twin(h))) : b.shell(b.face(h));
    chi[s.idx()] -= 1;
  }
  for (FaceH f : b.faces()) chi[b.shell(f).idx()] += 1 - static_cast<long>(b.rings_of(f).size());
  for (LoopH l : b.border_cycles()) {
    ShellH s = b.shell(l);
    if (s.valid()) chi[s.idx()] += 1;
  }
  for (ShellH s : b.shells()) {
    long expect = 2 * (1 - static_cast<long>(b.shell_genus(s)));
    if (chi[s.idx()] != expect)
      c.add("euler_poincare", {s.str()}, "V - E + F + B - R = " + std::to_string(chi[s.idx()]) + " but genus " +
                                             std::to_string(b.shell_genus(s)) + " needs " + std::to_string(expect));
  }
  return c.out;
}

}  // namespace kintsugi

#include "kernel/local_check.h"

namespace kintsugi {

void StructureWalk::add(const char* invariant, std::vector<std::string> elements, std::string detail) {
  out_.push_back({invariant, std::move(elements), std::move(detail), 0.0});
}

bool StructureWalk::halfedge(HalfedgeH h) {
  if (!b_.alive(h)) return false;
  HalfedgeH n = b_.next(h), p = b_.prev(h);
  bool ok = true;
  if (!b_.alive(n) || !b_.alive(p)) {
    add("reference", {h.str()}, "next or prev is not a live half-edge");
    return false;
  }
  if (!b_.alive(b_.origin(h))) {
    add("reference", {h.str()}, "origin " + b_.origin(h).str() + " is not a live vertex");
    ok = false;
  }
  if (!b_.alive(b_.loop(h))) {
    add("reference", {h.str()}, "loop " + b_.loop(h).str() + " is not a live loop");
    return false;
  }
  if (b_.prev(n) != h || b_.next(p) != h) {
    add("twin_next_prev", {h.str(), n.str(), p.str()}, "next/prev are not reciprocal");
    ok = false;
  }
  if (b_.origin(n) != b_.target(h)) {
    add("twin_next_prev", {h.str(), n.str()}, "next does not start where " + h.str() + " ends");
    ok = false;
  }
  if (b_.loop(n) != b_.loop(h)) {
    add("loop_membership", {h.str(), n.str()}, "next is in another loop");
    ok = false;
  }
  if (b_.is_border(h) && b_.alive(b_.loop(twin(h))) && b_.is_border(twin(h)))
    add("edge_without_face", {edge_of(h).str()}, "both sides are border cycles");
  return ok;
}

long StructureWalk::loop(LoopH l) {
  if (!b_.alive(l)) {
    add("reference", {l.str()}, "not a live loop");
    return -1;
  }
  FaceH f = b_.face(l);
  if (f.valid() && !b_.alive(f)) add("reference", {l.str()}, "face " + f.str() + " is not a live face");
  if (b_.is_lone(l)) {
    if (!b_.alive(b_.lone_vertex(l))) {
      add("lone_vertex", {l.str()}, "lone vertex is not a live vertex");
    } else if (b_.out(b_.lone_vertex(l)).valid()) {
      add("lone_vertex", {l.str(), b_.lone_vertex(l).str()}, "the lone vertex has edges");
    }
    if (b_.is_border(l)) add("lone_vertex", {l.str()}, "a border cycle has no edges");
    return 0;
  }
  HalfedgeH start = b_.first(l);
  if (!b_.alive(start)) {
    add("reference", {l.str()}, "first half-edge is not live");
    return -1;
  }
  long n = 0;
  HalfedgeH h = start;
  const long bound = static_cast<long>(b_.halfedge_slots());
  do {
    if (!halfedge(h)) return -1;
    if (b_.loop(h) != l) {
      add("loop_membership", {l.str(), h.str()}, "half-edge on the cycle belongs to " + b_.loop(h).str());
      return -1;
    }
    h = b_.next(h);
    ++n;
  } while (h != start && n <= bound);
  if (h != start) {
    add("loop_closed", {l.str()}, "the cycle from " + start.str() + " does not close");
    return -1;
  }
  return n;
}

long StructureWalk::vertex(VertexH v) {
  if (!b_.alive(v)) {
    add("reference", {v.str()}, "not a live vertex");
    return -1;
  }
  HalfedgeH start = b_.out(v);
  if (!start.valid()) return 0;
  if (!b_.alive(start)) {
    add("reference", {v.str()}, "out half-edge " + start.str() + " is not live");
    return -1;
  }
  long n = 0;
  HalfedgeH h = start;
  const long bound = static_cast<long>(b_.halfedge_slots());
  do {
    if (!b_.alive(h) || b_.origin(h) != v) {
      add("vertex_orbit", {v.str(), h.str()}, "rotation reaches a half-edge that does not leave " + v.str());
      return -1;
    }
    if (!b_.alive(b_.prev(h))) return -1;
    h = b_.next(twin(h));
    ++n;
  } while (h != start && n <= bound);
  if (h != start) {
    add("vertex_orbit", {v.str()}, "rotation does not close");
    return -1;
  }
  return n;
}

void StructureWalk::face_outer(FaceH f) {
  LoopH o = b_.outer_loop(f);
  if (!b_.alive(o) || b_.face(o) != f) add("face_loops", {f.str()}, "outer loop is not the face's");
}

std::vector<Violation> check_local(const Body& b, const TouchedElements& t) {
  std::vector<Violation> out;
  StructureWalk walk(b, out);
  for (LoopH l : t.loops)
    if (b.alive(l)) walk.loop(l);
  for (VertexH v : t.vertices)
    if (b.alive(v)) walk.vertex(v);
  for (FaceH f : t.faces)
    if (b.alive(f)) walk.face_outer(f);
  return out;
}

}  // namespace kintsugi

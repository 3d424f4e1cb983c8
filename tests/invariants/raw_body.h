// Raw edits below the Euler operators, for tests only: they break one invariant of a
// valid body so that a test can check the validator names exactly that invariant
// (tests/invariants/topology_check_test.cpp). Body befriends RawBody for this alone;
// library code changes topology through kernel/euler.h and never includes this file.
#pragma once

#include "kernel/body.h"

namespace kintsugi {

struct RawBody {
  static HalfedgeRec& halfedge(Body& b, HalfedgeH h) { return b.halfedges_.at(h.idx()); }
  static VertexRec& vertex(Body& b, VertexH v) { return b.vertices_.at(v.idx()); }
  static LoopRec& loop(Body& b, LoopH l) { return b.loops_.at(l.idx()); }
  static FaceRec& face(Body& b, FaceH f) { return b.faces_.at(f.idx()); }
  static ShellRec& shell(Body& b, ShellH s) { return b.shells_.at(s.idx()); }

  // Tombstones without the bookkeeping an operator would do around them.
  static void kill(Body& b, VertexH v) { b.v_alive_.at(v.idx()) = 0; }
  static void kill(Body& b, LoopH l) { b.l_alive_.at(l.idx()) = 0; }
  static void kill(Body& b, FaceH f) { b.f_alive_.at(f.idx()) = 0; }
  static void kill(Body& b, ShellH s) { b.s_alive_.at(s.idx()) = 0; }

  // New live elements with the given records and nothing else changed.
  static VertexH add_vertex(Body& b, const geo::Vec3& p) {
    b.vertices_.push_back({});
    b.v_alive_.push_back(1);
    b.points_.push_back(p);
    return VertexH(static_cast<VertexH::Index>(b.vertices_.size() - 1));
  }
  static LoopH add_loop(Body& b, const LoopRec& r) {
    b.loops_.push_back(r);
    b.l_alive_.push_back(1);
    return LoopH(static_cast<LoopH::Index>(b.loops_.size() - 1));
  }
  static FaceH add_face(Body& b, const FaceRec& r) {
    b.faces_.push_back(r);
    b.f_alive_.push_back(1);
    b.surfaces_.push_back({});
    b.senses_.push_back(1);
    return FaceH(static_cast<FaceH::Index>(b.faces_.size() - 1));
  }
};

}  // namespace kintsugi

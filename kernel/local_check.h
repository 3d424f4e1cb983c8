// The local invariant check every Euler operator runs over what it touched (spec/
// invariants.md, "After each operator"): each touched loop is a closed cycle of its own
// half-edges with reciprocal next/prev, each touched vertex's rotation closes over
// half-edges leaving it, each touched face's outer loop is its own. Cheap, on in release
// builds. The walks are shared with the whole-body check in invariants/topology_check.h,
// which adds the global layers (orbit counts, ownership, connectivity, Euler–Poincaré).
#pragma once

#include "kernel/body.h"
#include "kernel/violation.h"

#include <string>
#include <vector>

namespace kintsugi {

// What an operator touched: the local check looks at exactly these.
struct TouchedElements {
  std::vector<LoopH> loops;
  std::vector<VertexH> vertices;
  std::vector<FaceH> faces;
};

// Everything wrong with the touched elements (dead ones are skipped: the operator
// killed them). Empty when all holds.
std::vector<Violation> check_local(const Body& b, const TouchedElements& t);

// The bounded walks, appending what they find to `out`.
class StructureWalk {
 public:
  StructureWalk(const Body& b, std::vector<Violation>& out) : b_(b), out_(out) {}
  // A loop is a closed cycle of its own half-edges (or a lone vertex). Returns the cycle
  // length (0 for a lone vertex), or -1 when the walk did not close.
  long loop(LoopH l);
  // The rotation of v reaches only half-edges leaving v and closes. Returns its length
  // (0: no edges), or -1.
  long vertex(VertexH v);
  // The outer loop of a live face is a live loop of that face.
  void face_outer(FaceH f);
  void add(const char* invariant, std::vector<std::string> elements, std::string detail);

 private:
  // References and next/prev reciprocity of one half-edge; false when it is too broken
  // to walk on from.
  bool halfedge(HalfedgeH h);
  const Body& b_;
  std::vector<Violation>& out_;
};

}  // namespace kintsugi

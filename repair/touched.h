// The elements a repair changed (created, moved, re-shaped, or whose loops it edited).
// The pipeline detects again only near these (the paper's queues, section 3.3), and the
// local geometry check looks at them and what is around them.
#pragma once

#include "kernel/handles.h"

#include <set>

namespace kintsugi {
// (An inline namespace: the kernel has its own per-operator `Touched` in namespace
// kintsugi, in a private header; this keeps the two distinct for the linker.)
inline namespace repair_touched {

struct Touched {
  std::set<VertexH> vertices;
  std::set<EdgeH> edges;
  std::set<FaceH> faces;
  // The faces whose surface was set (from the journal, once the repair is committed): a
  // face with many loops is taken whole only then (invariants/region_validity.h).
  std::set<FaceH> reshaped;

  bool empty() const { return vertices.empty() && edges.empty() && faces.empty(); }
  void merge(const Touched& o) {
    vertices.insert(o.vertices.begin(), o.vertices.end());
    edges.insert(o.edges.begin(), o.edges.end());
    faces.insert(o.faces.begin(), o.faces.end());
    reshaped.insert(o.reshaped.begin(), o.reshaped.end());
  }
  void clear() { *this = Touched{}; }
};

}  // namespace repair_touched
}  // namespace kintsugi

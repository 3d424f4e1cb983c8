// Gaps (paper 4.1): border cycles, classified by how many faces lie across them. A
// border cycle that passes a vertex twice is two gaps sharing that vertex: it is split
// into its fundamental cycles, each its own problem. O(size of the gaps).
#include "geometry/box.h"
#include "invariants/element_geometry.h"
#include "repair/detect_detail.h"

#include <set>
#include <unordered_map>

namespace kintsugi::detail {

// Splits the cyclic sequence of half-edges into simple cycles at repeated vertices.
std::vector<std::vector<HalfedgeH>> simple_cycles(const Body& b, const std::vector<HalfedgeH>& hs) {
  std::vector<std::vector<HalfedgeH>> out;
  std::vector<HalfedgeH> stack;
  std::unordered_map<VertexH, std::size_t> at;  // vertex -> index in stack of the half-edge leaving it
  for (HalfedgeH h : hs) {
    VertexH v = b.origin(h);
    auto it = at.find(v);
    if (it != at.end()) {
      std::size_t k = it->second;
      out.emplace_back(stack.begin() + long(k), stack.end());
      for (std::size_t i = k; i < stack.size(); ++i) at.erase(b.origin(stack[i]));
      stack.resize(k);
    }
    at[v] = stack.size();
    stack.push_back(h);
  }
  if (!stack.empty()) out.push_back(stack);
  return out;
}

void detect_gaps(DetectContext& c, std::vector<Problem>& out) {
  const Body& b = c.b;
  for (LoopH l : c.scope.borders) {
    for (const auto& cycle : simple_cycles(b, b.loop_halfedges(l))) {
      std::set<FaceH> faces;
      geo::Box box;
      for (HalfedgeH h : cycle) {
        faces.insert(b.face(twin(h)));
        // Points along the edge, not only its ends: a round gap bounded by one circle
        // has a single vertex.
        for (const geo::Vec3& q : halfedge_polyline(b, h, c.chordal)) box.add(q);
      }
      Problem p;
      p.type = faces.size() == 1 ? ProblemType::face_gap
             : faces.size() == 2 ? ProblemType::edge_gap
                                 : ProblemType::multi_face_gap;
      p.elements.push_back(l);
      for (FaceH f : faces) p.elements.push_back(f);
      p.measure = box.diagonal();
      p.measure_kind = Measure::diameter;
      p.subcase.shares_vertex = cycle.size() != b.loop_halfedges(l).size();
      out.push_back(std::move(p));
    }
  }
}

}  // namespace kintsugi::detail

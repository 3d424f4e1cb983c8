#include "repair/detect.h"

#include "invariants/element_geometry.h"
#include "repair/detect_detail.h"

#include <algorithm>

namespace kintsugi {

Detection detect(const Body& b, const geo::Tolerances& tol) {
  detail::DetectContext c{b, tol, 1e-3 * tol.length, {}, {}};
  c.faces.resize(b.face_slots());
  c.edge_length.assign(b.edge_slots(), 0.0);
  for (EdgeH e : b.edges()) c.edge_length[e.idx()] = edge_length(b, e);
  for (FaceH f : b.faces()) {
    std::optional<AreaAndBounds> m = face_area_and_bounds(b, f, c.chordal);
    detail::FaceInfo& fi = c.faces[f.idx()];
    if (!m) continue;  // unmeasurable faces are neither small nor slivers
    fi.measured = true;
    fi.area = m->area;
    fi.bbox_diagonal = m->bounds.diagonal();
    fi.small = m->area < tol.length * tol.length;
    fi.sliver = !fi.small && fi.bbox_diagonal > 0 && m->area / fi.bbox_diagonal < tol.length;
  }
  Detection d;
  detail::detect_gaps(c, d.problems);
  detail::detect_pinched(c, d.problems);
  detail::detect_small_and_sliver(c, d.problems);
  detail::detect_short_edges(c, d.problems);
  detail::detect_same_geometry(c, d.problems);
  detail::detect_mergeable(c, d.problems);
  std::stable_sort(d.problems.begin(), d.problems.end(),
                   [](const Problem& a, const Problem& b) { return problem_order(a.type) < problem_order(b.type); });
  for (const Problem& p : d.problems) d.counts[std::size_t(problem_order(p.type) - 1)]++;
  return d;
}

}  // namespace kintsugi

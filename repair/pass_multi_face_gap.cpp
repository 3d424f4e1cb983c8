// Pass 3, multiple-face gaps (paper 4.1, Figures 18-19): the faces around the gap are
// extended and intersected pairwise, and their intersection curves intersected. Where all
// meet in one point (within tolerance) the gap becomes one vertex there; where they meet
// in two points, one edge between two opposite faces; otherwise a new face fills the gap,
// with a plane when its border is coplanar within tolerance, else the analytic surface
// that fits best (the note says which). How far the faces are extended is decided by
// where they meet, not by the size of the gap; a meeting point that would fold an edge
// back is refused. repair/gap_closing.h has the steps.
#include "repair/gap_closing.h"

namespace kintsugi::detail {

namespace {

std::string repair_multi_face_gap(RepairCall& c) {
  std::string why;
  auto g = find_gap(c.b, c.problem, &why);
  if (!g) return why;
  if (g->runs.size() < 3) return "the gap now lies across fewer than three stretches of faces";
  GapClosure plan = plan_multi_face_gap(c.b, *g, c.tol);
  switch (plan.kind) {
    case GapClosure::one_vertex:
      c.note = "one vertex";
      return collapse_gap(c, *g, {}, plan.points);
    case GapClosure::two_vertices:
      c.note = "two vertices and an edge";
      return collapse_gap(c, *g, plan.keep, plan.points);
    case GapClosure::new_face: {
      std::string kind;
      why = fill_gap(c, *g, &kind);
      c.note = "new face (" + kind + "): " + plan.note;
      if (!why.empty()) return why + " (" + plan.note + ")";
      return "";
    }
  }
  return "unknown closure";
}

}  // namespace
}  // namespace kintsugi::detail

KINTSUGI_PASS(multi_face_gap) = {kintsugi::ProblemType::multi_face_gap, "multiple-face gaps",
                     "the faces around the gap are extended to where they meet: one vertex, two vertices and an edge, or a new face",
                     kintsugi::detail::repair_multi_face_gap};

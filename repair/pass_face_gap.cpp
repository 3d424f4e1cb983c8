// Pass 1, face gaps (paper 4.1, Figure 16): a gap inside one face is a hole the scanner
// left; the hole's loop is removed with its edges and vertices, and the face's own surface
// covers it (repair/gap_closing.h, remove_hole). A gap on the face's outer loop (an open
// end, such as a cylinder without its cap) is not covered by the face: it is filled with
// a new face, as a multiple-face gap with more than two meeting points is.
#include "repair/gap_closing.h"

namespace kintsugi::detail {

namespace {

std::string repair_face_gap(RepairCall& c) {
  std::string why;
  auto g = find_gap(c.b, c.problem, &why);
  if (!g) return why;
  if (g->runs.size() != 1) return "the gap now lies across " + std::to_string(g->runs.size()) + " stretches of faces";
  if (!c.b.is_outer(c.b.loop(twin(g->cycle[0])))) return remove_hole(c, *g);
  std::string kind;
  why = fill_gap(c, *g, &kind);
  if (why.empty()) c.note = "open end filled with a new face (" + kind + ")";
  return why;
}

}  // namespace
}  // namespace kintsugi::detail

KINTSUGI_PASS(face_gap) = {kintsugi::ProblemType::face_gap, "face gaps",
                     "a hole inside a face is removed with its edges and vertices; the face covers it",
                     kintsugi::detail::repair_face_gap};

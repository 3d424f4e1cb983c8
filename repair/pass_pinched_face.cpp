// Pass 4, pinched faces (paper 4.2): the two sides of the face that come closer than the
// tolerance are made to meet (repair/pinch.h): zipped into one edge where they run side
// by side, joined in one vertex at the narrowest place otherwise. Necking splits the
// face, spiking drops the spike's short end, bossing joins the ring to the outer loop.
#include "repair/beautify_detail.h"
#include "repair/pinch.h"

namespace kintsugi::detail {

std::string repair_pinched_face(RepairCall& c) {
  if (c.problem.elements.size() < 3) return "the problem names no face and two edges";
  FaceH f = parse_face(c.problem.elements[0]);
  EdgeH a = parse_edge(c.problem.elements[1]), e = parse_edge(c.problem.elements[2]);
  if (!f.valid() || !a.valid() || !e.valid()) return "the problem's elements are not a face and two edges";
  return close_pinch(c.b, f, a, e, c.tol, c.touched);
}

}  // namespace kintsugi::detail

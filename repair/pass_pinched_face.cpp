// Pass 4, pinched faces (paper 4.2): the two sides of the face that come closer than the
// tolerance are made to meet (repair/pinch.h): zipped into one edge where they run side
// by side, joined in one vertex at the narrowest place otherwise. Necking splits the
// face, spiking drops the spike's short end, bossing joins the ring to the outer loop.
// A pinch against a circle that would have to pass through more than three points not
// on one circle is refused (paper Figure 32(b)).
#include "repair/beautify_detail.h"
#include "repair/pinch.h"

namespace kintsugi::detail {

namespace {

std::string repair_pinched_face(RepairContext& c) {
  FaceH f = c.problem.first<FaceH>();
  std::vector<EdgeH> sides = c.problem.all<EdgeH>();
  if (!f.valid() || sides.size() != 2) return "the problem is not a face and two edges";
  return close_pinch(c.b, f, sides[0], sides[1], c.tol, c.touched);
}

}  // namespace
}  // namespace kintsugi::detail

KINTSUGI_PASS(pinched_face) = {kintsugi::ProblemType::pinched_face, "pinched faces",
                               "the two sides of the pinch meet: along one edge where they run side by side, "
                               "else in one vertex; necking splits the face, spiking drops the spike, bossing "
                               "joins the ring to the outer loop",
                               kintsugi::detail::repair_pinched_face};

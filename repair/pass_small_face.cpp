// Pass 9, small faces (paper 4.6): the face is replaced by one vertex where the faces
// around it meet (collapse_to_vertex, face_collapse.h).
#include "kernel/euler.h"
#include "repair/beautify_detail.h"
#include "repair/face_collapse.h"

#include <map>

namespace kintsugi::detail {

namespace {

std::string repair_small_face(RepairContext& c) {
  Body& b = c.b;
  FaceH f = c.problem.first<FaceH>();
  if (!b.alive(f)) return "no face named";
  if (!b.rings_of(f).empty()) return f.str() + " has inner loops";
  if (b.is_lone(b.outer_loop(f))) return f.str() + " has no edges";
  if (!(face_area(b, f, c.tol) < c.tol.length * c.tol.length)) return f.str() + " is no longer small";
  return collapse_to_vertex(b, f, c.tol, c.touched);
}

}  // namespace
}  // namespace kintsugi::detail

KINTSUGI_PASS(small_face) = {kintsugi::ProblemType::small_face, "small faces",
                             "the face is replaced by one vertex where the faces around it meet",
                             kintsugi::detail::repair_small_face};

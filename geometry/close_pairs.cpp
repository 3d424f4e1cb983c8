#include "geometry/close_pairs.h"

#include <CGAL/Bbox_3.h>
#include <CGAL/Box_intersection_d/Box_with_info_d.h>
#include <CGAL/box_intersection_d.h>

#include <algorithm>

namespace kintsugi::geo {

std::vector<std::pair<std::size_t, std::size_t>> close_pairs(const std::vector<Box>& boxes, double margin) {
  using CBox = CGAL::Box_intersection_d::Box_with_info_d<double, 3, std::size_t>;
  std::vector<CBox> in;
  in.reserve(boxes.size());
  const double h = margin / 2;  // each box grows by half the margin on every side
  for (std::size_t i = 0; i < boxes.size(); ++i) {
    const Box& b = boxes[i];
    if (b.empty()) continue;
    in.emplace_back(CGAL::Bbox_3(b.min.x() - h, b.min.y() - h, b.min.z() - h, b.max.x() + h, b.max.y() + h, b.max.z() + h), i);
  }
  std::vector<std::pair<std::size_t, std::size_t>> out;
  CGAL::box_self_intersection_d<CGAL::Parallel_if_available_tag>(
      in.begin(), in.end(),
      [&](const CBox& a, const CBox& b) { out.emplace_back(std::min(a.info(), b.info()), std::max(a.info(), b.info())); },
      std::ptrdiff_t(10), CGAL::Box_intersection_d::CLOSED);
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace kintsugi::geo

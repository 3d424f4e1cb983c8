#include "geometry/close_pairs.h"

#include <CGAL/Bbox_3.h>
#include <CGAL/Box_intersection_d/Box_with_info_d.h>
#include <CGAL/box_intersection_d.h>

#include <algorithm>

namespace kintsugi::geo {

namespace {

// The sweep's test for one pair: the boxes, each grown by h on every side, overlap
// (closed intervals); an empty box meets nothing.
bool meet(const Box& a, const Box& b, double h) {
  return !a.empty() && !b.empty() && ((b.min.array() - h) <= (a.max.array() + h)).all() &&
         ((b.max.array() + h) >= (a.min.array() - h)).all();
}

}  // namespace

std::vector<std::pair<std::size_t, std::size_t>> close_pairs(const std::vector<Box>& boxes, double margin) {
  const double h = margin / 2;  // each box grows by half the margin on every side
  // A face's few sides (most faces have four): every pair directly, without the sweep's
  // set-up.
  constexpr std::size_t kDirect = 16;
  if (boxes.size() <= kDirect) {
    std::vector<std::pair<std::size_t, std::size_t>> out;
    for (std::size_t i = 0; i < boxes.size(); ++i)
      for (std::size_t j = i + 1; j < boxes.size(); ++j)
        if (meet(boxes[i], boxes[j], h)) out.emplace_back(i, j);
    return out;
  }
  using CBox = CGAL::Box_intersection_d::Box_with_info_d<double, 3, std::size_t>;
  std::vector<CBox> in;
  in.reserve(boxes.size());
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

std::vector<std::pair<std::size_t, std::size_t>> close_pairs_grouped(const std::vector<Box>& boxes,
                                                                     const std::vector<std::size_t>& starts, double margin) {
  const double h = margin / 2;
  constexpr std::size_t kSmall = 16;
  std::vector<std::pair<std::size_t, std::size_t>> out;
  std::vector<Box> swept;                                    // one per range below
  std::vector<std::pair<std::size_t, std::size_t>> ranges;  // [first, last) of boxes
  for (std::size_t g = 0; g + 1 < starts.size(); ++g) {
    const std::size_t first = starts[g], last = starts[g + 1];
    if (last - first <= kSmall) {
      Box around;
      for (std::size_t i = first; i < last; ++i)
        if (!boxes[i].empty()) {
          around.add(boxes[i].min);
          around.add(boxes[i].max);
        }
      // Pairs within the group, directly.
      for (std::size_t i = first; i < last; ++i)
        for (std::size_t j = i + 1; j < last; ++j)
          if (meet(boxes[i], boxes[j], h)) out.emplace_back(i, j);
      swept.push_back(around);
      ranges.emplace_back(first, last);
    } else {
      for (std::size_t i = first; i < last; ++i) {
        swept.push_back(boxes[i]);
        ranges.emplace_back(i, i + 1);
      }
    }
  }
  // Ranges are disjoint and a range is never paired with itself: each pair of boxes comes
  // from one pair of ranges, once.
  for (auto [p, q] : close_pairs(swept, margin))
    for (std::size_t i = ranges[p].first; i < ranges[p].second; ++i)
      for (std::size_t j = ranges[q].first; j < ranges[q].second; ++j)
        if (meet(boxes[i], boxes[j], h)) out.emplace_back(std::min(i, j), std::max(i, j));
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace kintsugi::geo

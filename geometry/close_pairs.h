// Which of many boxes come within a distance of each other: the candidates for "closer
// than the tolerance" tests, so that those tests are not run on every pair (a plate with
// thousands of bosses has all their base loops in one face).
#pragma once

#include "geometry/box.h"

#include <cstddef>
#include <utility>
#include <vector>

namespace kintsugi::geo {

// Index pairs (i < j) of boxes whose gap is below `margin` along every axis. Every pair
// of points, one in each box, closer than `margin` is in such a pair (the converse need
// not hold). Empty boxes pair with nothing. CGAL's box_self_intersection_d: a sweep,
// O(n log² n + pairs).
std::vector<std::pair<std::size_t, std::size_t>> close_pairs(const std::vector<Box>& boxes, double margin);

}  // namespace kintsugi::geo

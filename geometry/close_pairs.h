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

// The same pairs as close_pairs(boxes, margin), for boxes that come in groups (the sides
// of a face, loop by loop: group g is [starts[g], starts[g + 1]), the last start being
// boxes.size()). A small group enters the sweep as one box around its members, a large
// one box by box, so a plate's many short rings cost a quarter of the sweep and their
// consecutive sides never reach it.
std::vector<std::pair<std::size_t, std::size_t>> close_pairs_grouped(const std::vector<Box>& boxes,
                                                                     const std::vector<std::size_t>& starts, double margin);

}  // namespace kintsugi::geo

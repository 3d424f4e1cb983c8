// close_pairs answers with every pair of boxes within the margin along every axis, and
// only those, whether it scans all pairs (a few boxes) or sweeps (many).
#include "geometry/close_pairs.h"

#include <gtest/gtest.h>
#include <rapidcheck.h>
#include <rapidcheck/gtest.h>

namespace kintsugi::geo {
namespace {

// The definition, pair by pair: the boxes grown by half the margin overlap (closed).
std::vector<std::pair<std::size_t, std::size_t>> by_definition(const std::vector<Box>& boxes, double margin) {
  std::vector<std::pair<std::size_t, std::size_t>> out;
  for (std::size_t i = 0; i < boxes.size(); ++i)
    for (std::size_t j = i + 1; j < boxes.size(); ++j) {
      if (boxes[i].empty() || boxes[j].empty()) continue;
      bool meet = true;
      for (int k = 0; k < 3; ++k)
        meet = meet && boxes[j].min[k] - margin / 2 <= boxes[i].max[k] + margin / 2 &&
               boxes[i].min[k] - margin / 2 <= boxes[j].max[k] + margin / 2;
      if (meet) out.emplace_back(i, j);
    }
  return out;
}

TEST(ClosePairs, BoxesAMarginApartMeetAndFartherOnesDoNot) {
  std::vector<Box> boxes(3);
  boxes[0].add(Vec3(0, 0, 0));
  boxes[0].add(Vec3(1, 1, 1));
  boxes[1].add(Vec3(1.5, 0, 0));  // 0.5 from box 0 along x
  boxes[1].add(Vec3(2, 1, 1));
  boxes[2].add(Vec3(3, 3, 3));  // far from both
  using P = std::vector<std::pair<std::size_t, std::size_t>>;
  EXPECT_EQ(close_pairs(boxes, 0.5), (P{{0, 1}}));
  EXPECT_EQ(close_pairs(boxes, 0.49), P{});
}

// Small sets take the direct scan, large ones CGAL's sweep: both must give the same
// pairs as the definition, in index order. Coordinates on a coarse grid make boxes
// touch exactly at the margin often.
RC_GTEST_PROP(ClosePairs, AreThePairsTheDefinitionNames, ()) {
  const int n = *rc::gen::element(0, 2, 5, 16, 17, 40, 120);
  const double margin = *rc::gen::element(0.0, 0.5, 1.0, 2.0);
  std::vector<Box> boxes(static_cast<std::size_t>(n));
  for (Box& b : boxes) {
    if (*rc::gen::inRange(0, 10) == 0) continue;  // empty: pairs with nothing
    for (int corner = 0; corner < 2; ++corner)
      b.add(Vec3(*rc::gen::inRange(0, 12), *rc::gen::inRange(0, 12), *rc::gen::inRange(0, 12)) * 0.5);
  }
  RC_ASSERT(close_pairs(boxes, margin) == by_definition(boxes, margin));
}

// Grouped or not, the same pairs: groups small (one box for the sweep) and large (box by
// box), empty ones, boxes in them empty too.
RC_GTEST_PROP(ClosePairs, GroupedAreTheSamePairs, ()) {
  const double margin = *rc::gen::element(0.0, 0.5, 1.0, 2.0);
  std::vector<Box> boxes;
  std::vector<std::size_t> starts{0};
  const int groups = *rc::gen::inRange(0, 12);
  for (int g = 0; g < groups; ++g) {
    const int n = *rc::gen::element(0, 1, 3, 16, 17, 30);
    for (int i = 0; i < n; ++i) {
      Box& b = boxes.emplace_back();
      if (*rc::gen::inRange(0, 10) == 0) continue;
      for (int corner = 0; corner < 2; ++corner)
        b.add(Vec3(*rc::gen::inRange(0, 12), *rc::gen::inRange(0, 12), *rc::gen::inRange(0, 12)) * 0.5);
    }
    starts.push_back(boxes.size());
  }
  RC_ASSERT(close_pairs_grouped(boxes, starts, margin) == by_definition(boxes, margin));
}

}  // namespace
}  // namespace kintsugi::geo

// How far two solids are apart, both ways: the largest distance from a point of one
// body's surface to the other body's surface, and back (a Hausdorff-like measure over the
// faces' tessellations). Tests use it for "the repaired model lies within tolerance of the
// clean (designer's) model".
#pragma once

#include "kernel/body.h"

#include <string>

namespace kintsugi::test {

struct TwoSided {
  double a_to_b = 0.0;  // max over points of a of the distance to b
  double b_to_a = 0.0;
  double max() const { return a_to_b > b_to_a ? a_to_b : b_to_a; }
  std::string problem;  // a face that could not be tessellated (then the distances are infinite)
};

// `chordal`: accuracy of the boundary sampling of the tessellations.
TwoSided two_sided_distance(const Body& a, const Body& b, double chordal);

}  // namespace kintsugi::test

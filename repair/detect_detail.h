// Internal to detection: per-face measures computed once and shared by the detectors.
#pragma once

#include "geometry/area.h"
#include "geometry/tolerance.h"
#include "kernel/body.h"
#include "repair/problem.h"

#include <vector>

namespace kintsugi::detail {

struct FaceInfo {
  bool measured = false;
  double area = 0.0;
  double bbox_diagonal = 0.0;
  bool small = false;   // area < tol²
  bool sliver = false;  // area / bbox diagonal < tol, and not small
};

struct DetectContext {
  const Body& b;
  geo::Tolerances tol;
  double chordal;                  // for sampling curved boundaries
  std::vector<FaceInfo> faces;     // by face slot
  std::vector<double> edge_length; // by edge slot
};

void detect_gaps(DetectContext& c, std::vector<Problem>& out);
void detect_pinched(DetectContext& c, std::vector<Problem>& out);
void detect_small_and_sliver(DetectContext& c, std::vector<Problem>& out);  // types 5, 6, 9
void detect_short_edges(DetectContext& c, std::vector<Problem>& out);       // types 7, 11
void detect_same_geometry(DetectContext& c, std::vector<Problem>& out);
void detect_mergeable(DetectContext& c, std::vector<Problem>& out);

}  // namespace kintsugi::detail

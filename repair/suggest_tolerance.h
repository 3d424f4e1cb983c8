// The tolerance a model suggests (paper 3.1 assumes one tolerance separates artefacts
// from intended features; section 8 leaves finding it open). Every size a tolerance
// decides on is collected: each edge's length and each face's width (or the square root
// of its area, when smaller), intended or not, and the sizes that are no single
// element's — pinch distances, surface deviations of neighbouring faces, the totals of
// chains — from a detection at a probe tolerance of 5% of the model's size. Gaps are not
// sizes: border cycles are found at any tolerance. The widest gap between consecutive
// sizes (as a ratio) below the probe is where spurious features end and intended ones
// begin; the suggestion is the geometric mean of the sizes either side of it, so that at
// it, detect reports exactly the features below the gap. Defects are a model's smallest
// features, so the intended ones have to be measured too: the gap is only seen between
// sizes on both of its sides.
#pragma once

#include "kernel/body.h"

#include <string>
#include <vector>

namespace kintsugi {

struct SizeEvidence {
  std::string what;  // e.g. "short_edge e7 (length)"
  double size;
};

struct ToleranceSuggestion {
  // "high" (a gap of a factor 10 or more between consecutive sizes, the highest such
  // below 5% of the model's size, and 3 times any other gap above it): a gap to use. "medium" (4, and 1.5 times the next) and "low" (2, and
  // 1.5 times the next): the best guess, reported but not used without the user's word
  // — designed parts have intended features a factor 5 apart (a table's 2-mm rails under
  // its 15-mm boards), which sizes alone cannot tell from defects. "none": no gap that
  // stands out. "no defects": no size below 5% of the model's; `tolerance` is below every
  // feature.
  std::string confidence = "none";
  double tolerance = 0.0;
  double below = 0.0;  // the largest spurious size (0 when none)
  double above = 0.0;  // the smallest intended size (the probe when none below it)
  double ratio = 0.0;  // above / below: how wide the gap is
  double next_ratio = 0.0;  // the second-widest gap, for comparison
  std::vector<SizeEvidence> spurious;    // the largest few below the gap
  std::vector<SizeEvidence> intentional; // the smallest few above it
  std::string explanation;               // one sentence

  bool usable() const { return confidence != "none"; }  // `tolerance` holds a suggestion
  // A suggestion detect and beautify may act on when the user gives no tolerance.
  bool trusted() const { return confidence == "high" || confidence == "no defects"; }
};

ToleranceSuggestion suggest_tolerance(const Body& b);

}  // namespace kintsugi

// The tolerance a model suggests (paper 3.1 assumes one tolerance separates artefacts
// from intended features; section 8 leaves finding it open). Every size that decides a
// problem — edge and chain lengths, the square root of small face areas, sliver widths,
// pinch distances, surface deviations of neighbouring faces, gap diameters — is
// collected by detecting at a generous probe tolerance (a few percent of the model's
// size), and the widest gap between consecutive sizes (as a ratio) is where spurious
// features end and intended ones begin. The suggestion is the geometric mean of the
// sizes either side of that gap, so that at it, detect reports exactly the features
// below the gap.
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
  // "high", "medium": a clear gap (use `tolerance`); "none": no clear gap, nothing to
  // use; "no defects": nothing looks spurious, `tolerance` is below every feature.
  std::string confidence = "none";
  double tolerance = 0.0;
  double below = 0.0;  // the largest spurious size (0 when none)
  double above = 0.0;  // the smallest intended size (the probe when none below it)
  double ratio = 0.0;  // above / below: how wide the gap is
  double next_ratio = 0.0;  // the second-widest gap, for comparison
  std::vector<SizeEvidence> spurious;    // the largest few below the gap
  std::vector<SizeEvidence> intentional; // the smallest few above it
  std::string explanation;               // one sentence

  bool usable() const { return confidence != "none"; }
};

ToleranceSuggestion suggest_tolerance(const Body& b);

}  // namespace kintsugi

// A detected topological problem: its type, where it is, how big it is.
#pragma once

#include "repair/problem_type.h"

#include <string>
#include <vector>

namespace kintsugi {

struct Problem {
  ProblemType type;
  // Printed handles ("f3", "e7", "v2", "l1"). Handles are the ids in the native file, so
  // these names survive a write → read.
  std::vector<std::string> elements;
  double measure = 0.0;       // in model units (area for faces, length otherwise)
  std::string measure_name;   // "length", "area", "width", "distance", "diameter"
  std::string subcase;        // e.g. "necking/straight" for pinched faces; empty if none
};

}  // namespace kintsugi

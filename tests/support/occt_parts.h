// Designer parts built with OpenCASCADE's own modelling operators (primitives, booleans,
// fillets, chamfers), as another modeller would build them: the clean models the
// scan-parts score (tests/occt/scan_parts_test.cpp) injects defects into. Sizes are
// 50-200 mm; every feature (fillet radius, hole, step) is at least 4 mm, so it stays a
// feature and not an artefact at the largest tolerance the score uses (2 mm).
#pragma once

#include <TopoDS_Shape.hxx>

#include <string>
#include <vector>

namespace kintsugi::test {

struct OcctPart {
  std::string name;
  TopoDS_Shape shape;
};

// The parts, in a fixed order. A part whose construction fails in this OpenCASCADE is left
// out (`dropped` gets its name and why).
std::vector<OcctPart> occt_parts(std::vector<std::string>* dropped);

}  // namespace kintsugi::test

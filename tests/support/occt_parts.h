// Designer parts built with OpenCASCADE's own modelling operators (primitives, booleans,
// fillets, chamfers, revolved sketches), as another modeller would build them: the clean
// models the scan-parts score (tests/occt/scan_parts_test.cpp) injects defects into.
// Sizes are 50-200 mm; features (fillet radii, chamfers, holes, steps) are 2 mm and up,
// most 4 mm or more. At a tolerance above a part's smallest feature the score skips the
// case (the designer's part itself would have problems there).
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

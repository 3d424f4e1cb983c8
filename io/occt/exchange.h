// STEP, IGES and OpenCASCADE BREP exchange, and OpenCASCADE's BRepCheck as an independent
// validity judge (spec/exchange.md: what maps to what, orientation, units, what is
// refused). Built only when OpenCASCADE is found (KINTSUGI_HAVE_OCCT).
//
// Nothing here throws: OpenCASCADE exceptions are caught and turned into messages that
// name the file and what is wrong.
#pragma once

#include "kernel/body.h"

#include <optional>
#include <string>
#include <vector>

namespace kintsugi::io {

enum class CadFormat { step, brep, iges };

struct CadImport {
  Body body;
  std::string units = "mm";  // the file's length unit; geometry stays in these units
  double unit_in_mm = 1.0;   // one file unit in millimetres
  std::vector<std::string> warnings;
};

// Reads a STEP (AP203/214/242 as OpenCASCADE reads them) or .brep file. Returns nullopt
// and sets *error (naming the file and what is wrong) for a missing, empty, truncated or
// corrupt file, a file without a shape, a non-manifold edge, or faces on surfaces we
// cannot represent (counted per surface type, with a locator for each face:
// "face #12 (STEP entity #345): B-spline surface not within precision of an analytic
// surface"). Solids and open shells are read; free edges become border cycles.
std::optional<CadImport> import_cad(const std::string& path, CadFormat f, std::string* error);

// Writes the body: a solid per closed shell, a shell per open one (a compound when
// there are several). Coordinates are written as they are, declared in `units` ("mm",
// "cm", "m", "in", "ft", "um", ...). Vertex, edge and face tolerances are `precision`
// (the model's modelling precision), at least OpenCASCADE's default 1e-7. Returns false
// and sets *error on failure.
bool export_cad(const Body& b, const std::string& path, CadFormat f, std::string* error,
                const std::string& units = "mm", double precision = 0);

struct OcctVerdict {
  bool valid;
  std::vector<std::string> problems;  // BRepCheck statuses, each with the sub-shape ("face f3: ...")
};
// Converts the body to a TopoDS_Shape exactly as export_cad does and runs
// BRepCheck_Analyzer on it, with the tolerances set to `precision` (the modelling
// precision our own check uses, so that both hold the model to one standard). A body
// that cannot be converted is not valid; the problems then say why.
OcctVerdict occt_check(const Body& b, double precision = 0);

// The validity gate's OpenCASCADE half (invariants/region_validity.h): registers a check
// that the region's faces convert (the model can still be written) and that
// BRepCheck_Analyzer finds nothing wrong with each of them — unless the face was already
// in `input` (the model before beautify; copied) and BRepCheck found it wrong there too,
// so that a repair is not blamed for what was there before. The input's verdicts are
// taken face by face, only for faces a repair touched and only when the repaired face
// fails: a whole-model BRepCheck (quadratic in the edges of a shell: 30 s at 10,000
// faces) is never needed, and a bad face far away does not turn the check off elsewhere.
// `precision` is the run's modelling precision (the shapes' tolerances, as occt_check).
void register_occt_region_check(const Body& input, double precision);

}  // namespace kintsugi::io

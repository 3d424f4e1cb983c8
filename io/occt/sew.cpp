// Sewing faces that a file gives unconnected (IGES trimmed surfaces) into shells.
#include "io/occt/convert.h"

#include <BRepBuilderAPI_Sewing.hxx>
#include <ShapeFix_Shell.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Shell.hxx>

namespace kintsugi::io::occt {

TopoDS_Shape sew_faces(const TopoDS_Shape& shape, double tolerance, std::vector<std::string>* warnings) {
  int faces = 0, shells = 0;
  for (TopExp_Explorer ex(shape, TopAbs_FACE); ex.More(); ex.Next()) ++faces;
  for (TopExp_Explorer ex(shape, TopAbs_SHELL); ex.More(); ex.Next()) ++shells;
  if (faces < 2 || shells > 0) return shape;  // already shells (or nothing to sew)
  BRepBuilderAPI_Sewing sew(tolerance);
  sew.Add(shape);
  sew.Perform();
  TopoDS_Shape out = sew.SewedShape();
  if (out.IsNull()) return shape;
  // Faces of one shell oriented consistently (a sewn shell may keep a face reversed).
  for (TopExp_Explorer ex(out, TopAbs_SHELL); ex.More(); ex.Next()) {
    ShapeFix_Shell fix(TopoDS::Shell(ex.Current()));
    fix.FixFaceOrientation(TopoDS::Shell(ex.Current()));
  }
  if (warnings)
    warnings->push_back(std::to_string(faces) + " unconnected faces sewn into shells (tolerance " + std::to_string(tolerance) +
                        "; " + std::to_string(sew.NbFreeEdges()) + " free edges left)");
  return out;
}

}  // namespace kintsugi::io::occt

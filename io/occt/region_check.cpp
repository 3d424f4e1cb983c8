// The validity gate's OpenCASCADE half (exchange.h, register_occt_region_check): each
// face of a repaired region converted and put to BRepCheck_Analyzer.
#include "io/occt/exchange.h"

#include "io/occt/convert.h"
#include "io/occt/messages.h"
#include "invariants/region_validity.h"

#include <BRepCheck_Analyzer.hxx>
#include <BRepCheck_ListOfStatus.hxx>
#include <BRepCheck_Result.hxx>
#include <Standard_Failure.hxx>
#include <TopExp.hxx>
#include <TopTools_IndexedMapOfShape.hxx>

#include <map>
#include <memory>
#include <set>
#include <string>
#include <unordered_map>
#include <vector>

namespace kintsugi::io {

namespace {

// BRepCheck's verdict on one face: valid, or the first status it found.
struct FaceVerdict {
  bool valid = true;
  std::string status;  // empty when BRepCheck gave none
};

FaceVerdict brepcheck_face(const TopoDS_Shape& face) {
  BRepCheck_Analyzer ana(face);
  if (ana.IsValid()) return {};
  TopTools_IndexedMapOfShape all;
  TopExp::MapShapes(face, all);
  all.Add(face);
  for (int i = 1; i <= all.Extent(); ++i) {
    Handle(BRepCheck_Result) res = ana.Result(all(i));
    if (res.IsNull()) continue;
    for (BRepCheck_ListIteratorOfListOfStatus it(res->Status()); it.More(); it.Next())
      if (it.Value() != BRepCheck_NoError) return {false, occt::status_name(it.Value())};
  }
  return {false, ""};
}

// The model before beautify and BRepCheck's verdict on each of its faces, taken when
// first asked for.
struct RegionCheckInput {
  std::shared_ptr<const Body> body;
  std::unordered_map<std::uint32_t, bool> face_valid;
  double precision = 0;
};
RegionCheckInput g_input;

// `near`: only the loops of f near that box (Region::near).
bool face_passes_brepcheck(const Body& b, FaceH f, const geo::Box* near = nullptr) {
  const std::set<FaceH> one{f};
  occt::LoopSubsets loops;
  if (near) loops[f] = loops_near(b, f, *near);
  std::string why;
  std::optional<occt::BuiltShape> s = occt::to_shape(b, &why, &one, &loops, g_input.precision);
  return s && BRepCheck_Analyzer(s->face[f.idx()]).IsValid() == Standard_True;
}

// Whether face f of the model before beautify failed BRepCheck: then the same face after a
// repair may fail too. A face checked near a change only (`near`) is compared with the
// same place of the face before, which is not remembered.
bool failed_before(FaceH f, const geo::Box* near) {
  const Body* in = g_input.body.get();
  if (!in || !in->alive(f)) return false;  // a new face: it must pass
  if (near) {
    try {
      return !face_passes_brepcheck(*in, f, near);
    } catch (const Standard_Failure&) {
      return true;
    }
  }
  auto it = g_input.face_valid.find(f.idx());
  if (it == g_input.face_valid.end()) {
    bool valid = true;
    try {
      valid = face_passes_brepcheck(*in, f);
    } catch (const Standard_Failure&) {
      valid = false;
    }
    it = g_input.face_valid.emplace(f.idx(), valid).first;
  }
  return !it->second;
}

std::string occt_region_check(const Body& b, const Region& r) {
  occt::silence_occt();
  try {
    std::string why;
    occt::LoopSubsets loops;
    for (const auto& [f, near] : r.near) loops[f] = near.loops;
    std::optional<occt::BuiltShape> s = occt::to_shape(b, &why, &r.faces, &loops, g_input.precision);
    if (!s) return "the model could not be written: " + why;
    for (FaceH f : r.faces) {
      auto near = r.near.find(f);
      const FaceVerdict v = brepcheck_face(s->face[f.idx()]);
      if (v.valid || failed_before(f, near == r.near.end() ? nullptr : &near->second.box)) continue;
      if (!v.status.empty()) return "OpenCASCADE's checker: " + f.str() + ": " + v.status;
      return "OpenCASCADE's checker: " + f.str() + " is not valid";
    }
  } catch (const Standard_Failure& e) {
    return std::string("OpenCASCADE failed while checking the region: ") + e.GetMessageString();
  }
  return "";
}

}  // namespace

void register_occt_region_check(const Body& input, double precision) {
  g_input.body = std::make_shared<const Body>(input);
  g_input.face_valid.clear();
  g_input.precision = precision;
  set_external_region_check(&occt_region_check);
}

}  // namespace kintsugi::io

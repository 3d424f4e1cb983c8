// Ring slivers: a scanned chamfer or fillet of a circular edge, a band far narrower than
// the tolerance round a cylinder's end or a boss's foot, made by OpenCASCADE's own
// chamfer and fillet operators. Found in session 23: the band measured π times its width
// (its box's diagonal is a diameter, not its length), so a fillet band was not a sliver
// at all, and the collapse refused the chamfer band ("meets itself along" its seam).
// Beautify must give back the designer's part: the cylinder meeting the cap or the plate
// in one circle, with the designer's counts, valid by our check and OpenCASCADE's.
#include "invariants/element_geometry.h"
#include "invariants/geometry_check.h"
#include "invariants/region_validity.h"
#include "invariants/topology_check.h"
#include "io/occt/convert.h"
#include "io/occt/exchange.h"
#include "repair/beautify.h"

#include <BRepAdaptor_Curve.hxx>
#include <BRepAlgoAPI_Fuse.hxx>
#include <BRepBuilderAPI_Transform.hxx>
#include <BRepFilletAPI_MakeChamfer.hxx>
#include <BRepFilletAPI_MakeFillet.hxx>
#include <BRepPrimAPI_MakeBox.hxx>
#include <BRepPrimAPI_MakeCylinder.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <gp_Trsf.hxx>

#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace kintsugi {
namespace {

// A cylinder of radius 10 and height 20 on the z axis, alone or as a boss on a plate
// (its foot at z = 0).
TopoDS_Shape designer(bool boss) {
  TopoDS_Shape s = BRepPrimAPI_MakeCylinder(10, 20).Shape();
  if (boss) s = BRepAlgoAPI_Fuse(BRepPrimAPI_MakeBox(gp_Pnt(-20, -20, -5), 40, 40, 5).Shape(), s).Shape();
  return s;
}

// The designer's part with the circle at height z blended `width` wide.
TopoDS_Shape blended(bool boss, double z, bool fillet, double width) {
  TopoDS_Shape s = designer(boss);
  TopoDS_Edge circle;
  for (TopExp_Explorer ex(s, TopAbs_EDGE); ex.More(); ex.Next()) {
    BRepAdaptor_Curve c(TopoDS::Edge(ex.Current()));
    if (c.GetType() == GeomAbs_Circle && std::abs(c.Value(c.FirstParameter()).Z() - z) < 1e-9)
      circle = TopoDS::Edge(ex.Current());
  }
  if (circle.IsNull()) return {};
  if (fillet) {
    BRepFilletAPI_MakeFillet f(s);
    f.Add(width, circle);
    return f.Shape();
  }
  BRepFilletAPI_MakeChamfer c(s);
  c.Add(width, circle);
  return c.Shape();
}

TopoDS_Shape moved(const TopoDS_Shape& s, bool move) {
  if (!move) return s;
  gp_Trsf r, t;
  r.SetRotation(gp_Ax1(gp_Pnt(0, 0, 0), gp_Dir(1, 2, 3)), 0.7);
  t.SetTranslation(gp_Vec(31, -17, 5));
  return BRepBuilderAPI_Transform(s, t * r, true).Shape();
}

Body body_of(const TopoDS_Shape& s) {
  std::vector<std::string> warnings;
  std::string error;
  std::optional<Body> b = io::occt::from_shape(
      s, [](const TopoDS_Shape&, int i) { return "face #" + std::to_string(i); }, &warnings, &error);
  if (!b) throw std::runtime_error(error);
  return std::move(*b);
}

TEST(RingSliver, AChamferOrFilletOfACircleFarBelowTheToleranceIsRemoved) {
  struct Case {
    bool boss;
    double z;  // the circle blended: the top (20) or, on the boss, its foot (0)
  };
  for (Case k : {Case{false, 20}, Case{true, 20}, Case{true, 0}})
    for (bool fillet : {false, true})
      for (bool move : {false, true}) {
        const std::string name = std::string(k.boss ? "boss" : "cylinder") + (k.z > 0 ? " top" : " foot") +
                                 (fillet ? " fillet" : " chamfer") + (move ? " moved" : "");
        SCOPED_TRACE(name);
        const TopoDS_Shape shape = blended(k.boss, k.z, fillet, 0.03);
        ASSERT_FALSE(shape.IsNull());
        Body b = body_of(moved(shape, move));
        const Body want = body_of(moved(designer(k.boss), move));
        const geo::Tolerances tol = geo::Tolerances::for_model(0.1, model_size(b));
        io::register_occt_region_check(b, tol.precision);
        BeautifyReport r = beautify(b, tol);
        set_external_region_check(nullptr);
        bool ring = false;
        std::string all;
        for (const RepairEntry& e : r.problems) {
          all += std::string(problem_name(e.problem.type)) + " " + outcome_name(e.outcome) + " " + e.reason + "\n";
          ring = ring || (e.problem.type == ProblemType::sliver_face && e.repaired());
        }
        EXPECT_TRUE(ring) << all;
        EXPECT_TRUE(r.left.empty()) << all;
        EXPECT_EQ(b.counts().faces, want.counts().faces) << all;
        EXPECT_EQ(b.counts().edges, want.counts().edges) << all;
        EXPECT_EQ(b.counts().vertices, want.counts().vertices) << all;
        EXPECT_TRUE(check_topology(b).empty());
        auto ours = region_violations(b, whole_body(b), tol, tol.precision);
        EXPECT_TRUE(ours.empty()) << ours.front().invariant << ": " << ours.front().detail;
        const io::OcctVerdict theirs = io::occt_check(b, tol.precision);
        EXPECT_TRUE(theirs.valid) << (theirs.problems.empty() ? "" : theirs.problems.front());
      }
}

}  // namespace
}  // namespace kintsugi

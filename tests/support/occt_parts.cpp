#include "tests/support/occt_parts.h"

#include <BRepAlgoAPI_Common.hxx>
#include <BRepAlgoAPI_Cut.hxx>
#include <BRepAlgoAPI_Fuse.hxx>
#include <BRepBuilderAPI_MakeEdge.hxx>
#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepBuilderAPI_MakeWire.hxx>
#include <BRepBuilderAPI_MakePolygon.hxx>
#include <BRepFilletAPI_MakeChamfer.hxx>
#include <BRepFilletAPI_MakeFillet.hxx>
#include <BRepPrimAPI_MakeBox.hxx>
#include <BRepPrimAPI_MakeCone.hxx>
#include <BRepPrimAPI_MakeCylinder.hxx>
#include <BRepPrimAPI_MakePrism.hxx>
#include <BRepPrimAPI_MakeRevol.hxx>
#include <BRepPrimAPI_MakeSphere.hxx>
#include <BRepPrimAPI_MakeTorus.hxx>
#include <BRepPrimAPI_MakeWedge.hxx>
#include <BRep_Tool.hxx>
#include <GC_MakeArcOfCircle.hxx>
#include <Geom_Circle.hxx>
#include <Geom_Curve.hxx>
#include <Precision.hxx>
#include <ShapeUpgrade_UnifySameDomain.hxx>
#include <Standard_Failure.hxx>
#include <TopExp.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopoDS.hxx>
#include <gp_Ax2.hxx>
#include <gp_Pnt.hxx>
#include <gp_Pnt2d.hxx>
#include <gp_Vec2d.hxx>

#include <cmath>
#include <functional>
#include <stdexcept>

namespace kintsugi::test {

namespace {

TopoDS_Shape box(double x, double y, double z, double dx, double dy, double dz) {
  return BRepPrimAPI_MakeBox(gp_Pnt(x, y, z), dx, dy, dz).Shape();
}
TopoDS_Shape zcyl(double x, double y, double z, double r, double h) {
  return BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(x, y, z), gp::DZ()), r, h).Shape();
}

// Booleans leave faces split along the tools' seams; a modeller's part has one face per
// surface patch, so same-domain faces and edges are unified (as a CAD system does).
TopoDS_Shape unify(const TopoDS_Shape& s) {
  ShapeUpgrade_UnifySameDomain u(s, true, true, false);
  u.Build();
  return u.Shape();
}
TopoDS_Shape fuse(const TopoDS_Shape& a, const TopoDS_Shape& b) {
  BRepAlgoAPI_Fuse op(a, b);
  if (!op.IsDone()) throw std::runtime_error("fuse failed");
  return unify(op.Shape());
}
TopoDS_Shape cut(const TopoDS_Shape& a, const TopoDS_Shape& b) {
  BRepAlgoAPI_Cut op(a, b);
  if (!op.IsDone()) throw std::runtime_error("cut failed");
  return unify(op.Shape());
}

// The straight edges of s parallel to `dir` whose midpoint satisfies `pick`.
template <class Pick>
std::vector<TopoDS_Edge> edges_where(const TopoDS_Shape& s, const gp_Dir& dir, Pick pick) {
  std::vector<TopoDS_Edge> out;
  TopTools_IndexedMapOfShape m;
  TopExp::MapShapes(s, TopAbs_EDGE, m);
  for (int i = 1; i <= m.Extent(); ++i) {
    TopoDS_Edge e = TopoDS::Edge(m(i));
    TopoDS_Vertex a, b;
    TopExp::Vertices(e, a, b);
    if (a.IsNull() || b.IsNull()) continue;
    gp_Pnt p = BRep_Tool::Pnt(a), q = BRep_Tool::Pnt(b);
    if (p.Distance(q) < 1e-6) continue;
    gp_Vec d(p, q);
    if (std::abs(std::abs(d.Normalized().Dot(gp_Vec(dir))) - 1) > 1e-9) continue;
    gp_Pnt mid((p.XYZ() + q.XYZ()) / 2);
    if (pick(mid)) out.push_back(e);
  }
  return out;
}

// The edges of s whose 3D curve (with its range) satisfies `pick`.
template <class Pick>
std::vector<TopoDS_Edge> curve_edges_where(const TopoDS_Shape& s, Pick pick) {
  std::vector<TopoDS_Edge> out;
  TopTools_IndexedMapOfShape m;
  TopExp::MapShapes(s, TopAbs_EDGE, m);
  for (int i = 1; i <= m.Extent(); ++i) {
    const TopoDS_Edge& e = TopoDS::Edge(m(i));
    double a, b;
    Handle(Geom_Curve) c = BRep_Tool::Curve(e, a, b);
    if (!c.IsNull() && pick(c, a, b)) out.push_back(e);
  }
  return out;
}

// A pick for curve_edges_where: circles at height z (of radius r, when r > 0).
auto circle_at(double z, double r = 0) {
  return [z, r](const Handle(Geom_Curve)& c, double a, double) {
    return c->IsKind(STANDARD_TYPE(Geom_Circle)) && std::abs(c->Value(a).Z() - z) < 1e-6 &&
           (r <= 0 || std::abs(Handle(Geom_Circle)::DownCast(c)->Radius() - r) < 1e-6);
  };
}

TopoDS_Shape fillet(const TopoDS_Shape& s, const std::vector<TopoDS_Edge>& edges, double r) {
  if (edges.empty()) throw std::runtime_error("no edges to fillet");
  BRepFilletAPI_MakeFillet f(s);
  for (const TopoDS_Edge& e : edges) f.Add(r, e);
  f.Build();
  if (!f.IsDone()) throw std::runtime_error("fillet failed");
  return f.Shape();
}

TopoDS_Shape chamfer(const TopoDS_Shape& s, const std::vector<TopoDS_Edge>& edges, double d) {
  if (edges.empty()) throw std::runtime_error("no edges to chamfer");
  BRepFilletAPI_MakeChamfer c(s);
  for (const TopoDS_Edge& e : edges) c.Add(d, e);
  c.Build();
  if (!c.IsDone()) throw std::runtime_error("chamfer failed");
  return c.Shape();
}

// An L-bracket (base 120 x 60 x 12, upright 12 x 60 x 70) with a through hole in the base
// and its four outer vertical base edges filleted.
TopoDS_Shape bracket() {
  TopoDS_Shape s = fuse(box(0, 0, 0, 120, 60, 12), box(0, 0, 0, 12, 60, 70));
  s = cut(s, zcyl(75, 30, -5, 9, 30));
  s = fillet(s, edges_where(s, gp::DZ(), [](const gp_Pnt& m) { return m.Z() < 12 && m.X() > 100; }), 8);
  return s;
}

// A flange: disc r 70, 14 thick, centre bore r 22, six bolt holes r 6 on a 50 circle.
TopoDS_Shape flange() {
  TopoDS_Shape s = cut(zcyl(0, 0, 0, 70, 14), zcyl(0, 0, -5, 22, 30));
  for (int i = 0; i < 6; ++i) {
    double a = i * M_PI / 3;
    s = cut(s, zcyl(50 * std::cos(a), 50 * std::sin(a), -5, 6, 30));
  }
  return s;
}

// A block 90 x 70 x 45 with its four top edges chamfered 6.
TopoDS_Shape chamfered_block() {
  TopoDS_Shape s = box(0, 0, 0, 90, 70, 45);
  std::vector<TopoDS_Edge> top = edges_where(s, gp::DX(), [](const gp_Pnt& m) { return m.Z() > 44; });
  for (const TopoDS_Edge& e : edges_where(s, gp::DY(), [](const gp_Pnt& m) { return m.Z() > 44; })) top.push_back(e);
  return chamfer(s, top, 6);
}

// A shaft r 16, 120 long, ending in a cone frustum (r 16 -> 6 over 25), with a collar.
TopoDS_Shape shaft() {
  TopoDS_Shape s = zcyl(0, 0, 0, 16, 120);
  s = fuse(s, BRepPrimAPI_MakeCone(gp_Ax2(gp_Pnt(0, 0, 120), gp::DZ()), 16, 6, 25).Shape());
  s = fuse(s, zcyl(0, 0, 30, 24, 15));
  return s;
}

// A block 110 x 110 x 50 with a spherical pocket (r 35, centre 10 above the top face).
TopoDS_Shape spherical_pocket() {
  return cut(box(0, 0, 0, 110, 110, 50), BRepPrimAPI_MakeSphere(gp_Pnt(55, 55, 60), 35).Shape());
}

// A ring r 45, 40 high, bore r 25, with a toroidal groove (R 45, r 6) round its middle.
TopoDS_Shape grooved_ring() {
  TopoDS_Shape s = cut(zcyl(0, 0, 0, 45, 40), zcyl(0, 0, -5, 25, 50));
  return cut(s, BRepPrimAPI_MakeTorus(gp_Ax2(gp_Pnt(0, 0, 20), gp::DZ()), 45, 6).Shape());
}

// A plate 150 x 100 x 20 with a rectangular pocket 70 x 40 x 10 and a step along one side.
TopoDS_Shape pocketed_plate() {
  TopoDS_Shape s = cut(box(0, 0, 0, 150, 100, 20), box(40, 30, 10, 70, 40, 20));
  return cut(s, box(-1, -1, 12, 152, 16, 20));
}

// A block 100 x 100 x 30 with a countersunk hole (cone r 18 -> 8 over 10, bore r 8).
TopoDS_Shape countersunk_block() {
  TopoDS_Shape s = cut(box(0, 0, 0, 100, 100, 30), zcyl(50, 50, -5, 8, 50));
  return cut(s, BRepPrimAPI_MakeCone(gp_Ax2(gp_Pnt(50, 50, 20), gp::DZ()), 8, 18, 10).Shape());
}

// A plus-shaped slab: two crossing bars 140 x 40 x 25 (planar faces only, concave corners).
TopoDS_Shape cross_slab() { return fuse(box(0, 50, 0, 140, 40, 25), box(50, 0, 0, 40, 140, 25)); }

// A block 80 x 80 x 40 with its four vertical edges filleted r 10.
TopoDS_Shape filleted_block() {
  TopoDS_Shape s = box(0, 0, 0, 80, 80, 40);
  return fillet(s, edges_where(s, gp::DZ(), [](const gp_Pnt&) { return true; }), 10);
}

// A post r 20, 80 high, with a hemispherical dome, standing on a base 90 x 90 x 15.
TopoDS_Shape domed_post() {
  TopoDS_Shape s = fuse(box(-45, -45, 0, 90, 90, 15), zcyl(0, 0, 15, 20, 80));
  return fuse(s, BRepPrimAPI_MakeSphere(gp_Pnt(0, 0, 95), 20).Shape());
}

// A block 100 x 100 x 40 under a pyramid roof 30 high (apex of four triangles, degree 4).
TopoDS_Shape roofed_block() {
  // The wedge's y axis is N x X: with N = -y and X = x it is +z; its z then runs along -y.
  gp_Ax2 frame(gp_Pnt(0, 100, 40), gp::DY().Reversed(), gp::DX());
  TopoDS_Shape roof = BRepPrimAPI_MakeWedge(frame, 100, 30, 100, 50, 50, 50, 50).Shape();
  return fuse(box(0, 0, 0, 100, 100, 40), roof);
}

// A tee: a pipe stub r 14 standing on a bar r 20, 120 long (their edge is where two
// cylinders of different radii meet: a B-spline curve), the bar's ends chamfered 3.
TopoDS_Shape tee() {
  TopoDS_Shape bar = BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(-60, 0, 0), gp::DX()), 20, 120).Shape();
  TopoDS_Shape s = fuse(bar, zcyl(0, 0, 0, 14, 45));
  return chamfer(s, curve_edges_where(s, [](const Handle(Geom_Curve)& c, double a, double b) {
                   return std::abs(std::abs(c->Value(0.5 * (a + b)).X()) - 60) < 1e-6;
                 }),
                 3);
}

// A post r 25, 50 high, on a plate 100 x 100 x 12, with its top edge filleted r 6 (a
// torus between the post's side and its top, tangent to both) and its foot filleted r 4.
TopoDS_Shape filleted_post() {
  TopoDS_Shape s = fuse(box(-50, -50, 0, 100, 100, 12), zcyl(0, 0, 12, 25, 50));
  s = fillet(s, curve_edges_where(s, circle_at(62)), 6);
  return fillet(s, curve_edges_where(s, circle_at(12)), 4);
}

// A block 80 x 60 x 40 with all twelve edges filleted r 6: cylinders tangent to the
// planes, a sphere at each corner tangent to three cylinders (every edge a tangent one).
TopoDS_Shape rounded_box() {
  TopoDS_Shape s = box(0, 0, 0, 80, 60, 40);
  std::vector<TopoDS_Edge> all;
  for (const gp_Dir& d : {gp::DX(), gp::DY(), gp::DZ()})
    for (const TopoDS_Edge& e : edges_where(s, d, [](const gp_Pnt&) { return true; })) all.push_back(e);
  return fillet(s, all, 6);
}

// A plate 140 x 80 x 15 with a through slot 60 long, r 10 ends: two planes and two half
// cylinders, tangent along four straight edges.
TopoDS_Shape slotted_plate() {
  TopoDS_Shape slot = fuse(box(40, 30, -5, 60, 20, 25), zcyl(40, 40, -5, 10, 25));
  slot = fuse(slot, zcyl(100, 40, -5, 10, 25));
  return cut(box(0, 0, 0, 140, 80, 15), slot);
}

// A stepped shaft: r 20 for 60, then r 12 for 50; the step's inner corner filleted r 3 (a
// torus, concave) and the far end chamfered 2 (a cone).
TopoDS_Shape stepped_shaft() {
  TopoDS_Shape s = fuse(zcyl(0, 0, 0, 20, 60), zcyl(0, 0, 60, 12, 50));
  s = fillet(s, curve_edges_where(s, circle_at(60, 12)), 3);
  return chamfer(s, curve_edges_where(s, circle_at(110, 12)), 2);
}

// A plate 100 x 100 x 20 with a through hole r 15, its top edge chamfered 3 (a cone) and
// its bottom edge filleted 2 (a torus).
TopoDS_Shape hole_plate() {
  TopoDS_Shape s = cut(box(0, 0, 0, 100, 100, 20), zcyl(50, 50, -5, 15, 30));
  s = chamfer(s, curve_edges_where(s, circle_at(20)), 3);
  return fillet(s, curve_edges_where(s, circle_at(0)), 2);
}

// A base 100 x 100 x 20 carrying a cone frustum (r 30 -> 15 over 40), its foot filleted
// r 5 (a torus between the top plane and the cone).
TopoDS_Shape cone_boss() {
  TopoDS_Shape s =
      fuse(box(-50, -50, 0, 100, 100, 20), BRepPrimAPI_MakeCone(gp_Ax2(gp_Pnt(0, 0, 20), gp::DZ()), 30, 15, 40).Shape());
  return fillet(s, curve_edges_where(s, circle_at(20)), 5);
}

// A rod r 8 bent through a right angle on a plate 80 x 60 x 10: a vertical cylinder 30
// high, a quarter torus (major radius 25) and a horizontal cylinder 40 long, tangent to
// each other along circles; the rod's foot filleted r 3 (a torus round the first one).
TopoDS_Shape bent_rod() {
  const double r = 8, bend = 25;
  TopoDS_Shape s = fuse(box(-30, -30, 0, 80, 60, 10), zcyl(0, 0, 10, r, 30));
  const gp_Ax2 torus_frame(gp_Pnt(bend, 0, 40), gp::DY(), gp::DX().Reversed());  // sweeps from -x up to +z
  s = fuse(s, BRepPrimAPI_MakeTorus(torus_frame, bend, r, M_PI / 2).Shape());
  s = fuse(s, BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(bend, 0, 40 + bend), gp::DX()), r, 40).Shape());
  return fillet(s, curve_edges_where(s, circle_at(10, r)), 3);
}

// A block 100 x 60 x 30 with a capsule-shaped pocket in its top: a horizontal cylinder
// r 12 (axis 4 below the top, 50 long) with a sphere at each end, cut out: concave sphere
// and cylinder faces tangent along circles, meeting the top plane in lines and arcs.
TopoDS_Shape capsule_block() {
  const double r = 12, z = 26;
  TopoDS_Shape capsule = BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(25, 30, z), gp::DX()), r, 50).Shape();
  // The spheres' poles on the capsule's axis, their seams rising to the top: with the
  // poles up, the boolean split each end in two along its seam, which unification left.
  capsule = fuse(capsule, BRepPrimAPI_MakeSphere(gp_Ax2(gp_Pnt(25, 30, z), gp::DX(), gp::DZ()), r).Shape());
  capsule = fuse(capsule, BRepPrimAPI_MakeSphere(gp_Ax2(gp_Pnt(75, 30, z), gp::DX(), gp::DZ()), r).Shape());
  return cut(box(0, 0, 0, 100, 60, 30), capsule);
}

// A hex nut 80 across the flats, 30 high, bore r 18, its top corners chamfered the way a
// nut's are: kept inside a cone (35 degrees to the top, r 40.5 at the top), which leaves a
// cone face at each of the six corners, bounded by hyperbolas on the flats.
TopoDS_Shape hex_nut() {
  const double across = 80, h = 30, top_r = 40.5, slope = std::tan(35 * M_PI / 180);
  const double R = across / std::sqrt(3.0);
  BRepBuilderAPI_MakePolygon hex;
  for (int i = 0; i < 6; ++i) hex.Add(gp_Pnt(R * std::cos(i * M_PI / 3), R * std::sin(i * M_PI / 3), 0));
  hex.Close();
  TopoDS_Shape prism = BRepPrimAPI_MakePrism(BRepBuilderAPI_MakeFace(hex.Wire()).Face(), gp_Vec(0, 0, h)).Shape();
  const double bottom_r = top_r + (h + 1) / slope;  // the cone reaches 1 below the nut
  TopoDS_Shape cone = BRepPrimAPI_MakeCone(gp_Ax2(gp_Pnt(0, 0, -1), gp::DZ()), bottom_r, top_r, h + 1).Shape();
  BRepAlgoAPI_Common common(prism, cone);
  if (!common.IsDone()) throw std::runtime_error("common failed");
  return cut(unify(common.Shape()), zcyl(0, 0, -5, 18, h + 10));
}

// A block 90 x 70 x 40 with its vertical edges filleted r 10, then its top loop (four
// lines and four arcs, tangent to each other) chamfered 4: planes and cones in turn round
// the top, meeting the fillets' cylinders.
TopoDS_Shape filleted_chamfered_block() {
  TopoDS_Shape s = box(0, 0, 0, 90, 70, 40);
  s = fillet(s, edges_where(s, gp::DZ(), [](const gp_Pnt&) { return true; }), 10);
  std::vector<TopoDS_Edge> top = curve_edges_where(s, [](const Handle(Geom_Curve)& c, double a, double b) {
    return std::abs(c->Value(a).Z() - 40) < 1e-6 && std::abs(c->Value(b).Z() - 40) < 1e-6;
  });
  return chamfer(s, top, 4);
}

// A block 100 x 80 x 60 with a vertical bore r 15 and a horizontal bore r 10 along x whose
// axes cross: two cylinders of different radii meeting inside in closed B-spline curves.
TopoDS_Shape cross_bore_block() {
  TopoDS_Shape s = cut(box(0, 0, 0, 100, 80, 60), zcyl(50, 40, -5, 15, 70));
  return cut(s, BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(-5, 40, 30), gp::DX()), 10, 110).Shape());
}


// Parts added in session 35, each with geometry the earlier ones lack: a surface off every
// axis, non-tangent meetings of curved surfaces, concave fillets round a pocket, planes
// meeting at angles other than 90 degrees.

// A block 100 x 80 x 50 whose top falls away 20 degrees towards -x over two thirds of its
// length (a ridge where the slope meets the flat), with a bore r 8 drilled square to the
// slope: a cylinder off every axis, meeting the slope in a circle and the bottom in an
// ellipse.
TopoDS_Shape inclined_bore_block() {
  const double a = 20 * M_PI / 180;
  const gp_Dir n(-std::sin(a), 0, std::cos(a));  // the slope's outward normal
  const gp_Dir along(std::cos(a), 0, std::sin(a));  // up the slope; n x along = +y
  const gp_Pnt on(50, 40, 40);                     // a point of the slope
  // A box standing on the slope (its z along n), wide enough to take the top off.
  const gp_Pnt corner = on.Translated(gp_Vec(along) * -100 + gp_Vec(0, -100, 0));
  TopoDS_Shape s = cut(box(0, 0, 0, 100, 80, 50), BRepPrimAPI_MakeBox(gp_Ax2(corner, n, along), 200, 200, 100).Shape());
  const gp_Pnt at(40, 40, 40 + std::tan(a) * (40 - 50));  // on the slope, 10 before `on`
  const gp_Pnt start = at.Translated(gp_Vec(n) * 20);
  return cut(s, BRepPrimAPI_MakeCylinder(gp_Ax2(start, n.Reversed()), 8, 150).Shape());
}

// A knob: a stem r 12 rising 40 from a plate 90 x 90 x 12, capped by a ball r 18 whose
// centre is 10 above the stem's top (ball and stem meet at an angle in a circle, not
// tangent); the stem's foot filleted r 4.
TopoDS_Shape knob() {
  TopoDS_Shape s = fuse(box(-45, -45, 0, 90, 90, 12), zcyl(0, 0, 12, 12, 40));
  s = fuse(s, BRepPrimAPI_MakeSphere(gp_Pnt(0, 0, 62), 18).Shape());
  return fillet(s, curve_edges_where(s, circle_at(12, 12)), 4);
}

// A plate 120 x 120 x 20 with a centre bore r 15 (its top edge chamfered 4) and an O-ring
// groove round it: a torus (R 38, r 5) whose centre circle lies in the top face, so the
// groove is half a torus meeting the top square to it.
TopoDS_Shape oring_plate() {
  TopoDS_Shape s = cut(box(-60, -60, 0, 120, 120, 20), zcyl(0, 0, -5, 15, 30));
  s = chamfer(s, curve_edges_where(s, circle_at(20, 15)), 4);
  return cut(s, BRepPrimAPI_MakeTorus(gp_Ax2(gp_Pnt(0, 0, 20), gp::DZ()), 38, 5).Shape());
}

// A hexagonal prism 60 across the flats, 50 high, its six vertical edges chamfered 5
// (planes meeting at 150 degrees), with a blind hole r 10, 20 deep, in its top.
TopoDS_Shape chamfered_hex_prism() {
  const double R = 60 / std::sqrt(3.0);
  BRepBuilderAPI_MakePolygon hex;
  for (int i = 0; i < 6; ++i) hex.Add(gp_Pnt(R * std::cos(i * M_PI / 3), R * std::sin(i * M_PI / 3), 0));
  hex.Close();
  TopoDS_Shape s = BRepPrimAPI_MakePrism(BRepBuilderAPI_MakeFace(hex.Wire()).Face(), gp_Vec(0, 0, 50)).Shape();
  s = chamfer(s, edges_where(s, gp::DZ(), [](const gp_Pnt&) { return true; }), 5);
  return cut(s, zcyl(0, 0, 30, 10, 30));
}

// A spindle revolved from a sketch, as a modeller draws a turned part: a cylinder r 10,
// a cone out to r 25, a cone back to r 12 and a cylinder r 12 (cone meets cylinder and
// cone at angles), the cones' ridge rounded r 6 in the sketch (an arc: a torus tangent to
// both; OpenCASCADE's fillet between two cones makes a B-spline surface instead).
TopoDS_Shape spindle() {
  const gp_Pnt2d a(10, 30), p(25, 50), c(12, 70);  // the ridge p between the cones
  const double r = 6;
  const gp_Vec2d u = gp_Vec2d(p, a).Normalized(), v = gp_Vec2d(p, c).Normalized();
  const double half = 0.5 * std::acos(u.Dot(v));   // half the angle at the ridge
  const gp_Pnt2d t1 = p.Translated(u * (r / std::tan(half))), t2 = p.Translated(v * (r / std::tan(half)));
  const gp_Vec2d in = (u + v).Normalized();
  const gp_Pnt2d centre = p.Translated(in * (r / std::sin(half)));
  const gp_Pnt2d mid = centre.Translated(in * -r);
  auto at = [](const gp_Pnt2d& q) { return gp_Pnt(q.X(), 0, q.Y()); };
  BRepBuilderAPI_MakeWire w;
  const std::vector<gp_Pnt2d> before = {{0, 0}, {10, 0}, a, t1}, after = {t2, c, {12, 100}, {0, 100}, {0, 0}};
  for (std::size_t i = 0; i + 1 < before.size(); ++i) w.Add(BRepBuilderAPI_MakeEdge(at(before[i]), at(before[i + 1])).Edge());
  w.Add(BRepBuilderAPI_MakeEdge(GC_MakeArcOfCircle(at(t1), at(mid), at(t2)).Value()).Edge());
  for (std::size_t i = 0; i + 1 < after.size(); ++i) w.Add(BRepBuilderAPI_MakeEdge(at(after[i]), at(after[i + 1])).Edge());
  if (!w.IsDone()) throw std::runtime_error("spindle sketch not closed");
  return BRepPrimAPI_MakeRevol(BRepBuilderAPI_MakeFace(w.Wire()).Face(), gp_Ax1(gp::Origin(), gp::DZ())).Shape();
}

// A plate 140 x 100 x 25 with a pocket 80 x 50, 15 deep, milled the way a cutter leaves
// it: its four vertical corners filleted r 10, then its floor's edges filleted r 4
// (concave cylinders along the sides and tori in the corners).
TopoDS_Shape filleted_pocket_plate() {
  TopoDS_Shape s = cut(box(0, 0, 0, 140, 100, 25), box(30, 25, 10, 80, 50, 30));
  s = fillet(s, edges_where(s, gp::DZ(), [](const gp_Pnt& m) {
               return m.X() > 1 && m.X() < 139 && m.Y() > 1 && m.Y() < 99;
             }),
             10);
  return fillet(s, curve_edges_where(s, [](const Handle(Geom_Curve)& c, double a, double b) {
                  return std::abs(c->Value(a).Z() - 10) < 1e-6 && std::abs(c->Value(b).Z() - 10) < 1e-6;
                }),
                4);
}

// A bracket bent the way sheet stock is not: a base 10 thick and an arm 10 thick leaning
// 30 degrees back from upright, one extruded profile 60 wide (planes at 120 and 60
// degrees), the inside of the bend filleted r 8 and a hole r 8 through the base.
TopoDS_Shape leaning_bracket() {
  const double s30 = 0.5, c30 = std::sqrt(3.0) / 2;
  const gp_Pnt2d d(15, 10), e(d.X() - 60 * s30, d.Y() + 60 * c30);  // the arm's inner face
  const gp_Pnt2d f(e.X() - 10 * c30, e.Y() - 10 * s30);             // its outer face's top
  const gp_Pnt2d g(f.X() + f.Y() / c30 * s30, 0);                   // ... down to the floor
  BRepBuilderAPI_MakePolygon profile;
  for (const gp_Pnt2d& q : {g, gp_Pnt2d(100, 0), gp_Pnt2d(100, 10), d, e, f}) profile.Add(gp_Pnt(q.X(), 0, q.Y()));
  profile.Close();
  TopoDS_Shape s = BRepPrimAPI_MakePrism(BRepBuilderAPI_MakeFace(profile.Wire()).Face(), gp_Vec(0, 60, 0)).Shape();
  s = fillet(s, edges_where(s, gp::DY(), [&](const gp_Pnt& m) {
               return std::abs(m.X() - d.X()) < 1e-6 && std::abs(m.Z() - d.Y()) < 1e-6;
             }),
             8);
  return cut(s, zcyl(65, 30, -5, 8, 30));
}

// A tapered pin: a cone r 12 -> 6 over 60 ending in a ball tangent to it (centre on the
// axis just above the cone's top, radius 6 / cos of the half angle), on a collar r 20,
// 10 high.
TopoDS_Shape tapered_pin() {
  const double tan_a = 6.0 / 60, cos_a = 1 / std::sqrt(1 + tan_a * tan_a);
  TopoDS_Shape s = fuse(zcyl(0, 0, 0, 20, 10), BRepPrimAPI_MakeCone(gp_Ax2(gp_Pnt(0, 0, 10), gp::DZ()), 12, 6, 60).Shape());
  return fuse(s, BRepPrimAPI_MakeSphere(gp_Pnt(0, 0, 70 + 6 * tan_a), 6 / cos_a).Shape());
}


// A handle: half a torus (R 30, tube r 6, its axis along y) standing on a plate
// 100 x 60 x 10; the plane through the axis cuts the tube in two circles at its feet.
TopoDS_Shape torus_handle() {
  // Swept half a turn about -y from +x: over the top, from x = 30 to x = -30; its end
  // discs lie in the plate's top.
  TopoDS_Shape arch = BRepPrimAPI_MakeTorus(gp_Ax2(gp_Pnt(0, 0, 10), gp::DY().Reversed(), gp::DX()), 30, 6, M_PI).Shape();
  return fuse(box(-50, -30, 0, 100, 60, 10), arch);
}

// A block 120 x 60 x 40 with a dovetail groove along x across its top: 20 deep, 30 wide
// at the top and 50 at the floor (sides at 63 degrees to the floor), its floor edges
// filleted r 4.
TopoDS_Shape dovetail_block() {
  BRepBuilderAPI_MakePolygon profile;
  for (const gp_Pnt& q : {gp_Pnt(-5, 15, 41), gp_Pnt(-5, 45, 41), gp_Pnt(-5, 55, 20), gp_Pnt(-5, 5, 20)}) profile.Add(q);
  profile.Close();
  TopoDS_Shape groove = BRepPrimAPI_MakePrism(BRepBuilderAPI_MakeFace(profile.Wire()).Face(), gp_Vec(130, 0, 0)).Shape();
  TopoDS_Shape s = cut(box(0, 0, 0, 120, 60, 40), groove);
  return fillet(s, edges_where(s, gp::DX(), [](const gp_Pnt& m) { return std::abs(m.Z() - 20) < 1e-6; }), 4);
}

// A block 100 x 80 x 40 with a pocket a ball-end cutter leaves: a bore r 12, 25 deep,
// ending in a hemisphere (concave, tangent to the bore along a circle), its rim
// chamfered 3.
TopoDS_Shape ball_end_pocket() {
  TopoDS_Shape s = cut(box(0, 0, 0, 100, 80, 40), zcyl(50, 40, 27, 12, 20));
  s = cut(s, BRepPrimAPI_MakeSphere(gp_Pnt(50, 40, 27), 12).Shape());
  return chamfer(s, curve_edges_where(s, circle_at(40, 12)), 3);
}

// A pipe (r 20 outside, 14 inside, 80 long) welded to a flange (r 45, 12 thick) with a
// fillet r 5 between the pipe and the flange's face (a torus), four bolt holes r 5.
TopoDS_Shape flanged_pipe() {
  TopoDS_Shape s = fuse(zcyl(0, 0, 0, 45, 12), zcyl(0, 0, 12, 20, 80));
  s = fillet(s, curve_edges_where(s, circle_at(12, 20)), 5);
  s = cut(s, zcyl(0, 0, -5, 14, 100));
  for (int i = 0; i < 4; ++i) s = cut(s, zcyl(33 * std::cos(i * M_PI / 2 + M_PI / 4), 33 * std::sin(i * M_PI / 2 + M_PI / 4), -5, 5, 30));
  return s;
}

// A shaft r 15, 120 long, with a keyway 6 wide and 4 deep along 50 of its top (planes
// meeting the cylinder in lines), its ends chamfered 2.
TopoDS_Shape keyed_shaft() {
  TopoDS_Shape s = BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(0, 0, 0), gp::DX()), 15, 120).Shape();
  s = chamfer(s, curve_edges_where(s, [](const Handle(Geom_Curve)& c, double a, double) {
                return c->IsKind(STANDARD_TYPE(Geom_Circle)) &&
                       (std::abs(c->Value(a).X()) < 1e-6 || std::abs(c->Value(a).X() - 120) < 1e-6);
              }),
              2);
  return cut(s, box(35, -3, 11, 50, 6, 10));
}

}  // namespace

std::vector<OcctPart> occt_parts(std::vector<std::string>* dropped) {
  const std::vector<std::pair<std::string, std::function<TopoDS_Shape()>>> makers = {
      {"bracket", bracket},
      {"flange", flange},
      {"chamfered_block", chamfered_block},
      {"shaft", shaft},
      {"spherical_pocket", spherical_pocket},
      {"grooved_ring", grooved_ring},
      {"pocketed_plate", pocketed_plate},
      {"countersunk_block", countersunk_block},
      {"cross_slab", cross_slab},
      {"filleted_block", filleted_block},
      {"domed_post", domed_post},
      {"roofed_block", roofed_block},
      {"tee", tee},
      {"filleted_post", filleted_post},
      {"rounded_box", rounded_box},
      {"slotted_plate", slotted_plate},
      {"stepped_shaft", stepped_shaft},
      {"hole_plate", hole_plate},
      {"cone_boss", cone_boss},
      {"bent_rod", bent_rod},
      {"capsule_block", capsule_block},
      {"hex_nut", hex_nut},
      {"filleted_chamfered_block", filleted_chamfered_block},
      {"cross_bore_block", cross_bore_block},
      {"inclined_bore_block", inclined_bore_block},
      {"knob", knob},
      {"oring_plate", oring_plate},
      {"chamfered_hex_prism", chamfered_hex_prism},
      {"spindle", spindle},
      {"filleted_pocket_plate", filleted_pocket_plate},
      {"leaning_bracket", leaning_bracket},
      {"tapered_pin", tapered_pin},
      {"torus_handle", torus_handle},
      {"dovetail_block", dovetail_block},
      {"ball_end_pocket", ball_end_pocket},
      {"flanged_pipe", flanged_pipe},
      {"keyed_shaft", keyed_shaft},
  };
  std::vector<OcctPart> out;
  for (const auto& [name, make] : makers) {
    try {
      out.push_back({name, make()});
    } catch (const Standard_Failure& e) {
      if (dropped) dropped->push_back(name + ": " + e.GetMessageString());
    } catch (const std::exception& e) {
      if (dropped) dropped->push_back(name + ": " + e.what());
    }
  }
  return out;
}

}  // namespace kintsugi::test

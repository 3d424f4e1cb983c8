// Body -> TopoDS_Shape (spec/exchange.md, "Export").
//
// Exact construction: one TopoDS_Vertex per vertex and one TopoDS_Edge per edge, shared
// by the wires of both faces, so the OpenCASCADE shape has exactly our topology. What we
// do not store — parameter-space curves, and the degenerated edges OpenCASCADE wants at
// sphere poles and cone apexes — is added per wire by ShapeFix_Wire with every fix that
// could change the topology switched off.
#include "io/occt/convert.h"
#include "io/occt/pcurve.h"

#include "geometry/curve.h"
#include "geometry/occt/freeform_occt.h"
#include "geometry/surface.h"
#include "geometry/types.h"

#include <BRepBuilderAPI_MakeEdge.hxx>
#include <BRepLib.hxx>
#include <BRep_Builder.hxx>
#include <BRep_Tool.hxx>
#include <ElCLib.hxx>
#include <ElSLib.hxx>
#include <GeomAdaptor_Surface.hxx>
#include <gp_Dir2d.hxx>
#include <Geom2d_Curve.hxx>
#include <Geom2d_Line.hxx>
#include <TopTools_MapOfShape.hxx>
#include <Geom_Surface.hxx>
#include <Geom_BSplineCurve.hxx>
#include <Geom_Circle.hxx>
#include <Geom_ConicalSurface.hxx>
#include <Geom_CylindricalSurface.hxx>
#include <Geom_Ellipse.hxx>
#include <Geom_Line.hxx>
#include <Geom_Plane.hxx>
#include <Geom_SphericalSurface.hxx>
#include <Geom_ToroidalSurface.hxx>
#include <Precision.hxx>
#include <ShapeFix_Wire.hxx>
#include <Standard_Failure.hxx>
#include <TColStd_Array1OfInteger.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <TColgp_Array1OfPnt.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Compound.hxx>
#include <TopoDS_Edge.hxx>
#include <TopoDS_Face.hxx>
#include <TopoDS_Iterator.hxx>
#include <TopoDS_Shell.hxx>
#include <TopoDS_Solid.hxx>
#include <TopoDS_Vertex.hxx>
#include <TopoDS_Wire.hxx>
#include <gp_Ax2.hxx>
#include <gp_Ax3.hxx>
#include <gp_Circ.hxx>
#include <gp_Elips.hxx>
#include <gp_Lin.hxx>
#include <gp_Pnt2d.hxx>
#include <gp_Vec2d.hxx>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <sstream>

namespace kintsugi::io::occt {

namespace {

using geo::Vec3;

constexpr double kTol = 1e-7;  // Precision::Confusion(), OpenCASCADE's default

gp_Pnt pnt(const Vec3& p) { return gp_Pnt(p.x(), p.y(), p.z()); }
gp_Dir dir(const Vec3& d) { return gp_Dir(d.x(), d.y(), d.z()); }
gp_Ax3 ax3(const geo::Frame& f) { return gp_Ax3(pnt(f.origin), dir(f.z), dir(f.x)); }
gp_Ax2 ax2(const geo::Frame& f) { return gp_Ax2(pnt(f.origin), dir(f.z), dir(f.x)); }

// Our surfaces map onto right-handed gp_Ax3 frames with the same parametrisation, so
// the OpenCASCADE surface normal is ours (spec/exchange.md). The one exception: a cone
// with a negative half-angle is written with the axis flipped (STEP and OpenCASCADE use
// a positive semi-angle); flipping z and y together keeps the frame right-handed and the
// normal outward, so the sense is unchanged.
Handle(Geom_Surface) to_geom(const geo::Surface& s) {
  struct V {
    Handle(Geom_Surface) operator()(const std::monostate&) const { return nullptr; }
    Handle(Geom_Surface) operator()(const geo::Plane& p) const { return new Geom_Plane(ax3(p.frame)); }
    Handle(Geom_Surface) operator()(const geo::Cylinder& c) const {
      return new Geom_CylindricalSurface(ax3(c.frame), c.radius);
    }
    Handle(Geom_Surface) operator()(const geo::Cone& c) const {
      if (c.half_angle >= 0) return new Geom_ConicalSurface(ax3(c.frame), c.half_angle, c.radius);
      gp_Ax3 a(pnt(c.frame.origin), dir(-c.frame.z), dir(c.frame.x));
      return new Geom_ConicalSurface(a, -c.half_angle, c.radius);
    }
    Handle(Geom_Surface) operator()(const geo::Sphere& s) const {
      return new Geom_SphericalSurface(ax3(s.frame), s.radius);
    }
    Handle(Geom_Surface) operator()(const geo::Torus& t) const {
      return new Geom_ToroidalSurface(ax3(t.frame), t.major_radius, t.minor_radius);
    }
    // Free-form: the surface rebuilt from its data (a copy: each face owns its surface).
    Handle(Geom_Surface) operator()(const geo::BSplineSurface&) const { return copy(); }
    Handle(Geom_Surface) operator()(const geo::RevolutionSurface&) const { return copy(); }
    Handle(Geom_Surface) operator()(const geo::ExtrusionSurface&) const { return copy(); }
    Handle(Geom_Surface) operator()(const geo::OffsetSurface&) const { return copy(); }
    Handle(Geom_Surface) copy() const { return Handle(Geom_Surface)::DownCast(geo::occt::geom_surface(all)->Copy()); }
    const geo::Surface& all;
  };
  return std::visit(V{s}, s);
}

// A 3D curve and the parameter range [t0, t1] of the edge from p0 to p1 along it.
struct EdgeCurve {
  Handle(Geom_Curve) curve;
  double t0 = 0, t1 = 0;
};

// Moves t1 into (t0, t0 + 2π] on a periodic curve; a full turn when the ends coincide.
void periodic_range(double t0, double* t1, bool closed) {
  const double two_pi = 2 * M_PI;
  if (closed) {
    *t1 = t0 + two_pi;
    return;
  }
  while (*t1 <= t0) *t1 += two_pi;
  while (*t1 > t0 + two_pi) *t1 -= two_pi;
}

std::optional<EdgeCurve> to_geom(const geo::Curve& c, const Vec3& p0, const Vec3& p1, bool closed, std::string* why) {
  EdgeCurve out;
  if (const auto* l = std::get_if<geo::Line>(&c)) {
    gp_Lin lin(pnt(l->origin), dir(l->direction));
    out.t0 = ElCLib::Parameter(lin, pnt(p0));
    out.t1 = ElCLib::Parameter(lin, pnt(p1));
    if (closed || std::abs(out.t1 - out.t0) < kTol) return *why = "a line edge whose ends coincide", std::nullopt;
    if (out.t1 < out.t0) {  // the line runs against the edge: write it the edge's way
      lin.Reverse();
      out.t0 = -out.t0;
      out.t1 = -out.t1;
    }
    out.curve = new Geom_Line(lin);
  } else if (const auto* ci = std::get_if<geo::Circle>(&c)) {
    gp_Circ circ(ax2(ci->frame), ci->radius);
    out.t0 = ElCLib::Parameter(circ, pnt(p0));
    out.t1 = ElCLib::Parameter(circ, pnt(p1));
    periodic_range(out.t0, &out.t1, closed);
    out.curve = new Geom_Circle(circ);
  } else if (const auto* e = std::get_if<geo::Ellipse>(&c)) {
    geo::Frame f = e->frame;
    double a = e->major_radius, b = e->minor_radius;
    if (a < b) {  // gp_Elips wants the major axis along x
      f.x = f.y();
      std::swap(a, b);
    }
    gp_Elips el(ax2(f), a, b);
    out.t0 = ElCLib::Parameter(el, pnt(p0));
    out.t1 = ElCLib::Parameter(el, pnt(p1));
    periodic_range(out.t0, &out.t1, closed);
    out.curve = new Geom_Ellipse(el);
  } else if (const auto* pl = std::get_if<geo::Polyline>(&c)) {
    std::vector<Vec3> pts = pl->points;
    if (pts.size() < 2) return *why = "a polyline with fewer than two points", std::nullopt;
    if ((pts.front() - p0).norm() > (pts.back() - p0).norm() && !closed) std::reverse(pts.begin(), pts.end());
    // Degree 1, knots at cumulative arc length: the polyline's own parametrisation.
    std::vector<Vec3> uniq{pts.front()};
    for (const Vec3& p : pts)
      if ((p - uniq.back()).norm() > kTol) uniq.push_back(p);
    if (uniq.size() < 2) return *why = "a polyline of coincident points", std::nullopt;
    int n = int(uniq.size());
    TColgp_Array1OfPnt poles(1, n);
    TColStd_Array1OfReal knots(1, n);
    TColStd_Array1OfInteger mults(1, n);
    double s = 0;
    for (int i = 0; i < n; ++i) {
      if (i > 0) s += (uniq[i] - uniq[i - 1]).norm();
      poles(i + 1) = pnt(uniq[i]);
      knots(i + 1) = s;
      mults(i + 1) = (i == 0 || i == n - 1) ? 2 : 1;
    }
    out.curve = new Geom_BSplineCurve(poles, knots, mults, 1);
    out.t0 = 0;
    out.t1 = s;
  } else if (std::holds_alternative<geo::BSplineCurve>(c)) {
    // The B-spline itself, between the vertices' parameters; written the edge's way.
    Handle(Geom_Curve) bs = Handle(Geom_Curve)::DownCast(geo::occt::geom_curve(c)->Copy());
    geo::ParameterRange r = geo::parameter_range(c, p0, p1, closed ? 1e-300 + (p0 - p1).norm() : 0.0);
    out.t0 = r.t0;
    out.t1 = r.t1;
    if (closed && !bs->IsPeriodic()) {
      out.t0 = bs->FirstParameter();
      out.t1 = bs->LastParameter();
    }
    if (!bs->IsPeriodic()) {
      // A vertex's projection can land a rounding error beyond the curve's ends, which
      // Geom_BSplineCurve refuses ("parameter out of range": hammer.brep of occt-misc).
      out.t0 = std::clamp(out.t0, bs->FirstParameter(), bs->LastParameter());
      out.t1 = std::clamp(out.t1, bs->FirstParameter(), bs->LastParameter());
    }
    if (out.t1 < out.t0) {
      out.t0 = bs->ReversedParameter(out.t0);
      out.t1 = bs->ReversedParameter(out.t1);
      bs = bs->Reversed();
    }
    if (!(out.t1 > out.t0)) return *why = "a B-spline edge whose ends coincide", std::nullopt;
    out.curve = bs;
  } else {
    return *why = "no curve", std::nullopt;
  }
  return out;
}

std::string status_of(BRepBuilderAPI_EdgeError e) {
  switch (e) {
    case BRepBuilderAPI_EdgeDone: return "done";
    case BRepBuilderAPI_PointProjectionFailed: return "a vertex does not project onto the curve";
    case BRepBuilderAPI_ParameterOutOfRange: return "parameter out of range";
    case BRepBuilderAPI_DifferentPointsOnClosedCurve: return "different points on a closed curve";
    case BRepBuilderAPI_PointWithInfiniteParameter: return "a vertex at an infinite parameter";
    case BRepBuilderAPI_DifferentsPointAndParameter: return "a vertex is not at its curve parameter";
    case BRepBuilderAPI_LineThroughIdenticPoints: return "a line through identical points";
  }
  return "unknown error";
}

class Builder {
 public:
  Builder(const Body& b, const std::set<FaceH>* only, const LoopSubsets* loops, double precision)
      : b_(b), only_(only), loops_(loops), tol_(std::max(kTol, precision)) {}

  std::optional<BuiltShape> run(std::string* error) {
    if (only_) return run_faces(error);
    out_.vertex.make_dense(b_.vertex_slots());
    out_.edge.make_dense(b_.edge_slots());
    out_.face.make_dense(b_.face_slots());
    out_.loop_wire.make_dense(b_.loop_slots());
    out_.shell.make_dense(b_.shell_slots());
    out_.solid.make_dense(b_.shell_slots());
    for (VertexH v : b_.vertices()) make_vertex(v);
    for (EdgeH e : b_.edges())
      if (!make_edge(e, error)) return std::nullopt;
    for (FaceH f : b_.faces())
      if (!make_face(f, error)) return std::nullopt;
    make_shells();
    return std::move(out_);
  }

 private:
  void make_vertex(VertexH v) {
    TopoDS_Vertex tv;
    bb_.MakeVertex(tv, pnt(b_.point(v)), tol_);
    out_.vertex[v.idx()] = tv;
  }

  bool make_edge(EdgeH e, std::string* error) {
    HalfedgeH h = halfedge_of(e, 0);
    VertexH v0 = b_.origin(h), v1 = b_.target(h);
    std::string why;
    std::optional<EdgeCurve> c = to_geom(b_.curve(e), b_.point(v0), b_.point(v1), v0 == v1, &why);
    if (!c) return *error = "edge " + e.str() + ": " + why, false;
    TopoDS_Vertex tv0 = TopoDS::Vertex(out_.vertex[v0.idx()]), tv1 = TopoDS::Vertex(out_.vertex[v1.idx()]);
    // The vertex tolerance covers the distance between the vertex and the curve's end,
    // so a body whose geometry is slightly off is still written with its topology.
    double d0 = c->curve->Value(c->t0).Distance(pnt(b_.point(v0)));
    double d1 = c->curve->Value(c->t1).Distance(pnt(b_.point(v1)));
    if (d0 > tol_) bb_.UpdateVertex(tv0, std::max(BRep_Tool::Tolerance(tv0), 1.001 * d0));
    if (d1 > tol_) bb_.UpdateVertex(tv1, std::max(BRep_Tool::Tolerance(tv1), 1.001 * d1));
    BRepBuilderAPI_MakeEdge me(c->curve, tv0, tv1, c->t0, c->t1);
    if (!me.IsDone()) return *error = "edge " + e.str() + ": OpenCASCADE refused it: " + status_of(me.Error()), false;
    TopoDS_Edge te = me.Edge();
    if (tol_ > kTol) bb_.UpdateEdge(te, tol_);
    // A polyline stands for a curve it is within `chordal_error` of: that is its tolerance.
    if (const auto* pl = std::get_if<geo::Polyline>(&b_.curve(e)); pl && pl->chordal_error > tol_) {
      bb_.UpdateEdge(te, pl->chordal_error);
      bb_.UpdateVertex(tv0, std::max(BRep_Tool::Tolerance(tv0), pl->chordal_error));
      bb_.UpdateVertex(tv1, std::max(BRep_Tool::Tolerance(tv1), pl->chordal_error));
    }
    out_.edge[e.idx()] = te;
    return true;
  }

  // A wire per loop, in the face's own (surface) sense: our loops run counter-clockwise
  // about the outward normal; when that is the reverse of the surface normal the wire
  // is written backwards and the face REVERSED, so exploring the face gives our order.
  TopoDS_Wire make_wire(LoopH l, bool same_sense) {
    std::vector<HalfedgeH> hs = b_.loop_halfedges(l);
    if (!same_sense) std::reverse(hs.begin(), hs.end());
    TopoDS_Wire w;
    bb_.MakeWire(w);
    for (HalfedgeH h : hs) {
      bool forward = (h.idx() & 1u) == 0;
      if (!same_sense) forward = !forward;
      const TopoDS_Shape& e = out_.edge[edge_of(h).idx()];
      bb_.Add(w, e.Oriented(forward ? TopAbs_FORWARD : TopAbs_REVERSED));
    }
    w.Closed(true);
    return w;
  }

  // A seam edge has two pcurves on its face, one per orientation, a period apart; the
  // face lies between them, so seen along the FORWARD pcurve the REVERSED one is on the
  // left (material on the left of a wire in the parameter plane). ShapeFix guesses the
  // pair's order; this puts it right.
  void orient_seams(const TopoDS_Wire& w, const TopoDS_Face& face) {
    for (TopoDS_Iterator it(w); it.More(); it.Next()) {
      TopoDS_Edge e = TopoDS::Edge(it.Value());
      if (it.Value().Orientation() != TopAbs_FORWARD || !BRep_Tool::IsClosed(e, face)) continue;
      double a, b;
      Handle(Geom2d_Curve) cf = BRep_Tool::CurveOnSurface(TopoDS::Edge(e.Oriented(TopAbs_FORWARD)), face, a, b);
      Handle(Geom2d_Curve) cr = BRep_Tool::CurveOnSurface(TopoDS::Edge(e.Oriented(TopAbs_REVERSED)), face, a, b);
      if (cf.IsNull() || cr.IsNull()) continue;
      gp_Pnt2d pf;
      gp_Vec2d d;
      cf->D1(0.5 * (a + b), pf, d);
      gp_Pnt2d pr = cr->Value(0.5 * (a + b));
      gp_Vec2d left(-d.Y(), d.X());
      if (gp_Vec2d(pf, pr).Dot(left) < 0) bb_.UpdateEdge(e, cr, cf, face, BRep_Tool::Tolerance(e));
    }
  }

  // A seam of a sphere, cylinder or cone is an isoparametric line (u constant, v moving
  // with the curve's parameter at unit speed): its two pcurves are made exact lines.
  // ShapeFix projects them as B-splines, whose rounding wobble at our 1e-7 tolerances made
  // BRepCheck find the wire crossing itself where the seam meets another edge at a vertex
  // (two fused spheres, fuzz_from_occt 2026-12-03; OpenCASCADE's own shape has lines).
  // A seam that is not such a line (within 1e-9 in the parameters) keeps its projection.
  void exact_seam_pcurves(const TopoDS_Wire& w, const TopoDS_Face& face) {
    GeomAdaptor_Surface ad(BRep_Tool::Surface(face));
    const GeomAbs_SurfaceType type = ad.GetType();
    if (type != GeomAbs_Sphere && type != GeomAbs_Cylinder && type != GeomAbs_Cone) return;
    auto uv = [&](const gp_Pnt& p, double* u, double* v) {
      if (type == GeomAbs_Sphere) ElSLib::Parameters(ad.Sphere(), p, *u, *v);
      else if (type == GeomAbs_Cylinder) ElSLib::Parameters(ad.Cylinder(), p, *u, *v);
      else ElSLib::Parameters(ad.Cone(), p, *u, *v);
    };
    const double period = 2 * M_PI, eps = 1e-9;
    for (TopoDS_Iterator it(w); it.More(); it.Next()) {
      const TopoDS_Edge e = TopoDS::Edge(it.Value());
      if (it.Value().Orientation() != TopAbs_FORWARD || !BRep_Tool::IsClosed(e, face) || BRep_Tool::Degenerated(e)) continue;
      double t0, t1;
      Handle(Geom_Curve) c = BRep_Tool::Curve(e, t0, t1);
      if (c.IsNull() || !(t1 > t0)) continue;
      // Inside the range: at a sphere's pole u is undefined.
      const double ta = t0 + 0.25 * (t1 - t0), tm = 0.5 * (t0 + t1), tb = t0 + 0.75 * (t1 - t0);
      double ua, va, um, vm, ub, vb;
      uv(c->Value(ta), &ua, &va);
      uv(c->Value(tm), &um, &vm);
      uv(c->Value(tb), &ub, &vb);
      auto same_u = [&](double x, double y) { return std::abs(std::remainder(x - y, period)) <= eps; };
      const double slope = (vb - va) / (tb - ta);
      if (!same_u(ua, um) || !same_u(ub, um) || std::abs(std::abs(slope) - 1) > eps ||
          std::abs(vm - (va + slope * (tm - ta))) > eps)
        continue;
      const double v0 = va - slope * (ta - t0);  // v at t0
      const TopoDS_Edge fwd = TopoDS::Edge(e.Oriented(TopAbs_FORWARD)), rev = TopoDS::Edge(e.Oriented(TopAbs_REVERSED));
      double a, b;
      Handle(Geom2d_Curve) cf = BRep_Tool::CurveOnSurface(fwd, face, a, b);
      Handle(Geom2d_Curve) cr = BRep_Tool::CurveOnSurface(rev, face, a, b);
      if (cf.IsNull() || cr.IsNull()) continue;
      // Each pcurve keeps the period orient_seams gave it.
      auto line_at = [&](const Handle(Geom2d_Curve)& old) -> Handle(Geom2d_Curve) {
        const double u = um + period * std::round((old->Value(tm).X() - um) / period);
        return new Geom2d_Line(gp_Pnt2d(u, v0 - slope * t0), gp_Dir2d(0, slope > 0 ? 1 : -1));
      };
      bb_.UpdateEdge(fwd, line_at(cf), line_at(cr), face, BRep_Tool::Tolerance(fwd));
      bb_.Range(fwd, face, t0, t1);
    }
  }

  // Puts the wire's pcurves in the periods where they join up in the parameter plane.
  // ShapeFix projects each edge on its own, so a pcurve can land a period away from its
  // neighbours, and ShapeFix_Wire::FixShifted moved the two pcurves of a seam split by a
  // hole across it (fuzz_from_occt) onto one line. Here: the wire is cut into runs at
  // its pole edges (degenerated, added by FixDegenerated, whose u-extent is free); within
  // a run each edge is moved by whole periods to start where the one before ends; a seam
  // edge moves with both its pcurves (orient_seams set them a period apart), so its
  // second use is already placed, and a run that reaches it in another period is moved
  // whole. Pole edges are then redrawn from the end before them to the start after them,
  // and the wire moved so that its middle is in the surface's parameter box.
  void chain_pcurves(const TopoDS_Wire& w, const TopoDS_Face& face) {
    Handle(Geom_Surface) s = BRep_Tool::Surface(face);
    const double up = s->IsUPeriodic() ? s->UPeriod() : 0, vp = s->IsVPeriodic() ? s->VPeriod() : 0;
    if (up == 0 && vp == 0) return;
    std::vector<TopoDS_Edge> uses;
    for (TopoDS_Iterator it(w); it.More(); it.Next()) {
      double a, b;
      if (BRep_Tool::CurveOnSurface(TopoDS::Edge(it.Value()), face, a, b).IsNull()) return;
      uses.push_back(TopoDS::Edge(it.Value()));
    }
    const std::size_t n = uses.size();
    auto ends = [&](const TopoDS_Edge& e, gp_Pnt2d* from, gp_Pnt2d* to) {
      double a, b;
      Handle(Geom2d_Curve) c = BRep_Tool::CurveOnSurface(e, face, a, b);
      bool fwd = e.Orientation() == TopAbs_FORWARD;
      *from = c->Value(fwd ? a : b);
      *to = c->Value(fwd ? b : a);
    };
    auto periods = [](double d, double period) { return period > 0 ? period * std::round(d / period) : 0.0; };
    // Moves the edge's pcurve(s) on the face, both of a seam's.
    auto shift = [&](const TopoDS_Edge& e, const gp_Vec2d& by) {
      if (by.Magnitude() == 0) return;
      const TopoDS_Edge fwd = TopoDS::Edge(e.Oriented(TopAbs_FORWARD)), rev = TopoDS::Edge(e.Oriented(TopAbs_REVERSED));
      double a, b;
      Handle(Geom2d_Curve) cf = Handle(Geom2d_Curve)::DownCast(BRep_Tool::CurveOnSurface(fwd, face, a, b)->Copy());
      cf->Translate(by);
      if (BRep_Tool::IsClosed(e, face)) {
        Handle(Geom2d_Curve) cr = Handle(Geom2d_Curve)::DownCast(BRep_Tool::CurveOnSurface(rev, face, a, b)->Copy());
        cr->Translate(by);
        bb_.UpdateEdge(fwd, cf, cr, face, BRep_Tool::Tolerance(fwd));
      } else {
        bb_.UpdateEdge(fwd, cf, face, BRep_Tool::Tolerance(fwd));
      }
      bb_.Range(fwd, face, a, b);  // a new pcurve has no range (a pole edge has no 3D curve to take it from)
    };
    // Runs start after a pole edge (or at the first edge when there is none).
    std::size_t start = 0;
    for (std::size_t i = 0; i < n; ++i)
      if (BRep_Tool::Degenerated(uses[i])) start = (i + 1) % n;
    TopTools_MapOfShape placed;
    std::vector<std::size_t> run;
    auto close_run = [&] {
      for (std::size_t k : run) placed.Add(uses[k]);
      run.clear();
    };
    gp_Pnt2d last;
    for (std::size_t j = 0; j < n; ++j) {
      const std::size_t i = (start + j) % n;
      const TopoDS_Edge& e = uses[i];
      if (BRep_Tool::Degenerated(e)) {
        close_run();
        continue;
      }
      gp_Pnt2d from, to;
      ends(e, &from, &to);
      if (run.empty()) {
        run.push_back(i);
        last = to;
        continue;
      }
      gp_Vec2d by(periods(last.X() - from.X(), up), periods(last.Y() - from.Y(), vp));
      bool in_run = false;
      for (std::size_t k : run) in_run = in_run || uses[k].IsSame(e);
      if (placed.Contains(e) || in_run) {
        // Already placed (a seam's second use): move the run so far instead, unless it
        // holds a seam placed before it.
        bool fixed = false;
        for (std::size_t k : run) fixed = fixed || (placed.Contains(uses[k]));
        if (!fixed && !in_run)
          for (std::size_t k : run) shift(uses[k], by.Reversed());
      } else {
        shift(e, by);
        to.Translate(by);
      }
      run.push_back(i);
      last = to;
    }
    close_run();
    // Pole edges: from the end before to the start after.
    for (std::size_t i = 0; i < n; ++i) {
      if (!BRep_Tool::Degenerated(uses[i])) continue;
      gp_Pnt2d before, after, unused;
      ends(uses[(i + n - 1) % n], &unused, &before);
      ends(uses[(i + 1) % n], &after, &unused);
      if (before.Distance(after) <= Precision::PConfusion()) continue;
      const bool fwd = uses[i].Orientation() == TopAbs_FORWARD;
      gp_Pnt2d p = fwd ? before : after, q = fwd ? after : before;
      Handle(Geom2d_Line) line = new Geom2d_Line(p, gp_Dir2d(gp_Vec2d(p, q)));
      const TopoDS_Edge e = TopoDS::Edge(uses[i].Oriented(TopAbs_FORWARD));
      bb_.UpdateEdge(e, line, face, BRep_Tool::Tolerance(e));
      bb_.Range(e, face, 0, p.Distance(q));
      bb_.Range(e, 0, p.Distance(q));
    }
    // The whole wire into the surface's parameter box.
    double umin = 1e300, umax = -1e300, vmin = 1e300, vmax = -1e300;
    for (const TopoDS_Edge& e : uses) {
      gp_Pnt2d from, to;
      ends(e, &from, &to);
      for (const gp_Pnt2d& p : {from, to}) {
        umin = std::min(umin, p.X()), umax = std::max(umax, p.X());
        vmin = std::min(vmin, p.Y()), vmax = std::max(vmax, p.Y());
      }
    }
    double u0, u1, v0, v1;
    s->Bounds(u0, u1, v0, v1);
    gp_Vec2d whole(up > 0 ? -periods(0.5 * (umin + umax) - (u0 + 0.5 * up), up) : 0,
                   vp > 0 ? -periods(0.5 * (vmin + vmax) - (v0 + 0.5 * vp), vp) : 0);
    TopTools_MapOfShape moved;
    for (const TopoDS_Edge& e : uses)
      if (moved.Add(e)) shift(e, whole);
  }

  // A whole sphere (one loop: its seam both ways) is written to STEP by OpenCASCADE as
  // a face bounded by a vertex only, and read back with the seam OpenCASCADE puts at
  // u = 0. So that the seam comes back where it is, the sphere is written with its x
  // axis turned (about its z axis; same points, same normals) towards the seam: the
  // direction, in the equator's plane, of the seam's midpoint.
  std::optional<Vec3> whole_sphere_seam(FaceH f, const geo::Sphere& sp) const {
    std::vector<LoopH> ls = b_.loops_of(f);
    if (ls.size() != 1 || b_.is_lone(ls[0])) return std::nullopt;
    std::vector<HalfedgeH> hs = b_.loop_halfedges(ls[0]);
    if (hs.size() != 2 || edge_of(hs[0]) != edge_of(hs[1])) return std::nullopt;
    EdgeH e = edge_of(hs[0]);
    HalfedgeH h = halfedge_of(e, 0);
    const geo::Curve& c = b_.curve(e);
    if (std::holds_alternative<std::monostate>(c)) return std::nullopt;
    geo::ParameterRange r = geo::parameter_range(c, b_.point(b_.origin(h)), b_.point(b_.target(h)), kTol);
    Vec3 d = geo::evaluate(c, 0.5 * (r.t0 + r.t1)) - sp.frame.origin;
    Vec3 z = sp.frame.z.normalized();
    d -= d.dot(z) * z;
    if (d.norm() <= 1e-9 * std::max(1.0, sp.radius)) return std::nullopt;
    return Vec3(d.normalized());
  }

  // pcurves of a free-form face's edges by our own projection (io/occt/pcurve.h), where
  // it can vouch for them; ShapeFix below does the rest. Seams (two pcurves a period
  // apart) are left to ShapeFix.
  void project_pcurves(const geo::Surface& s, FaceH f, const std::vector<std::pair<LoopH, TopoDS_Wire>>& wires,
                       const TopoDS_Face& face) {
    const Handle(Geom_Surface) gs = BRep_Tool::Surface(face);
    for (const auto& wire : wires)
      for (HalfedgeH h : b_.loop_halfedges(wire.first)) {
        const EdgeH edge = edge_of(h);
        if (b_.face(twin(h)) == f) continue;  // a seam
        const TopoDS_Edge e = TopoDS::Edge(out_.edge[edge.idx()]);
        if (BRep_Tool::Degenerated(e)) continue;
        double t0, t1;
        const Handle(Geom_Curve) c = BRep_Tool::Curve(e, t0, t1);
        if (c.IsNull() || !(t1 > t0)) continue;
        if (Handle(Geom2d_Curve) pc =
                projected_pcurve_remembered(s, b_.curve(edge), gs, c, t0, t1, 0.5 * BRep_Tool::Tolerance(e)))
          bb_.UpdateEdge(e, pc, face, BRep_Tool::Tolerance(e));
      }
  }

  bool make_face(FaceH f, std::string* error) {
    const geo::Surface& s = b_.surface(f);
    if (std::holds_alternative<std::monostate>(s)) return *error = "face " + f.str() + ": no surface", false;
    if (std::string p = geo::surface_problem(s); !p.empty()) return *error = "face " + f.str() + ": " + p, false;
    Handle(Geom_Surface) gs = to_geom(s);
    if (const auto* sp = std::get_if<geo::Sphere>(&s))
      if (std::optional<Vec3> x = whole_sphere_seam(f, *sp))
        gs = new Geom_SphericalSurface(gp_Ax3(pnt(sp->frame.origin), dir(sp->frame.z), dir(*x)), sp->radius);
    bool sense = b_.same_sense(f);
    TopoDS_Face tf;
    bb_.MakeFace(tf, gs, tol_);
    std::vector<std::pair<LoopH, TopoDS_Wire>> wires;
    for (LoopH l : loops_of(f)) {
      if (b_.is_lone(l)) {
        // A lone vertex: OpenCASCADE has no loop of a single vertex in a face; the
        // vertex is added to the face as an INTERNAL sub-shape.
        bb_.Add(tf, out_.vertex[b_.lone_vertex(l).idx()].Oriented(TopAbs_INTERNAL));
        continue;
      }
      wires.emplace_back(l, make_wire(l, sense));
    }
    if (geo::is_freeform(s)) project_pcurves(s, f, wires, tf);
    // pcurves (and pole edges) per wire, in the context of the face without any wire.
    for (auto& [l, w] : wires) {
      ShapeFix_Wire fix(w, tf, tol_);
      fix.ModifyTopologyMode() = Standard_False;
      fix.FixReorderMode() = 0;
      fix.FixSmallMode() = 0;
      fix.FixConnectedMode() = 0;
      fix.FixSelfIntersectionMode() = 0;
      fix.FixLackingMode() = 0;
      fix.FixGaps3dMode() = 0;
      fix.FixGaps2dMode() = 0;
      fix.FixNotchedEdgesMode() = 0;
      fix.FixTailMode() = 0;
      // Tolerances stay as built (the precision): SameParameter would widen an edge's tolerance
      // to cover a curve that misses its surface, and hide from BRepCheck exactly the
      // inconsistency occt_check is there to find.
      fix.FixSameParameterMode() = 0;
      fix.FixVertexToleranceMode() = 0;
      fix.FixShiftedMode() = 0;
      fix.FixEdgeCurves();
      orient_seams(w, tf);
      exact_seam_pcurves(w, tf);
      fix.FixDegenerated();
      w = fix.Wire();
      chain_pcurves(w, tf);
    }
    for (auto& [l, w] : wires) {
      bb_.Add(tf, w);
      out_.loop_wire[l.idx()] = w;
    }
    if (!sense) tf.Orientation(TopAbs_REVERSED);
    out_.face[f.idx()] = tf;
    return true;
  }

  void make_shells() {
    std::vector<std::vector<FaceH>> faces(b_.shell_slots());
    for (FaceH f : b_.faces()) faces[b_.shell(f).idx()].push_back(f);
    std::vector<std::uint8_t> open(b_.shell_slots(), 0);
    for (LoopH l : b_.border_cycles()) open[b_.shell(l).idx()] = 1;
    std::vector<TopoDS_Shape> tops;
    for (ShellH s : b_.shells()) {
      TopoDS_Shell ts;
      bb_.MakeShell(ts);
      for (FaceH f : faces[s.idx()]) bb_.Add(ts, out_.face[f.idx()]);
      ts.Closed(!open[s.idx()]);
      out_.shell[s.idx()] = ts;
      if (open[s.idx()]) {
        tops.push_back(ts);
        continue;
      }
      TopoDS_Solid so;
      bb_.MakeSolid(so);
      bb_.Add(so, ts);
      out_.solid[s.idx()] = so;
      tops.push_back(so);
    }
    if (tops.size() == 1) {
      out_.shape = tops.front();
    } else {
      TopoDS_Compound c;
      bb_.MakeCompound(c);
      for (const TopoDS_Shape& t : tops) bb_.Add(c, t);
      out_.shape = c;
    }
    BRepLib::UpdateTolerances(out_.shape, Standard_False);
  }

  // Only the faces in only_ (and their edges), as a compound: what a repair's region
  // check needs, at a cost that does not grow with the model.
  std::optional<BuiltShape> run_faces(std::string* error) {
    std::set<EdgeH> edges;
    std::set<VertexH> vertices;
    for (FaceH f : *only_)
      for (LoopH l : loops_of(f))
        if (b_.is_lone(l)) {
          vertices.insert(b_.lone_vertex(l));
        } else {
          for (HalfedgeH h : b_.loop_halfedges(l)) {
            edges.insert(edge_of(h));
            vertices.insert(b_.origin(h));
          }
        }
    for (VertexH v : vertices) make_vertex(v);
    for (EdgeH e : edges)
      if (!make_edge(e, error)) return std::nullopt;
    TopoDS_Compound c;
    bb_.MakeCompound(c);
    for (FaceH f : *only_) {
      if (!make_face(f, error)) return std::nullopt;
      bb_.Add(c, out_.face[f.idx()]);
    }
    out_.shape = c;
    return std::move(out_);
  }

  const Body& b_;
  // The loops of f to make: those of loops_ where f has an entry, else all.
  std::vector<LoopH> loops_of(FaceH f) const {
    if (loops_)
      if (auto it = loops_->find(f); it != loops_->end()) return it->second;
    return b_.loops_of(f);
  }

  const std::set<FaceH>* only_ = nullptr;
  const LoopSubsets* loops_ = nullptr;
  // Vertex, edge and face tolerances: the model's modelling precision, so that
  // BRepCheck holds the shape to the standard our own check does (never below
  // OpenCASCADE's default).
  double tol_ = kTol;
  BRep_Builder bb_;
  BuiltShape out_;
};

}  // namespace

std::optional<BuiltShape> to_shape(const Body& b, std::string* error, const std::set<FaceH>* only,
                                   const LoopSubsets* loops, double precision) {
  geo::occt::register_freeform_backend();  // as in from_shape
  std::string local;
  if (!error) error = &local;
  try {
    return Builder(b, only, loops, precision).run(error);
  } catch (const Standard_Failure& e) {
    *error = std::string("OpenCASCADE failed while building the shape: ") + e.GetMessageString();
  } catch (const std::exception& e) {
    *error = std::string("building the shape failed: ") + e.what();
  }
  return std::nullopt;
}

}  // namespace kintsugi::io::occt

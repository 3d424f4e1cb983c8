// The OpenCASCADE → Body conversion (io::occt::from_shape, io/occt/from_occt.cpp: what
// import_cad runs on every STEP and BREP shape) on shapes OpenCASCADE's own modelling
// operators build from the fuzz bytes: up to three primitives (box, cylinder, cone,
// sphere, torus) placed by rigid motions, combined by booleans (fuse, cut, common),
// optionally unified (ShapeUpgrade_UnifySameDomain) and then filleted or chamfered on a
// few edges. A shape OpenCASCADE fails to build is skipped.
//
// What must hold (spec/exchange.md), a violation aborts (the fuzzer reports it):
//  - from_shape returns a body or refuses with a non-empty reason; it never throws;
//  - the body passes check_topology;
//  - it has the shape's topology: one face per distinct TopoDS face (TopExp::MapShapes),
//    one edge per distinct non-degenerated edge of the faces' wires, one vertex per
//    vertex of those edges (and of wires made only of degenerated edges: lone-vertex
//    loops), one loop per FORWARD/REVERSED wire; so Σ 2(1 − genus) over its shells is
//    OpenCASCADE's V − E + F − R + B;
//  - one shell per set of faces connected across edges (our shells are connected; an
//    OpenCASCADE shell touching itself only at a vertex is two of ours), and no border
//    cycle when every shell of a valid shape is closed;
//  - round trip: to_shape of the body gives as many faces and non-degenerated edges,
//    and BRepCheck_Analyzer accepts it whenever it accepted the input.
//
// Input bytes (missing bytes read as 0):
//   [0]            number of solids: 1 + b % 3
//   per solid, 8:  kind (b % 5: box, cylinder, cone, sphere, torus), three size bytes,
//                  three translation bytes (half-millimetre steps in [-20, 20]), a
//                  rotation byte (axis b % 8: none, x, y, z, (1,1,0), (1,0,1), (1,1,1),
//                  (1,2,3); angle (b / 8) % 24 × 15°)
//   per boolean:   b % 3: fuse, cut, common (solid i combined into the result so far)
//   finish:        b % 4: 1 fillet, 2 chamfer, else nothing; bit 4 (16): unify first
//   if finishing:  edge count 1 + b % 3, then per edge an index byte, then a size byte
//                  (0.25 + (b % 16) × 0.25 mm)
// Sizes are whole millimetres (boxes 1–40, radii 1–20), so coincident faces and edges,
// which booleans split and unify, come often.
#include "fuzz/die.h"
#include "invariants/topology_check.h"
#include "io/occt/convert.h"
#include "io/occt/exchange.h"

#include <BRepAlgoAPI_BooleanOperation.hxx>
#include <BRepAlgoAPI_Common.hxx>
#include <BRepAlgoAPI_Cut.hxx>
#include <BRepAlgoAPI_Fuse.hxx>
#include <BRepBuilderAPI_Transform.hxx>
#include <BRepCheck_Analyzer.hxx>
#include <BRepFilletAPI_MakeChamfer.hxx>
#include <BRepFilletAPI_MakeFillet.hxx>
#include <BRepPrimAPI_MakeBox.hxx>
#include <BRepPrimAPI_MakeCone.hxx>
#include <BRepPrimAPI_MakeCylinder.hxx>
#include <BRepPrimAPI_MakeSphere.hxx>
#include <BRepPrimAPI_MakeTorus.hxx>
#include <BRepAdaptor_Curve.hxx>
#include <BRep_Tool.hxx>
#include <GeomAPI_ProjectPointOnCurve.hxx>
#include <Geom_Curve.hxx>
#include <Message.hxx>
#include <Message_Messenger.hxx>
#include <Message_Printer.hxx>
#include <ShapeAnalysis_Edge.hxx>
#include <ShapeUpgrade_UnifySameDomain.hxx>
#include <Standard_Failure.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_IndexedDataMapOfShapeListOfShape.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopTools_ListOfShape.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Iterator.hxx>
#include <gp_Ax2.hxx>
#include <gp_Trsf.hxx>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <numeric>
#include <optional>
#include <string>
#include <vector>

using namespace kintsugi;

using fuzz::die;

namespace {

class Bytes {
 public:
  Bytes(const std::uint8_t* d, std::size_t n) : d_(d), n_(n) {}
  unsigned next() { return i_ < n_ ? d_[i_++] : 0u; }

 private:
  const std::uint8_t* d_;
  std::size_t n_, i_ = 0;
};

// One primitive, placed (OpenCASCADE throws on parameters it refuses).
TopoDS_Shape primitive(Bytes& in) {
  const unsigned kind = in.next() % 5, a = in.next(), b = in.next(), c = in.next();
  const double tx = (int(in.next() % 81) - 40) / 2.0, ty = (int(in.next() % 81) - 40) / 2.0,
               tz = (int(in.next() % 81) - 40) / 2.0;
  const unsigned rot = in.next();
  TopoDS_Shape s;
  switch (kind) {
    case 0: s = BRepPrimAPI_MakeBox(1.0 + a % 40, 1.0 + b % 40, 1.0 + c % 40).Shape(); break;
    case 1: s = BRepPrimAPI_MakeCylinder(1.0 + a % 20, 1.0 + b % 40).Shape(); break;
    case 2: {
      double r1 = a % 20, r2 = b % 20;
      if (r1 == r2) r2 += 1;  // equal radii: a cylinder, which MakeCone refuses
      s = BRepPrimAPI_MakeCone(r1, r2, 1.0 + c % 40).Shape();
      break;
    }
    case 3: s = BRepPrimAPI_MakeSphere(1.0 + a % 20).Shape(); break;
    default: {
      double major = 2.0 + a % 20, minor = 1.0 + b % unsigned(major - 1);
      s = BRepPrimAPI_MakeTorus(major, minor).Shape();
      break;
    }
  }
  static const double kAxes[8][3] = {{0, 0, 1}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1},
                                     {1, 1, 0}, {1, 0, 1}, {1, 1, 1}, {1, 2, 3}};
  gp_Trsf t;
  if (rot % 8 != 0) {
    const double* ax = kAxes[rot % 8];
    t.SetRotation(gp_Ax1(gp::Origin(), gp_Dir(ax[0], ax[1], ax[2])), ((rot / 8) % 24) * M_PI / 12);
  }
  gp_Trsf move;
  move.SetTranslation(gp_Vec(tx, ty, tz));
  t = move * t;
  return BRepBuilderAPI_Transform(s, t, Standard_True).Shape();
}

// A boolean's result, or a null shape when it failed.
template <class Operation>
TopoDS_Shape run_boolean(const TopoDS_Shape& a, const TopoDS_Shape& b) {
  Operation o;
  TopTools_ListOfShape args, tools;
  args.Append(a);
  tools.Append(b);
  o.SetArguments(args);
  o.SetTools(tools);
  o.Build();
  return o.IsDone() && !o.HasErrors() ? o.Shape() : TopoDS_Shape();
}

TopoDS_Shape boolean(unsigned op, const TopoDS_Shape& a, const TopoDS_Shape& b) {
  if (op == 0) return run_boolean<BRepAlgoAPI_Fuse>(a, b);
  if (op == 1) return run_boolean<BRepAlgoAPI_Cut>(a, b);
  return run_boolean<BRepAlgoAPI_Common>(a, b);
}

// The shape the bytes describe, or a null shape when OpenCASCADE could not build it.
TopoDS_Shape build_shape(Bytes& in) {
  const unsigned n = 1 + in.next() % 3;
  std::vector<TopoDS_Shape> solids;
  for (unsigned i = 0; i < n; ++i) solids.push_back(primitive(in));
  TopoDS_Shape s = solids[0];
  for (unsigned i = 1; i < n && !s.IsNull(); ++i) s = boolean(in.next() % 3, s, solids[i]);
  if (s.IsNull()) return s;
  const unsigned finish = in.next();
  if (finish & 16) {
    ShapeUpgrade_UnifySameDomain u(s, Standard_True, Standard_True, Standard_False);
    u.Build();
    s = u.Shape();
  }
  if (finish % 4 != 1 && finish % 4 != 2) return s;
  TopTools_IndexedMapOfShape edges;
  TopExp::MapShapes(s, TopAbs_EDGE, edges);
  const unsigned count = 1 + in.next() % 3;
  std::vector<TopoDS_Edge> picked;
  for (unsigned i = 0; i < count; ++i) {
    unsigned k = in.next();
    if (edges.Extent() == 0) break;
    TopoDS_Edge e = TopoDS::Edge(edges(1 + int(k % unsigned(edges.Extent()))));
    if (!BRep_Tool::Degenerated(e)) picked.push_back(e);
  }
  const double size = 0.25 + (in.next() % 16) * 0.25;
  if (picked.empty()) return s;
  if (finish % 4 == 1) {
    BRepFilletAPI_MakeFillet f(s);
    for (const TopoDS_Edge& e : picked) f.Add(size, e);
    f.Build();
    return f.IsDone() ? f.Shape() : TopoDS_Shape();
  }
  BRepFilletAPI_MakeChamfer c(s);
  for (const TopoDS_Edge& e : picked) c.Add(size, e);
  c.Build();
  return c.IsDone() ? c.Shape() : TopoDS_Shape();
}

// The topology from_shape promises, counted on the OpenCASCADE side.
struct Expected {
  std::size_t vertices = 0, edges = 0, faces = 0, loops = 0, components = 0;
  long chi = 0;  // V − E + F − R (border cycles come on top)
};

Expected expected_of(const TopoDS_Shape& s) {
  Expected x;
  TopTools_IndexedMapOfShape faces, edges, vertices;
  TopExp::MapShapes(s, TopAbs_FACE, faces);
  x.faces = std::size_t(faces.Extent());
  std::size_t rings = 0;
  for (int i = 1; i <= faces.Extent(); ++i) {
    std::size_t wires = 0;
    for (TopoDS_Iterator w(faces(i)); w.More(); w.Next()) {
      if (w.Value().ShapeType() != TopAbs_WIRE) continue;
      TopAbs_Orientation o = w.Value().Orientation();
      if (o != TopAbs_FORWARD && o != TopAbs_REVERSED) continue;  // ignored on import
      bool any = false, only_degenerated = true;
      TopoDS_Shape lone;
      for (TopoDS_Iterator e(w.Value()); e.More(); e.Next()) {
        const TopoDS_Edge& edge = TopoDS::Edge(e.Value());
        any = true;
        if (BRep_Tool::Degenerated(edge)) {
          lone = TopExp::FirstVertex(edge);
          continue;
        }
        only_degenerated = false;
        edges.Add(edge);
        TopoDS_Vertex a, b;
        TopExp::Vertices(edge, a, b);
        vertices.Add(a);
        vertices.Add(b);
      }
      if (!any) continue;  // an empty wire is no loop
      if (only_degenerated) vertices.Add(lone);
      ++wires;
    }
    x.loops += wires;
    if (wires > 0) rings += wires - 1;
  }
  x.edges = std::size_t(edges.Extent());
  x.vertices = std::size_t(vertices.Extent());
  x.chi = long(x.vertices) - long(x.edges) + long(x.faces) - long(rings);
  // Faces connected across non-degenerated edges.
  std::vector<int> parent(x.faces);
  std::iota(parent.begin(), parent.end(), 0);
  auto find = [&](int f) {
    while (parent[f] != f) f = parent[f] = parent[parent[f]];
    return f;
  };
  TopTools_IndexedDataMapOfShapeListOfShape edge_faces;
  TopExp::MapShapesAndAncestors(s, TopAbs_EDGE, TopAbs_FACE, edge_faces);
  for (int i = 1; i <= edge_faces.Extent(); ++i) {
    if (!edges.Contains(edge_faces.FindKey(i))) continue;
    int first = -1;
    for (const TopoDS_Shape& f : edge_faces(i)) {
      int fi = faces.FindIndex(f) - 1;
      if (first < 0)
        first = fi;
      else
        parent[find(fi)] = find(first);
    }
  }
  for (std::size_t f = 0; f < x.faces; ++f) x.components += find(int(f)) == int(f);
  return x;
}

bool valid(const TopoDS_Shape& s) {
  try {
    return BRepCheck_Analyzer(s).IsValid() == Standard_True;
  } catch (const Standard_Failure&) {
    return false;  // OpenCASCADE's checker failing on its own shape: not ours to judge
  }
}

bool shells_closed(const TopoDS_Shape& s) {
  bool any = false;
  for (TopExp_Explorer ex(s, TopAbs_SHELL); ex.More(); ex.Next()) {
    any = true;
    if (!BRep_Tool::IsClosed(ex.Current())) return false;
  }
  for (TopExp_Explorer ex(s, TopAbs_FACE, TopAbs_SHELL); ex.More(); ex.Next()) return false;  // a loose face
  return any;
}

std::size_t non_degenerated_edges(const TopoDS_Shape& s) {
  TopTools_IndexedMapOfShape edges;
  TopExp::MapShapes(s, TopAbs_EDGE, edges);
  std::size_t n = 0;
  for (int i = 1; i <= edges.Extent(); ++i) n += !BRep_Tool::Degenerated(TopoDS::Edge(edges(i)));
  return n;
}

std::string counts_text(std::size_t v, std::size_t e, std::size_t f, std::size_t l, std::size_t s) {
  return "V " + std::to_string(v) + " E " + std::to_string(e) + " F " + std::to_string(f) + " loops " +
         std::to_string(l) + " shells " + std::to_string(s);
}

// Our bodies carry no tolerances: to_shape writes exact curves at 1e-7 and a polyline at
// its chordal error, so an input edge OpenCASCADE made with a wider tolerance (a
// boolean's section edge 0.009 off its faces) comes back as a curve off its faces by that
// much, which BRepCheck rightly reports (spec/exchange.md: export tolerances). The first
// edge whose tolerance is wider than written and whose curve is off its faces (measured,
// ShapeAnalysis_Edge) by more than that, or "" when the round trip must pass BRepCheck.
// (Vertex tolerances do not matter: to_shape widens a vertex's to reach its edges' curve
// ends.) from_shape copies vertex points, so the FORWARD input edge from a to b is a
// written edge from a's point to b's; among several, the one nearest the input edge's
// middle.
std::string number(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", x);
  return buf;
}

std::string looser_than_written(const TopoDS_Shape& in, const Body& b, const io::occt::BuiltShape& out) {
  auto same = [](const gp_Pnt& p, const geo::Vec3& q) { return p.Distance(gp_Pnt(q.x(), q.y(), q.z())) <= 1e-12; };
  TopTools_IndexedMapOfShape edges;
  TopExp::MapShapes(in, TopAbs_EDGE, edges);
  for (int i = 1; i <= edges.Extent(); ++i) {
    const TopoDS_Edge ie = TopoDS::Edge(edges(i).Oriented(TopAbs_FORWARD));
    if (BRep_Tool::Degenerated(ie)) continue;
    TopoDS_Vertex a, z;
    TopExp::Vertices(ie, a, z);
    if (a.IsNull() || z.IsNull()) continue;
    BRepAdaptor_Curve ic(ie);
    const gp_Pnt mid = ic.Value(0.5 * (ic.FirstParameter() + ic.LastParameter()));
    double best = std::numeric_limits<double>::infinity(), written = 0;
    for (EdgeH e : b.edges()) {
      const HalfedgeH h = halfedge_of(e, 0);
      if (!same(BRep_Tool::Pnt(a), b.point(b.origin(h))) || !same(BRep_Tool::Pnt(z), b.point(b.target(h)))) continue;
      const TopoDS_Edge& oe = TopoDS::Edge(out.edge[e.idx()]);
      double f = 0, l = 0;
      Handle(Geom_Curve) c = BRep_Tool::Curve(oe, f, l);
      if (c.IsNull()) continue;
      GeomAPI_ProjectPointOnCurve proj(mid, c, f, l);
      double d = proj.NbPoints() > 0 ? proj.LowerDistance() : std::min(mid.Distance(c->Value(f)), mid.Distance(c->Value(l)));
      if (d < best) best = d, written = BRep_Tool::Tolerance(oe);
    }
    if (!std::isfinite(best) || BRep_Tool::Tolerance(ie) <= 1.001 * written) continue;
    double deviation = 0;  // of the curve from its faces (pcurves), measured
    ShapeAnalysis_Edge().CheckSameParameter(ie, deviation, 23);
    if (deviation > written)
      return "edge #" + std::to_string(i) + ": tolerance " + number(BRep_Tool::Tolerance(ie)) + " and off its faces by " +
             number(deviation) + " in, tolerance " + number(written) + " written";
  }
  return "";
}

// KINTSUGI_FUZZ_VERBOSE=1: one line per input on what was built and what came of it
// (for replaying seeds and findings).
void say(const std::string& what) {
  static const bool verbose = std::getenv("KINTSUGI_FUZZ_VERBOSE") != nullptr;
  if (verbose) std::fprintf(stderr, "from_occt: %s\n", what.c_str());
}

void check(const TopoDS_Shape& shape) {
  const Expected x = expected_of(shape);
  const bool input_valid = valid(shape);
  say("shape " + counts_text(x.vertices, x.edges, x.faces, x.loops, x.components) +
      (input_valid ? ", valid" : ", BRepCheck finds it invalid"));
  std::vector<std::string> warnings;
  std::string error;
  std::optional<Body> body;
  try {
    body = io::occt::from_shape(
        shape, [](const TopoDS_Shape&, int i) { return "face #" + std::to_string(i); }, &warnings, &error);
  } catch (const Standard_Failure& e) {
    die(std::string("from_shape threw Standard_Failure: ") + e.GetMessageString());
  } catch (const std::exception& e) {
    die(std::string("from_shape threw: ") + e.what());
  }
  if (!body) {
    if (error.empty()) die("from_shape refused without a reason");
    say("refused: " + error.substr(0, error.find('\n')));
    return;
  }
  say("read, " + std::to_string(warnings.size()) + " warnings");
  for (const std::string& w : warnings) say("  " + w);
  if (auto bad = check_topology(*body); !bad.empty()) die("from_shape gave a body that breaks " + to_string(bad.front()));

  const Counts c = body->counts();
  if (c.faces != x.faces || c.edges != x.edges || c.vertices != x.vertices || c.loops != x.loops ||
      c.shells != x.components)
    die("from_shape changed the topology: the shape has " +
        counts_text(x.vertices, x.edges, x.faces, x.loops, x.components) + " (faces connected across edges), the body " +
        counts_text(c.vertices, c.edges, c.faces, c.loops, c.shells));
  long chi = 0;
  for (ShellH s : body->shells()) chi += 2 * (1 - long(body->shell_genus(s)));
  if (chi != x.chi + long(c.border_cycles))
    die("the body's genera give Euler characteristic " + std::to_string(chi) + ", the shape's counts " +
        std::to_string(x.chi) + " + " + std::to_string(c.border_cycles) + " border cycles");
  if (input_valid && shells_closed(shape) && c.border_cycles != 0)
    die("a valid closed shape read with " + std::to_string(c.border_cycles) + " border cycles");

  // Round trip.
  std::optional<io::occt::BuiltShape> back;
  std::string why;
  try {
    back = io::occt::to_shape(*body, &why);
  } catch (const Standard_Failure& e) {
    die(std::string("to_shape threw Standard_Failure: ") + e.GetMessageString());
  }
  if (!back) {
    if (input_valid) die("to_shape refused the body of a valid shape: " + why);
    return;
  }
  TopTools_IndexedMapOfShape back_faces;
  TopExp::MapShapes(back->shape, TopAbs_FACE, back_faces);
  if (std::size_t(back_faces.Extent()) != x.faces || non_degenerated_edges(back->shape) != x.edges)
    die("to_shape gave " + std::to_string(back_faces.Extent()) + " faces and " +
        std::to_string(non_degenerated_edges(back->shape)) + " edges, the shape read had " + std::to_string(x.faces) +
        " and " + std::to_string(x.edges));
  const std::string loose = looser_than_written(shape, *body, *back);
  if (!loose.empty()) say("round trip not judged by BRepCheck: " + loose);
  if (input_valid && loose.empty() && !valid(back->shape)) {
    io::OcctVerdict v = io::occt_check(*body);
    std::string list;
    for (std::size_t i = 0; i < v.problems.size() && i < 8; ++i) list += "\n  " + v.problems[i];
    die("BRepCheck accepts the shape but not its round trip (" + std::to_string(v.problems.size()) + " problems):" + list);
  }
  say("read and written back");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const bool silenced = [] {
    Message::DefaultMessenger()->RemovePrinters(STANDARD_TYPE(Message_Printer));
    return true;
  }();
  (void)silenced;
  if (size > 64) return 0;  // more bytes than any shape reads
  Bytes in(data, size);
  TopoDS_Shape shape;
  try {
    shape = build_shape(in);
  } catch (const Standard_Failure& e) {
    say(std::string("OpenCASCADE threw while building the shape: ") + e.GetMessageString());
    return 0;  // OpenCASCADE could not build it: not our business
  }
  if (shape.IsNull()) {
    say("OpenCASCADE could not build the shape");
    return 0;
  }
  check(shape);
  return 0;
}

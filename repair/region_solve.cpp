// One Ceres problem per repair (repair/region_solve.h). The residuals, in units chosen so
// one number compares them:
//   hard   vertex v on the surface of face g, for every face g around v:   d / precision
//   data   a sample of face f before the repair on f's new surface:        d / length, Huber loss
//   prior  vertex v near where the repair put it:                          1e-3 · |Δp| / length
// The hard terms outweigh the data terms by length/precision (10⁶ by default), so at the
// optimum a vertex is off its surfaces by ~10⁻¹² length: the constraints hold to the
// modelling precision whenever they can hold at all. The weak prior only fixes a vertex's
// freedom along a line when two faces meet there.
#include "repair/region_solve.h"

#include "geometry/bit_hash.h"
#include "geometry/same_geometry.h"
#include "geometry/solver_log.h"
#include "geometry/surface.h"
#include "geometry/surface_params.h"
#include "invariants/element_geometry.h"
#include "kernel/transaction.h"
#include "repair/beautify_detail.h"

#include <ceres/ceres.h>

#include <algorithm>
#include <chrono>
#include <functional>
#include <cmath>
#include <optional>
#include <type_traits>
#include <set>
#include <sstream>
#include <variant>

namespace kintsugi::detail {

namespace {

// A face whose loops have more corners than this stays fixed: moving it would pull every
// vertex on it into the problem, and the solve must stay local.
constexpr std::size_t kMaxSolvedFaceCorners = 64;

std::vector<VertexH> face_vertices(const Body& b, FaceH f) {
  std::vector<VertexH> out;
  for (LoopH l : b.loops_of(f))
    for (HalfedgeH h : b.loop_halfedges(l)) {
      VertexH v = b.origin(h);
      if (std::find(out.begin(), out.end(), v) == out.end()) out.push_back(v);
    }
  return out;
}

// Whether f has at most `limit` corners, counted without walking past the limit: a large
// face next to a repair (a plate with many holes) costs no more than a small one.
bool few_corners(const Body& b, FaceH f, std::size_t limit) {
  std::size_t n = 0;
  // The loops one by one (loops_of would list all of a plate's rings first).
  for (LoopH l = b.outer_loop(f); l.valid(); l = b.next_in_face(l)) {
    HalfedgeH start = b.first(l), h = start;
    if (!start.valid()) continue;
    if (n >= limit) return false;  // a loop has at least one corner
    do {
      if (++n > limit) return false;
      h = b.next(h);
    } while (h != start && h.valid());
  }
  return true;
}

void add_vertices(const Body& b, const Element& e, std::set<VertexH>& out) {
  if (auto* v = std::get_if<VertexH>(&e)) {
    out.insert(*v);
  } else if (auto* ed = std::get_if<EdgeH>(&e)) {
    out.insert(b.origin(halfedge_of(*ed, 0)));
    out.insert(b.target(halfedge_of(*ed, 0)));
  } else if (auto* l = std::get_if<LoopH>(&e)) {
    for (HalfedgeH h : b.loop_halfedges(*l)) out.insert(b.origin(h));
  } else if (auto* f = std::get_if<FaceH>(&e)) {
    for (VertexH v : face_vertices(b, *f)) out.insert(v);
  }
}

// Corners and edge midpoints of f's loops, on f's surface.
std::vector<geo::Vec3> samples_of(const Body& b, FaceH f, const geo::Tolerances& tol) {
  const geo::Surface& s = b.surface(f);
  std::vector<geo::Vec3> out;
  for (LoopH l : b.loops_of(f))
    for (HalfedgeH h : b.loop_halfedges(l)) {
      auto poly = halfedge_polyline(b, h, tol.probe_chordal());
      if (poly.empty()) continue;
      if (poly.size() == 2) {
        for (const geo::Vec3& q : {poly[0], geo::Vec3(0.5 * (poly[0] + poly[1]))})
          out.push_back(geo::closest_point(s, q).point);
      } else {
        // A curved side: up to eight points along it (a curved surface needs more than
        // its corners to be pinned down).
        const std::size_t n = poly.size() - 1, step = std::max<std::size_t>(1, n / 8);
        for (std::size_t i = 0; i < n; i += step) out.push_back(geo::closest_point(s, poly[i]).point);
      }
    }
  return out;
}

// The surfaces' unknowns and the residuals on them: geometry/surface_params.h.
using geo::on_solved_surface;
using geo::OnFixedSurface;
using geo::params_of;
using geo::surface_from;
using geo::SurfaceParams;
using Kind = geo::SurfaceKind;


// The signed offset of p from the half-plane of a periodic surface's seam (u = 0: through
// the axis and the frame's x).
double seam_offset(const geo::Surface& s, const geo::Vec3& p) {
  const geo::Frame& f = *seam_frame(s);
  return (p - f.origin).dot(f.z.cross(f.x).normalized());
}

// w·(offset of a variable point from a fixed seam's half-plane: through o, across m).
struct OnFixedSeam {
  geo::Vec3 o, m;
  const double* w;
  template <typename T>
  bool operator()(const T* x, T* r) const {
    r[0] = T(*w) * ((x[0] - o[0]) * m[0] + (x[1] - o[1]) * m[1] + (x[2] - o[2]) * m[2]);
    return true;
  }
};

ceres::Solver::Options solver_options() {
  ceres::Solver::Options options;
  options.linear_solver_type = ceres::SPARSE_NORMAL_CHOLESKY;
  options.max_num_iterations = 100;
  options.function_tolerance = 1e-14;
  options.gradient_tolerance = 1e-20;
  options.parameter_tolerance = 1e-15;
  options.logging_type = ceres::SILENT;
  return options;
}

double max_distance(const geo::Surface& s, const std::vector<geo::Vec3>& pts) {
  double m = 0.0;
  for (const auto& q : pts) m = std::max(m, std::abs(geo::signed_distance(s, q)));
  return m;
}

// Everything a solve reads, for the memo below: the solved faces (by handle, with their
// surfaces, ties and weights, and the samples from before the repair), the vertices (by
// handle, with their points), the constraints and the fixed surfaces they name, the
// tolerances.
struct SolveInput {
  double length = 0, precision = 0;
  std::vector<std::uint32_t> faces, vertices;
  std::vector<std::size_t> tie;
  std::vector<double> w_face;
  std::vector<geo::Surface> surfaces, fixed;
  std::vector<std::vector<geo::Vec3>> samples;
  std::vector<geo::Vec3> points;
  std::vector<std::pair<std::size_t, std::uint32_t>> constraints;
  std::uint64_t hash = 0;
  bool operator==(const SolveInput& o) const {
    return hash == o.hash && length == o.length && precision == o.precision && faces == o.faces &&
           vertices == o.vertices && tie == o.tie && w_face == o.w_face && constraints == o.constraints &&
           points == o.points && samples == o.samples && surfaces == o.surfaces && fixed == o.fixed;
  }
};

// What one solve of a region found: the solved geometry, and how it meets its constraints.
struct SolveOutcome {
  std::vector<geo::Surface> surfaces;  // of the solved faces
  std::vector<geo::Vec3> points;       // of the region's vertices
  std::vector<std::pair<double, std::size_t>> unmet;  // residual, constraint
  double max_residual = 0.0;
  std::vector<double> moved;  // of the solved faces
  bool too_far = false;
  std::vector<std::pair<double, std::size_t>> vertices_too_far;  // distance, vertex
  bool met() const { return unmet.empty() && vertices_too_far.empty() && !too_far; }
};

// Solves by their input, the last 1024 per thread (a few megabytes: each input holds its
// faces' samples). A solve is a function of its input, and the pipeline meets the same
// problem again unchanged: in each later round, and in each rerun after an unsolved
// repair was vetoed (beautify.cpp), where the whole run is replayed from the start. 32
// kept too few: MODERN_Sink_1.brep at --tol 0.59 ran 1877 of its 2049 solves (16 runs)
// in full, 1204 with 1024 kept (88 s to 72 s).
template <class Result>
struct SolveMemo {
  static constexpr std::size_t kKept = 1024;
  std::vector<std::pair<SolveInput, Result>> entries;  // oldest first
  const Result* find(const SolveInput& in) const {
    for (const auto& [key, result] : entries)
      if (key == in) return &result;
    return nullptr;
  }
  void add(SolveInput in, const Result& r) {
    if (entries.size() == kKept) entries.erase(entries.begin());
    entries.emplace_back(std::move(in), r);
  }
};
// Failures: each costs a full solve plus the search for the conflicting constraints; on
// CrankArm.brep (four merges that cannot be solved) that was about 30 of beautify's 38 s.
thread_local SolveMemo<RegionSolve> g_failed_solves;
// Successes: a repair whose solve succeeds can still be refused after it (the validity
// gate); on CrankArm.brep at tolerance 0.175 one pinch's solve of 114 unknowns ran 14
// times.
thread_local SolveMemo<SolveOutcome> g_succeeded_solves;

// Every solve uses sparse normal equations (Eigen's or SuiteSparse's Cholesky through
// Ceres). Each residual touches one surface and at most one vertex, so they stay sparse.
// A dense QR, kept once for problems under 120 unknowns as better conditioned under the
// hard weight, cost the residuals times the unknowns squared: three quarters of the Table
// 1 audit's repair time (a region of 30 vertices has ~100 unknowns), and on Top.brep a
// sliver's region of hundreds of vertices spent 14 of beautify's 15.5 s in it. The
// continuation below keeps the normal equations' conditioning in hand; outcomes were the
// same on the audit (one trial in 440 flipped a borderline cell), the scan parts and the
// sample parts (docs/benchmarks.md, "The region solve's linear solver").

using geo::fnv_mix;

RegionSolve solve_region_untimed(Body& b, Touched& touched, const OriginalFaces& original, const geo::Tolerances& tol,
                                 bool weigh_zipped_by_area, const std::set<FaceH>& held);

}  // namespace

std::set<FaceH> faces_near(const Body& b, const Problem& p) {
  std::set<VertexH> vs;
  for (const Element& e : p.elements) add_vertices(b, e, vs);
  std::set<FaceH> ring1, ring2;
  for (VertexH v : vs)
    for (FaceH f : faces_around(b, v)) ring1.insert(f);
  for (const Element& e : p.elements)
    if (auto* f = std::get_if<FaceH>(&e)) ring1.insert(*f);
  ring2 = ring1;
  for (FaceH f : ring1)
    if (few_corners(b, f, kMaxSolvedFaceCorners))
      for (VertexH v : face_vertices(b, f))
        for (FaceH g : faces_around(b, v)) ring2.insert(g);
  return ring2;
}

OriginalFaces snapshot_near(const Body& b, const Problem& p, const geo::Tolerances& tol) {
  OriginalFaces out;
  for (FaceH f : faces_near(b, p)) {
    if (std::holds_alternative<std::monostate>(b.surface(f)) || !few_corners(b, f, kMaxSolvedFaceCorners)) continue;
    try {
      OriginalFace o{b.surface(f), samples_of(b, f, tol), {}};
      for (LoopH l : b.loops_of(f))
        for (HalfedgeH h : b.loop_halfedges(l))
          if (FaceH g = b.face(twin(h)); g.valid() && g != f) o.neighbours.insert(g);
      out[f] = std::move(o);
    } catch (const std::exception&) {
      // A face whose boundary cannot be sampled gets no data terms; it then stays fixed.
    }
  }
  return out;
}

std::set<FaceH> region_faces(const Body& b, const Touched& touched) {
  std::set<FaceH> region;
  for (VertexH v : touched.vertices)
    if (b.alive(v))
      for (FaceH f : faces_around(b, v)) region.insert(f);
  for (EdgeH e : touched.edges)
    if (b.alive(e))
      for (unsigned s = 0; s < 2; ++s)
        if (FaceH f = b.face(halfedge_of(e, s)); f.valid()) region.insert(f);
  for (FaceH f : touched.faces)
    if (b.alive(f)) region.insert(f);
  return region;
}

RegionSolve solve_region(Body& b, Touched& touched, const OriginalFaces& original, const geo::Tolerances& tol,
                         bool weigh_zipped_by_area) {
  const auto start = std::chrono::steady_clock::now();
  // The edges that have an exact curve now (a line, a conic, a B-spline): the solve
  // re-derives the curves of every edge at a vertex it moves, and where a face it moved
  // meets a face it kept (a plate's top beside an O-ring groove's torus), a plane turned
  // by a hundredth of the tolerance cuts the torus in no circle: the edge becomes a
  // marched polyline, which lies on neither face to the precision and fails the gate.
  // Only the edges the solve can re-derive are looked at: those at the vertices it can
  // move (the touched ones and the corners of the faces it can solve), not every edge of
  // a large face in the region (a plate with thousands of holes: once per repair).
  std::set<EdgeH> exact;
  auto note_exact = [&](VertexH v) {
    for (HalfedgeH h : b.outgoing(v))
      if (const geo::Curve& c = b.curve(edge_of(h));
          !std::holds_alternative<geo::Polyline>(c) && !std::holds_alternative<std::monostate>(c))
        exact.insert(edge_of(h));
  };
  for (VertexH v : touched.vertices)
    if (b.alive(v)) note_exact(v);
  for (FaceH f : region_faces(b, touched))
    if (few_corners(b, f, kMaxSolvedFaceCorners))
      for (VertexH v : face_vertices(b, f)) note_exact(v);
  // The solved faces along edges that lost their exact curve, when the solve kept the
  // face across them.
  auto inexact = [&](const Touched& t, const RegionSolve& r) {
    std::set<FaceH> solved, out;
    for (const SurfaceMove& m : r.moved) solved.insert(m.face);
    for (EdgeH e : t.edges) {
      if (!b.alive(e) || !exact.count(e) || !std::holds_alternative<geo::Polyline>(b.curve(e))) continue;
      const FaceH f = b.face(halfedge_of(e, 0)), g = b.face(halfedge_of(e, 1));
      if (solved.count(f) && !solved.count(g)) out.insert(f);
      if (solved.count(g) && !solved.count(f)) out.insert(g);
    }
    return out;
  };
  RegionSolve out;
  {
    Transaction first(b);
    Touched t = touched;
    out = solve_region_untimed(b, t, original, tol, weigh_zipped_by_area, {});
    const std::set<FaceH> held = out.why.empty() ? inexact(t, out) : std::set<FaceH>{};
    if (held.empty()) {
      first.commit();
      touched = std::move(t);
    } else {
      // Solved again with those faces kept where they are; kept when that succeeds
      // without losing an exact curve, else the first solve stands (the gate judges it).
      first.rollback();
      Transaction second(b);
      Touched t2 = touched;
      RegionSolve again = solve_region_untimed(b, t2, original, tol, weigh_zipped_by_area, held);
      if (again.why.empty() && inexact(t2, again).empty()) {
        second.commit();
        touched = std::move(t2);
        out = std::move(again);
      } else {
        second.rollback();
        out = solve_region_untimed(b, touched, original, tol, weigh_zipped_by_area, {});  // remembered: no new solve
      }
    }
  }
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

namespace {

RegionSolve solve_region_untimed(Body& b, Touched& touched, const OriginalFaces& original, const geo::Tolerances& tol,
                                 bool weigh_zipped_by_area, const std::set<FaceH>& held) {
  RegionSolve out;
  const std::set<FaceH> region = region_faces(b, touched);
  std::set<VertexH> verts;
  for (VertexH v : touched.vertices)
    if (b.alive(v)) verts.insert(v);

  // Whether planar faces f and g, adjacent now, are one plane within the tolerance. For
  // faces already adjacent before the repair, pass 8's own test (surface_deviation); for
  // faces the repair made adjacent, that one plane fits both faces' samples within the
  // tolerance (pass 8's refit test: two fits of one scanned plane differ by up to twice
  // that). `zipped` is set when the repair made them adjacent.
  auto one_plane = [&](FaceH f, FaceH g, bool* zipped) {
    const OriginalFace &oi = original.at(f), &og = original.at(g);
    const bool was_apart = !oi.neighbours.count(g);
    if (zipped) *zipped = was_apart;
    if (!was_apart)
      return geo::surface_deviation(oi.surface, og.surface, oi.samples, og.samples, tol.length) <= tol.length;
    std::vector<geo::Vec3> both = oi.samples;
    both.insert(both.end(), og.samples.begin(), og.samples.end());
    geo::SurfaceFit fit = geo::fit_surface_like(oi.surface, both);
    bool one = fit.problem.empty() && fit.max_deviation <= tol.length;
    // Weighed by area (below), the tied plane is about the larger face's own: the
    // smaller face's samples must lie within the tolerance of that, not only of the
    // equal-weight fit (a boss side 30° off a pyramid's small side fitted both
    // within 0.02, then moved 0.023 in the solve; Beautify.InjectedDefects...,
    // rapidcheck seed 1).
    if (one && weigh_zipped_by_area) {
      double ai = 0, ag = 0;
      try {
        ai = face_area(b, f, tol), ag = face_area(b, g, tol);
      } catch (const std::exception&) {
      }
      const bool i_larger = ai >= ag;
      const OriginalFace& larger = i_larger ? oi : og;
      const OriginalFace& smaller = i_larger ? og : oi;
      one = max_distance(larger.surface, smaller.samples) <= tol.length;
    }
    return one;
  };
  auto has_data = [&](FaceH f) {
    auto it = original.find(f);
    return it != original.end() && !it->second.samples.empty();
  };
  // A plane beside a held one (below) that is one plane with it takes the held plane as
  // it is, and is held too: solved apart, it would tie to nothing and tilt to meet it.
  std::set<FaceH> adopted;
  for (FaceH h : held) {
    if (!b.alive(h) || !std::holds_alternative<geo::Plane>(b.surface(h)) || !has_data(h)) continue;
    const geo::Plane ph = std::get<geo::Plane>(b.surface(h));  // a copy: faces are set below
    for (LoopH l : b.loops_of(h))
      for (HalfedgeH e : b.loop_halfedges(l)) {
        const FaceH f = b.face(twin(e));
        if (!f.valid() || f == h || held.count(f) || adopted.count(f) || !region.count(f) || !has_data(f)) continue;
        if (!std::holds_alternative<geo::Plane>(b.surface(f)) || !one_plane(f, h, nullptr)) continue;
        // Its outward side kept: the held plane's normal may face the other way.
        const bool flip = std::get<geo::Plane>(b.surface(f)).frame.z.dot(ph.frame.z) < 0;
        b.set_surface(f, ph, flip ? !b.same_sense(f) : b.same_sense(f));
        touched.faces.insert(f);
        adopted.insert(f);
        for (VertexH v : face_vertices(b, f)) verts.insert(v);  // moved onto the plane it took
      }
  }

  // The solved faces: surfaces known from before the repair, not too large; not those
  // held where they are (solve_region's second try).
  std::vector<FaceH> faces;
  for (FaceH f : region) {
    auto it = original.find(f);
    if (it == original.end() || it->second.samples.empty() || held.count(f) || adopted.count(f)) continue;
    if (!params_of(b.surface(f))) continue;
    if (!few_corners(b, f, kMaxSolvedFaceCorners)) continue;
    auto corners = face_vertices(b, f);
    faces.push_back(f);
    verts.insert(corners.begin(), corners.end());
  }
  std::map<FaceH, std::size_t> face_index;
  for (std::size_t i = 0; i < faces.size(); ++i) face_index[faces[i]] = i;
  // Adjacent planar faces that are one plane within the tolerance (one_plane, above)
  // share one plane in the solve (issue 16: "faces the repair made one share one
  // surface"). A boss side a fraction of the tolerance inside the plate's side becomes
  // adjacent to it when its pinch is zipped: solved apart, the smaller face tilts to meet
  // the other along their new edge (3 degrees on a scan part), and pass 8 no longer sees
  // one face; solved together, they are coplanar and pass 8 merges them.
  std::vector<std::size_t> tie(faces.size());
  std::vector<std::size_t> zipped;  // faces tied to one they were not adjacent to before
  for (std::size_t i = 0; i < faces.size(); ++i) tie[i] = i;
  auto root = [&](std::size_t i) {
    while (tie[i] != i) i = tie[i] = tie[tie[i]];
    return i;
  };
  for (std::size_t i = 0; i < faces.size(); ++i) {
    if (!std::holds_alternative<geo::Plane>(b.surface(faces[i]))) continue;
    for (LoopH l : b.loops_of(faces[i]))
      for (HalfedgeH h : b.loop_halfedges(l)) {
        FaceH g = b.face(twin(h));
        auto it = face_index.find(g);
        if (it == face_index.end() || it->second == i || root(it->second) == root(i)) continue;
        if (!std::holds_alternative<geo::Plane>(b.surface(g))) continue;
        if (bool was_apart = false; one_plane(faces[i], g, &was_apart)) {
          if (was_apart) zipped.push_back(i);
          tie[root(it->second)] = root(i);
        }
      }
  }
  for (std::size_t i = 0; i < faces.size(); ++i) tie[i] = root(i);
  std::vector<VertexH> vlist(verts.begin(), verts.end());

  // Every (vertex, face around it) pair is a hard constraint; so is every vertex of a
  // seam on its seam (`on_seam`): a vertex with only a torus and a plane round it (a
  // fillet's end) is held on a circle of solutions, and slid along it while the seam's
  // other end slid elsewhere, the seam was no longer one iso-line (filleted_post, scan
  // parts 131000612: a vertex 5e-7 off its seam).
  // And two faces tangent along an edge stay tangent there (`tangent`, at two points of
  // the edge that are variables of the solve besides the vertices): a fillet's torus and
  // the plane it meets meet in a circle only while the plane is square to the torus's
  // axis at the tube's height, and a solve that tilted the plane by 2e-8 rad left their
  // edge 5.7e-7 off the torus (the same part, one repair later).
  enum class CKind { on_surface, on_seam, tangent };
  struct Constraint {
    std::size_t vertex;  // a vertex (< vlist.size()) or a point of a tangent edge
    FaceH face;
    CKind kind = CKind::on_surface;
    geo::Vec3 x_old = geo::Vec3::Zero();  // on_seam: the seam face's frame x before the solve
    FaceH other;                          // tangent: the second face
    double length = 0.0;                  // tangent: the edge's extent (angle to length)
  };
  auto constraint = [](std::size_t vertex, FaceH face, CKind kind = CKind::on_surface) {
    Constraint c;
    c.vertex = vertex, c.face = face, c.kind = kind;
    return c;
  };
  std::vector<geo::Vec3> start;  // the points' positions before the solve
  for (VertexH v : vlist) start.push_back(b.point(v));
  std::vector<Constraint> constraints;
  for (std::size_t i = 0; i < vlist.size(); ++i)
    for (FaceH g : faces_around(b, vlist[i]))
      if (!std::holds_alternative<std::monostate>(b.surface(g))) constraints.push_back(constraint(i, g));
  for (std::size_t i = 0; i < vlist.size(); ++i) {
    std::set<FaceH> seen;
    for (HalfedgeH h : b.outgoing(vlist[i])) {
      const FaceH g = b.face(h);
      if (!g.valid() || b.face(twin(h)) != g || seen.count(g)) continue;
      const geo::Frame* frame = seam_frame(b.surface(g));
      if (!frame) continue;
      // Only a vertex off the axis that is on the seam's side within the tolerance: a
      // seam the input put elsewhere than u = 0 keeps its curve (derive_edge_curve).
      const geo::Vec3 r = b.point(vlist[i]) - frame->origin;
      const geo::Vec3 across = r - r.dot(frame->z) * frame->z;
      if (!(across.norm() > tol.precision) || across.dot(frame->x) <= 0 ||
          !(std::abs(seam_offset(b.surface(g), b.point(vlist[i]))) <= tol.length))
        continue;
      seen.insert(g);
      constraints.push_back(constraint(i, g, CKind::on_seam));
      constraints.back().x_old = frame->x;
    }
  }
  {
    std::map<VertexH, std::size_t> vertex_index;
    for (std::size_t i = 0; i < vlist.size(); ++i) vertex_index[vlist[i]] = i;
    std::set<EdgeH> edges;
    for (FaceH f : region)
      for (LoopH l : b.loops_of(f))
        for (HalfedgeH h : b.loop_halfedges(l)) edges.insert(edge_of(h));
    for (VertexH v : vlist)
      for (HalfedgeH h : b.outgoing(v)) edges.insert(edge_of(h));
    for (EdgeH e : edges) {
      const HalfedgeH h = halfedge_of(e, 0);
      const FaceH f = b.face(h), g = b.face(twin(h));
      // Two fixed faces stay tangent by themselves, but a variable vertex on their edge
      // may still slide off their contact curve within the precision of both (a pocket's
      // rim vertex where a cylinder meets a sphere end, moved with the top plane by a
      // pinch's repair: 3e-7 off their circle at a precision of 1.2e-7, scan parts
      // capsule_block 1000102): its tangency is held.
      const bool faces_vary = face_index.count(f) || face_index.count(g);
      if (!f.valid() || !g.valid() || f == g ||
          (!faces_vary && !vertex_index.count(b.origin(h)) && !vertex_index.count(b.target(h))))
        continue;
      if (!params_of(b.surface(f)) || !params_of(b.surface(g))) continue;
      // Two planes along an edge are tangent only where they are one plane: the ties
      // above hold those together.
      if (std::holds_alternative<geo::Plane>(b.surface(f)) && std::holds_alternative<geo::Plane>(b.surface(g))) continue;
      std::vector<geo::Vec3> along = halfedge_polyline(b, h, tol.region_chordal());
      // A straight edge is its two ends: its inner points are taken on the chord. (Without
      // them a plane tangent to a cylinder along a ruling, a fillet's or a rounded end's
      // side, was never held tangent: the solve tilted the plane by 2e-4 rad, their ruling
      // became an ellipse of major radius 4e4, and the edge's vertices landed on its two arms:
      // scan-parts bracket 613002046.)
      if (along.size() == 2 && std::holds_alternative<geo::Line>(b.curve(e))) {
        const geo::Vec3 a = along[0], d = along[1] - along[0];
        along = {a, a + d / 3.0, a + 2.0 * d / 3.0, along[1]};
      }
      if (along.size() < 3) continue;
      double extent = 0;
      for (const geo::Vec3& q : along) extent = std::max(extent, (q - along.front()).norm());
      std::vector<geo::Vec3> at;
      for (std::size_t k : {along.size() / 3, (2 * along.size()) / 3})
        if (k > 0 && k + 1 < along.size()) at.push_back(along[k]);
      bool tangent = at.size() == 2;
      for (const geo::Vec3& q : at) {
        const geo::Vec3 nf = geo::closest_point(b.surface(f), q).normal, ng = geo::closest_point(b.surface(g), q).normal;
        tangent = tangent && nf.cross(ng).norm() * std::max(extent, tol.length) <= tol.precision;
      }
      if (!tangent) continue;
      // Its vertices too: near a tangent contact a point is within the precision of both
      // surfaces across a band sqrt(2·r·precision) wide (7e-4 beside a fillet of radius
      // 4), so a vertex on both may still lie off their contact curve.
      for (VertexH w : {b.origin(h), b.target(h)}) {
        auto at_w = vertex_index.find(w);
        if (at_w == vertex_index.end()) continue;
        constraints.push_back(constraint(at_w->second, f, CKind::tangent));
        constraints.back().other = g, constraints.back().length = std::max(extent, tol.length);
        if (b.origin(h) == b.target(h)) break;
      }
      if (!faces_vary) continue;
      for (const geo::Vec3& q : at) {
        const std::size_t i = start.size();
        start.push_back(q);
        constraints.push_back(constraint(i, f));
        constraints.push_back(constraint(i, g));
        constraints.push_back(constraint(i, f, CKind::tangent));
        constraints.back().other = g, constraints.back().length = std::max(extent, tol.length);
      }
    }
  }

  // A constraint's residual, a length: the surface of c.face is `s` (and of c.other `s2`).
  auto residual_of = [&](const Constraint& c, const geo::Surface& s, const geo::Surface* s2, const geo::Vec3& p) {
    switch (c.kind) {
      case CKind::on_seam: return std::abs(seam_offset(s, p));
      case CKind::tangent:
        return c.length * geo::closest_point(s, p).normal.cross(geo::closest_point(*s2, p).normal).norm();
      case CKind::on_surface: break;
    }
    return std::abs(geo::signed_distance(s, p));
  };
  auto residual_now = [&](const Constraint& c) {
    return residual_of(c, b.surface(c.face), c.other.valid() ? &b.surface(c.other) : nullptr, start[c.vertex]);
  };
  double before = 0.0;
  for (const auto& c : constraints) before = std::max(before, residual_now(c));
  out.variable_faces = int(faces.size());
  out.variable_vertices = int(vlist.size());
  out.residuals = int(constraints.size());
  // Tied faces not yet on one plane need the solve however well their vertices lie.
  for (std::size_t i = 0; i < faces.size(); ++i)
    if (tie[i] != i)
      before = std::max(before, max_distance(b.surface(faces[tie[i]]), original.at(faces[i]).samples) -
                                    max_distance(b.surface(faces[i]), original.at(faces[i]).samples));
  if (before <= tol.precision) {
    // Already consistent: nothing to solve; report how far the faces have moved.
    out.max_residual = before;
    for (FaceH f : faces) out.moved.push_back({f, max_distance(b.surface(f), original.at(f).samples)});
    return out;
  }

  // One solve, with constraint `skip` left out (none when skip >= constraints.size()).
  using Outcome = SolveOutcome;
  const double w_hard = 1.0 / tol.precision, w_data = 1.0 / tol.length, w_prior = 1e-3 / tol.length;
  // Faces the repair zipped together and tied to one plane weigh in by area, as the
  // scanned points they were fitted to would: every face has about the same number of
  // samples (corners and edge midpoints), so a boss side zipped against a long plate
  // side tilted the shared plane towards itself, and the plate's far corners moved
  // further than the tolerance (bracket, scan-parts score). Each face's residuals are
  // scaled by sqrt(its area / its group's largest), so its share of the cost is its share
  // of the area. Only groups with such a zipped pair: faces that were neighbours already
  // keep equal weights. Only for a pinch's repair (`weigh_zipped_by_area`): weighting the
  // faces pass 8's merge made adjacent let its refit make a sliver of a neighbour (Table
  // 1 audit, paper1, seed 7).
  std::vector<double> w_face(faces.size(), w_data);
  if (weigh_zipped_by_area) {
    std::set<std::size_t> zipped_groups;
    for (std::size_t i : zipped) zipped_groups.insert(tie[i]);
    std::map<std::size_t, std::vector<std::size_t>> groups;
    for (std::size_t i = 0; i < faces.size(); ++i) groups[tie[i]].push_back(i);
    for (const auto& [root_index, members] : groups) {
      if (members.size() < 2 || !zipped_groups.count(root_index)) continue;
      std::vector<double> area;
      double largest = 0;
      for (std::size_t i : members) {
        double a = 0;
        try {
          a = face_area(b, faces[i], tol);
        } catch (const std::exception&) {
        }
        area.push_back(std::isfinite(a) ? a : 0.0);
        largest = std::max(largest, area.back());
      }
      if (!(largest > 0)) continue;
      for (std::size_t k = 0; k < members.size(); ++k)
        w_face[members[k]] = w_data * std::sqrt(std::max(area[k] / largest, 1e-6));
    }
  }
  // Adds constraint c, at the point `x`, weighed by *hard (read at each evaluation);
  // `solved(face)` is the parameters a solved face is solved through, nullptr for a face
  // the solve keeps fixed. Shared by the full solve and the fixed faces' check.
  auto add_constraint = [&](ceres::Problem& problem, const Constraint& c, double* x, const double* hard,
                            const std::function<SurfaceParams*(FaceH)>& solved) {
    std::vector<double*> blocks;
    SurfaceParams* sf = solved(c.face);
    if (c.kind == CKind::tangent) {
      ceres::CostFunction* f = geo::on_tangent_surfaces(sf, *params_of(b.surface(c.face)), solved(c.other),
                                                        *params_of(b.surface(c.other)), c.length, hard, blocks);
      blocks.push_back(x);
      problem.AddResidualBlock(f, nullptr, blocks);
    } else if (c.kind == CKind::on_seam) {
      const geo::Frame& frame = *seam_frame(b.surface(c.face));
      if (sf) {
        ceres::CostFunction* f = geo::on_solved_seam(*sf, c.x_old, frame.z, hard, blocks);
        blocks.push_back(x);
        problem.AddResidualBlock(f, nullptr, blocks);
      } else {
        problem.AddResidualBlock(new ceres::AutoDiffCostFunction<OnFixedSeam, 1, 3>(
                                     new OnFixedSeam{frame.origin, frame.z.cross(frame.x).normalized(), hard}),
                                 nullptr, x);
      }
    } else if (sf) {
      ceres::CostFunction* f = on_solved_surface(*sf, true, geo::Vec3::Zero(), hard, blocks);
      blocks.push_back(x);
      problem.AddResidualBlock(f, nullptr, blocks);
    } else {
      problem.AddResidualBlock(new OnFixedSurface(b.surface(c.face), hard), nullptr, x);
    }
  };
  // One solve without constraint `skip` (none when out of range), from the region's
  // geometry, or from `from` (an earlier solve's outcome) at the full hard weight at once.
  auto run = [&](std::size_t skip, const Outcome* from = nullptr) {
    double hard = w_hard;  // the hard terms' weight of the current stage
    std::vector<SurfaceParams> params(faces.size());
    for (std::size_t i = 0; i < faces.size(); ++i) params[i] = *params_of(from ? from->surfaces[i] : b.surface(faces[i]));
    // A tied face is solved through its representative's parameters (params[tie[i]]).
    auto solved_params = [&](std::size_t i) -> SurfaceParams& { return params[tie[i]]; };
    std::vector<std::array<double, 3>> points(start.size());
    for (std::size_t i = 0; i < start.size(); ++i)
      for (int k = 0; k < 3; ++k) points[i][std::size_t(k)] = from ? from->points[i][k] : start[i][k];
    ceres::Problem problem;
    for (std::size_t i = 0; i < faces.size(); ++i) {
      if (tie[i] != i) continue;
      SurfaceParams& p = params[i];
      auto bl = p.blocks();
      for (std::size_t k = 0; k < bl.size(); ++k) {
        problem.AddParameterBlock(bl[k].first, bl[k].second);
        if (ceres::Manifold* m = p.manifold(k)) problem.SetManifold(bl[k].first, m);
      }
    }
    std::vector<double*> blocks;
    for (std::size_t i = 0; i < faces.size(); ++i)
      for (const auto& s : original.at(faces[i]).samples) {
        ceres::CostFunction* f = on_solved_surface(solved_params(i), false, s, &w_face[i], blocks);
        problem.AddResidualBlock(f, new ceres::HuberLoss(1.0), blocks);
      }
    for (std::size_t i = 0; i < start.size(); ++i)
      problem.AddResidualBlock(new ceres::AutoDiffCostFunction<geo::NearPoint, 3, 3>(new geo::NearPoint{start[i], w_prior}),
                               nullptr, points[i].data());
    auto solved_face = [&](FaceH f) -> SurfaceParams* {
      auto it = face_index.find(f);
      return it != face_index.end() ? &solved_params(it->second) : nullptr;
    };
    for (std::size_t k = 0; k < constraints.size(); ++k)
      if (k != skip) add_constraint(problem, constraints[k], points[constraints[k].vertex].data(), &hard, solved_face);
    ceres::Solver::Options options = solver_options();
    // Continuation: the hard weight grows from 10x the data weight to 1/precision by 100x
    // per solve, each starting where the last ended. Started at full weight, the solver
    // crawls along the stiff valley where a surface and its vertices move together.
    ceres::Solver::Summary summary;
    geo::quiet_solver_log();
    for (hard = from ? w_hard : 10 * w_data;; hard = std::min(w_hard, 100 * hard)) {
      ceres::Solve(options, &problem, &summary);
      if (hard >= w_hard) break;
    }

    // The solved geometry, judged geometrically (not by the weighted cost).
    Outcome o;
    for (std::size_t i = 0; i < faces.size(); ++i) {
      SurfaceParams q = solved_params(i);
      // A tied plane keeps its own normal's sense (the representative's may be opposite:
      // the face must not turn inside out).
      if (q.kind == Kind::plane) {
        const auto& old_z = std::get<geo::Plane>(b.surface(faces[i])).frame.z;
        if (old_z.dot(geo::Vec3(q.a[0], q.a[1], q.a[2])) < 0)
          for (double* x : {&q.a[0], &q.a[1], &q.a[2], &q.s[0]}) *x = -*x;
      }
      o.surfaces.push_back(surface_from(b.surface(faces[i]), q));
    }
    for (const auto& p : points) o.points.push_back(geo::Vec3(p[0], p[1], p[2]));
    for (std::size_t k = 0; k < constraints.size(); ++k) {
      if (k == skip) continue;
      const Constraint& c = constraints[k];
      auto it = face_index.find(c.face);
      const geo::Surface& s = it != face_index.end() ? o.surfaces[it->second] : b.surface(c.face);
      const geo::Surface* s2 = nullptr;
      if (c.other.valid()) {
        auto jt = face_index.find(c.other);
        s2 = jt != face_index.end() ? &o.surfaces[jt->second] : &b.surface(c.other);
      }
      double r = residual_of(c, s, s2, o.points[c.vertex]);
      if (!std::isfinite(r)) r = HUGE_VAL;
      o.max_residual = std::max(o.max_residual, r);
      if (!(r <= tol.precision)) o.unmet.push_back({r, k});
    }
    for (std::size_t i = 0; i < faces.size(); ++i) {
      o.moved.push_back(max_distance(o.surfaces[i], original.at(faces[i]).samples));
      o.too_far = o.too_far || !(o.moved.back() <= tol.length);
    }
    // A vertex sliding along its surfaces further than the tolerance reshapes its faces'
    // boundaries by more than the tolerance, however little the surfaces moved.
    for (std::size_t i = 0; i < vlist.size(); ++i)
      if (double d = (o.points[i] - b.point(vlist[i])).norm(); !(d <= tol.length)) o.vertices_too_far.push_back({d, i});
    return o;
  };
  // The points whose fixed surfaces alone cannot hold them: each point with a constraint
  // on fixed faces only (on a fixed surface, on a fixed seam, tangent between two fixed
  // surfaces) that it does not meet now is solved for alone, under those constraints and
  // its prior, with the weights' continuation of `run`. The full solve must meet them
  // too, with the same point free and nothing else to help it (the surfaces are fixed),
  // so where these cannot be met it cannot either: it would end, after up to 400
  // iterations crawling along the valley where two fixed surfaces touch (a pipe's bend
  // and its straight run, tangent), with the same constraints unmet (measured:
  // MODERN_Sink_1.brep at 4x its tolerance, 334 of its 605 solves ran all four stages to
  // their limit, ~40 ms each). Returns the unmet constraints, empty when all are met, and
  // puts in `too_far` the vertices that meet them only further than the tolerance away.
  std::vector<std::pair<double, std::size_t>> too_far;  // by fixed_conflict: distance, vertex
  auto fixed_conflict = [&]() {
    std::vector<std::pair<double, std::size_t>> unmet;  // residual, constraint
    auto fixed = [&](const Constraint& c) {
      return !face_index.count(c.face) && (!c.other.valid() || !face_index.count(c.other));
    };
    std::set<std::size_t> points;
    for (const Constraint& c : constraints)
      if (fixed(c) && !(residual_now(c) <= tol.precision)) points.insert(c.vertex);
    if (points.empty()) return unmet;
    double hard = w_hard;
    std::map<std::size_t, std::array<double, 3>> at;
    for (std::size_t i : points) at[i] = {start[i].x(), start[i].y(), start[i].z()};
    ceres::Problem problem;
    for (auto& [i, x] : at)
      problem.AddResidualBlock(new ceres::AutoDiffCostFunction<geo::NearPoint, 3, 3>(new geo::NearPoint{start[i], w_prior}),
                               nullptr, x.data());
    std::vector<std::size_t> held;
    for (std::size_t k = 0; k < constraints.size(); ++k) {
      const Constraint& c = constraints[k];
      if (!at.count(c.vertex) || !fixed(c)) continue;
      held.push_back(k);
      add_constraint(problem, c, at[c.vertex].data(), &hard, [](FaceH) -> SurfaceParams* { return nullptr; });
    }
    ceres::Solver::Options options = solver_options();
    ceres::Solver::Summary summary;
    geo::quiet_solver_log();
    for (hard = 10 * w_data;; hard = std::min(w_hard, 100 * hard)) {
      ceres::Solve(options, &problem, &summary);
      if (hard >= w_hard) break;
    }
    for (std::size_t k : held) {
      const Constraint& c = constraints[k];
      const auto& x = at[c.vertex];
      const double r = residual_of(c, b.surface(c.face), c.other.valid() ? &b.surface(c.other) : nullptr,
                                   geo::Vec3(x[0], x[1], x[2]));
      if (!(r <= tol.precision)) unmet.push_back({std::isfinite(r) ? r : HUGE_VAL, k});
    }
    // Met, but only by moving a vertex further than the tolerance: the full solve, whose
    // vertex must meet the same surfaces, would end refusing that (vertices_too_far).
    for (auto& [i, x] : at)
      if (i < vlist.size())
        if (const double d = (geo::Vec3(x[0], x[1], x[2]) - start[i]).norm(); !(d <= tol.length)) too_far.push_back({d, i});
    return unmet;
  };
  auto name = [&](std::size_t k) {
    const Constraint& c = constraints[k];
    const std::string at = c.vertex < vlist.size() ? vlist[c.vertex].str() : "a point of an edge";
    switch (c.kind) {
      case CKind::on_seam: return at + " on the seam of " + c.face.str();
      case CKind::tangent: return c.face.str() + " tangent to " + c.other.str() + " at " + at;
      case CKind::on_surface: break;
    }
    return at + " on " + c.face.str();
  };

  SolveInput input;
  input.length = tol.length, input.precision = tol.precision;
  input.tie = tie, input.w_face = w_face;
  std::uint64_t h = fnv_mix(fnv_mix(geo::kFnvOffsetBasis, tol.length), tol.precision);
  for (FaceH f : faces) {
    input.faces.push_back(f.idx()), input.surfaces.push_back(b.surface(f));
    input.samples.push_back(original.at(f).samples);
    for (const geo::Vec3& q : input.samples.back()) h = fnv_mix(fnv_mix(fnv_mix(h, q.x()), q.y()), q.z());
  }
  for (VertexH v : vlist) {
    input.vertices.push_back(v.idx()), input.points.push_back(b.point(v));
    h = fnv_mix(fnv_mix(fnv_mix(fnv_mix(h, double(v.idx())), b.point(v).x()), b.point(v).y()), b.point(v).z());
  }
  for (std::size_t i = vlist.size(); i < start.size(); ++i) input.points.push_back(start[i]);  // tangent edges' points
  for (const Constraint& c : constraints) {
    // A seam or tangency constraint is told apart by its top bits (face indices stay far
    // below them), a tangency's second face by a constraint of its own.
    input.constraints.emplace_back(c.vertex, c.face.idx() | (c.kind == CKind::on_seam ? 0x80000000u : 0u) |
                                                 (c.kind == CKind::tangent ? 0x40000000u : 0u));
    if (c.kind == CKind::tangent) input.constraints.emplace_back(c.vertex, c.other.idx() | 0x40000000u);
    if (!face_index.count(c.face)) input.fixed.push_back(b.surface(c.face));
    if (c.other.valid() && !face_index.count(c.other)) input.fixed.push_back(b.surface(c.other));
  }
  input.hash = h;
  if (const RegionSolve* seen = g_failed_solves.find(input)) return *seen;
  auto failed = [&](const RegionSolve& r) {
    g_failed_solves.add(std::move(input), r);
    return r;
  };

  Outcome o;
  if (const SolveOutcome* seen = g_succeeded_solves.find(input)) {
    o = *seen;
  } else {
    std::vector<std::pair<double, std::size_t>> fixed_unmet = fixed_conflict();
    if (!fixed_unmet.empty()) {
      std::sort(fixed_unmet.begin(), fixed_unmet.end(), [](const auto& a, const auto& c) { return a.first > c.first; });
      out.solved = true;
      out.max_residual = fixed_unmet.front().first;
      out.why = "the new geometry cannot meet these constraints together within the modelling precision " +
                fmt(tol.precision) + ", its fixed surfaces not meeting there:";
      for (std::size_t i = 0; i < fixed_unmet.size() && i < 8; ++i)
        out.why += (i ? ", " : " ") + name(fixed_unmet[i].second) + " (off " + fmt(fixed_unmet[i].first) + ")";
      if (fixed_unmet.size() > 8) out.why += " and " + std::to_string(fixed_unmet.size() - 8) + " more";
      return failed(out);
    }
    if (!too_far.empty()) {
      std::sort(too_far.begin(), too_far.end(), [](const auto& a, const auto& c) { return a.first > c.first; });
      out.solved = true;
      out.why = "the new topology forces vertices further than the tolerance " + fmt(tol.length) +
                " to meet their fixed surfaces:";
      for (std::size_t i = 0; i < too_far.size() && i < 8; ++i)
        out.why += (i ? ", " : " ") + vlist[too_far[i].second].str() + " by " + fmt(too_far[i].first);
      return failed(out);
    }
    o = run(constraints.size());
    if (o.met()) g_succeeded_solves.add(input, o);
  }
  out.solved = true;
  out.max_residual = o.max_residual;
  for (std::size_t i = 0; i < faces.size(); ++i) out.moved.push_back({faces[i], o.moved[i]});
  if (!o.unmet.empty()) {
    // The constraints that cannot be met together: those whose removal alone lets the
    // rest be met (dropping one at a time), when there are few enough to try. Each try
    // starts from this solve's outcome at the full weight: from the region's geometry,
    // through the weights' continuation, the tries were most of CrankArm.brep's beautify
    // at tolerance 0.175 (a pinch's 22 unmet constraints, 88 solves of 114 unknowns).
    std::sort(o.unmet.begin(), o.unmet.end(), [](const auto& a, const auto& c) { return a.first > c.first; });
    std::vector<std::size_t> conflict;
    constexpr std::size_t kMaxDropOne = 24;
    if (o.unmet.size() <= kMaxDropOne)
      for (auto [r, k] : o.unmet)
        if (Outcome without = run(k, &o); without.unmet.empty()) conflict.push_back(k);
    out.why = "the new geometry cannot meet these constraints together within the modelling precision " +
              fmt(tol.precision) + ":";
    if (!conflict.empty()) {
      for (std::size_t i = 0; i < conflict.size(); ++i) out.why += (i ? ", " : " ") + name(conflict[i]);
    } else {
      for (std::size_t i = 0; i < o.unmet.size() && i < 8; ++i)
        out.why += (i ? ", " : " ") + name(o.unmet[i].second) + " (off " + fmt(o.unmet[i].first) + ")";
      if (o.unmet.size() > 8) out.why += " and " + std::to_string(o.unmet.size() - 8) + " more";
    }
    return failed(out);
  }
  if (!o.vertices_too_far.empty()) {
    out.why = "the new topology forces vertices further than the tolerance " + fmt(tol.length) + ":";
    for (std::size_t i = 0; i < o.vertices_too_far.size() && i < 8; ++i)
      out.why += (i ? ", " : " ") + vlist[o.vertices_too_far[i].second].str() + " by " + fmt(o.vertices_too_far[i].first);
    return failed(out);
  }
  if (o.too_far) {
    out.why = "the new topology forces surfaces further than the tolerance " + fmt(tol.length) +
              " from where they were:";
    bool first = true;
    for (std::size_t i = 0; i < faces.size(); ++i)
      if (!(o.moved[i] <= tol.length)) {
        out.why += (first ? " " : ", ") + faces[i].str() + " by " + fmt(o.moved[i]);
        first = false;
      }
    return failed(out);
  }
  const std::vector<geo::Surface>& solved = o.surfaces;
  auto point_after = [&](std::size_t i) { return o.points[i]; };

  for (std::size_t i = 0; i < faces.size(); ++i) {
    b.set_surface(faces[i], solved[i], b.same_sense(faces[i]));
    touched.faces.insert(faces[i]);
  }
  std::set<EdgeH> edges;
  for (std::size_t i = 0; i < vlist.size(); ++i) {
    b.set_point(vlist[i], point_after(i));
    touched.vertices.insert(vlist[i]);
    for (HalfedgeH h : b.outgoing(vlist[i])) edges.insert(edge_of(h));
  }
  align_seams(b, vlist, tol, touched);
  for (EdgeH e : edges) {
    std::string why;
    auto c = derive_edge_curve(b, e, tol, &why);
    if (!c) {
      out.why = "after the solve, " + why;
      return out;
    }
    b.set_curve(e, *c);
    touched.edges.insert(e);
  }
  return out;
}

}  // namespace

}  // namespace kintsugi::detail

// Closing a pinch (paper 4.2); see repair/pinch.h.
#include "repair/pinch.h"

#include "geometry/curve.h"
#include "geometry/distance.h"
#include "geometry/surface.h"
#include "invariants/element_geometry.h"
#include "kernel/euler.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <optional>
#include <set>
#include <sstream>

namespace kintsugi::detail {

namespace {

std::string refused(const char* op, const Error& e) { return std::string(op) + " refused: " + e.message; }

// The half-edge of e in face f; invalid when e has no side in f or both (a seam).
HalfedgeH side_in(const Body& b, EdgeH e, FaceH f) {
  HalfedgeH x = halfedge_of(e, 0), y = halfedge_of(e, 1);
  bool in_x = b.face(x) == f, in_y = b.face(y) == f;
  if (in_x == in_y) return {};
  return in_x ? x : y;
}

// A side of the pinch: a half-edge of the face sampled by arc length (densely enough
// that "the stretch closer than t" is resolved to a fraction of t), and its polyline.
struct Side {
  HalfedgeH h;
  std::vector<geo::Vec3> p;
  std::vector<double> s;       // arc length from origin(h)
  std::vector<geo::Vec3> poly;  // the polyline the samples were taken on
  double length() const { return s.back(); }
};

Side sample(const Body& b, HalfedgeH h, const geo::Tolerances& tol) {
  Side out;
  out.h = h;
  out.poly = halfedge_polyline(b, h, tol.length * 0.01);
  double total = 0;
  for (std::size_t i = 0; i + 1 < out.poly.size(); ++i) total += (out.poly[i + 1] - out.poly[i]).norm();
  const double step = std::max(tol.length / 8, total / 2000);
  out.p.push_back(out.poly[0]);
  out.s.push_back(0);
  for (std::size_t i = 0; i + 1 < out.poly.size(); ++i) {
    const geo::Vec3 a = out.poly[i], d = out.poly[i + 1] - a;
    const double len = d.norm();
    const int n = std::max(1, int(std::ceil(len / step)));
    for (int k = 1; k <= n; ++k) {
      out.p.push_back(a + d * (double(k) / n));
      out.s.push_back(out.s.back() + len / n);
    }
  }
  return out;
}

// Arc length along side S of the point of S nearest q.
double position_of(const Side& S, const geo::Vec3& q) {
  geo::ClosestPair c = geo::point_polyline(q, S.p);
  std::size_t i = std::min(c.segment_b, S.s.size() - 1);
  double s0 = S.s[i], s1 = i + 1 < S.s.size() ? S.s[i + 1] : S.s[i];
  return s0 + c.t * (s1 - s0);
}

// The point of side S at arc length s, on the edge's curve.
geo::Vec3 point_at(const Body& b, const Side& S, double s) {
  auto it = std::lower_bound(S.s.begin(), S.s.end(), s);
  std::size_t i = std::size_t(std::clamp<std::ptrdiff_t>(it - S.s.begin(), 1, std::ptrdiff_t(S.s.size()) - 1));
  double w = S.s[i] > S.s[i - 1] ? (s - S.s[i - 1]) / (S.s[i] - S.s[i - 1]) : 0.0;
  geo::Vec3 p = S.p[i - 1] + std::clamp(w, 0.0, 1.0) * (S.p[i] - S.p[i - 1]);
  const geo::Curve& c = b.curve(edge_of(S.h));
  if (!std::holds_alternative<std::monostate>(c)) p = geo::closest_point(c, p).point;
  return p;
}

// The half-edges from `from` up to `to` (exclusive) along their loop, when they are
// shorter than t together: the short stretch joining a spike's two sides.
std::optional<std::vector<HalfedgeH>> short_stretch(const Body& b, HalfedgeH from, HalfedgeH to, double t) {
  if (b.loop(from) != b.loop(to)) return std::nullopt;
  std::vector<HalfedgeH> out;
  double len = 0;
  for (HalfedgeH h = from; h != to; h = b.next(h)) {
    len += edge_length(b, edge_of(h));
    if (len >= t || out.size() >= 16) return std::nullopt;
    out.push_back(h);
  }
  return out;
}

// Puts each vertex where the faces around it meet, trying the given sets of faces to
// leave out in turn (two nearly coincident faces, still to be merged by pass 8, make the
// meeting point ill-conditioned); the edges at the vertices get curves from their faces.
std::string place(Body& b, const std::vector<std::pair<VertexH, geo::Vec3>>& guesses, const geo::Tolerances& tol,
                  Touched& touched, const std::vector<std::set<FaceH>>& ignores) {
  std::string first_why;
  for (const std::set<FaceH>& ignore : ignores) {
    std::string why = place_vertices(b, guesses, tol, 2 * tol.length, touched, ignore);
    if (why.empty()) return "";
    if (first_why.empty()) first_why = why;
  }
  return first_why;
}

void touch_around(const Body& b, VertexH v, Touched& touched) {
  touched.vertices.insert(v);
  for (HalfedgeH h : b.outgoing(v)) {
    touched.edges.insert(edge_of(h));
    for (HalfedgeH s : {h, twin(h)})
      if (b.face(s).valid()) touched.faces.insert(b.face(s));
  }
}

// Joins the vertices origin(x) and origin(y) of face f's loops into one, keeping
// origin(x): a new edge across the face (mef within one loop: a new face with f's
// surface; mekr between loops: the ring joins the other loop) is collapsed by kev.
std::string join_vertices(Body& b, HalfedgeH x, HalfedgeH y) {
  VertexH keep = b.origin(x);
  FaceH f = b.face(x);
  EdgeH e;
  if (b.loop(x) == b.loop(y)) {
    auto r = euler::mef(b, Corner::before(x), Corner::before(y));
    if (!r) return refused("mef", r.error());
    b.set_surface(r->face, b.surface(f), b.same_sense(f));
    e = r->edge;
  } else {
    bool y_ring = !b.is_outer(b.loop(y));
    auto r = y_ring ? euler::mekr(b, Corner::before(x), Corner::before(y)) : euler::mekr(b, Corner::before(y), Corner::before(x));
    if (!r) return refused("mekr", r.error());
    e = r->edge;
  }
  HalfedgeH h = b.origin(halfedge_of(e, 0)) == keep ? halfedge_of(e, 0) : halfedge_of(e, 1);
  auto k = euler::kev(b, h);
  if (!k) return refused("kev", k.error());
  return "";
}

// Drops the stretch of arc length `len` at the start (or end) of a polyline.
std::vector<geo::Vec3> trimmed(std::vector<geo::Vec3> pts, double len, bool from_start) {
  if (!from_start) std::reverse(pts.begin(), pts.end());
  std::vector<geo::Vec3> out;
  double run = 0;
  for (std::size_t i = 0; i + 1 < pts.size(); ++i) {
    double seg = (pts[i + 1] - pts[i]).norm();
    if (run + seg > len) {
      if (out.empty()) out.push_back(pts[i] + (pts[i + 1] - pts[i]) * ((len - run) / seg));
      out.push_back(pts[i + 1]);
    }
    run += seg;
  }
  if (!from_start) std::reverse(out.begin(), out.end());
  return out;
}

// Whether consecutive half-edges p -> h of a loop still run beside each other away from
// the vertex they share (closer than t once t is cut off each there).
bool runs_beside(const Body& b, HalfedgeH p, HalfedgeH h, const geo::Tolerances& tol) {
  auto a = trimmed(halfedge_polyline(b, p, tol.length * 0.01), tol.length, false);
  auto c = trimmed(halfedge_polyline(b, h, tol.length * 0.01), tol.length, true);
  if (a.size() < 2 || c.size() < 2) return false;
  return geo::polyline_polyline(a, c).distance < tol.length;
}

std::string close_one(Body& b, FaceH f, EdgeH ea, EdgeH eb, const geo::Tolerances& tol, Touched& touched,
                      std::vector<VertexH>* merged);

// Zipping on along a side that folds back (a tilted boss's ring zipped edge after edge
// against a plate's side) can leave a chain of edges hanging into a face: each with the
// face on both sides, the last ending at a vertex on no other edge. That is a spike of
// width 0 — what the spiking repair drops — and it was left for pass 11, whose collapse of
// it then made the vertex it hung from mergeable: a type fixed before pass 11 (the Table 1
// audit, run 4c0c630, shard 9309: paper6 with a pinch, a face fitted twice and a short
// edge). The chain is killed from its hanging end (kev), among the edges and vertices the
// repair touched.
std::string drop_hanging_edges(Body& b, Touched& touched) {
  std::vector<VertexH> look(touched.vertices.begin(), touched.vertices.end());
  for (EdgeH e : touched.edges)
    if (b.alive(e)) look.push_back(b.origin(halfedge_of(e, 0))), look.push_back(b.target(halfedge_of(e, 0)));
  while (!look.empty()) {
    VertexH v = look.back();
    look.pop_back();
    if (!b.alive(v)) continue;
    const std::vector<HalfedgeH> out = b.outgoing(v);
    if (out.size() != 1) continue;
    const VertexH w = b.target(out[0]);
    auto r = euler::kev(b, twin(out[0]));  // kills v, the hanging end
    if (!r) return refused("kev", r.error());
    touched.vertices.erase(v);
    touched.vertices.insert(w);
    look.push_back(w);
  }
  return "";
}

}  // namespace

std::string close_pinch(Body& b, FaceH f, EdgeH ea, EdgeH eb, const geo::Tolerances& tol, Touched& touched) {
  std::vector<VertexH> merged;
  std::string why = close_one(b, f, ea, eb, tol, touched, &merged);
  // Several edges on a side (complex): the next edge of one side may still run beside
  // the other side, now consecutive with it at a vertex just made (consecutive edges
  // are never reported as pinched); zip on along it while it does.
  for (int round = 0; why.empty() && round < 16 && !merged.empty(); ++round) {
    VertexH v = merged.back();
    merged.pop_back();
    if (!b.alive(v)) continue;
    for (HalfedgeH h : b.outgoing(v)) {
      HalfedgeH p = b.prev(h);
      if (!b.face(h).valid() || edge_of(p) == edge_of(h) || !runs_beside(b, p, h, tol)) continue;
      why = close_one(b, b.face(h), edge_of(p), edge_of(h), tol, touched, &merged);
      break;
    }
  }
  if (why.empty()) why = drop_hanging_edges(b, touched);
  return why;
}

namespace {

// The strip between mid_a and mid_b (their face, bounded by them and the short edges
// joining their ends) is collapsed: the short edges by kev onto mid_a's vertices, then
// the strip, two edges by then, killed across mid_b (kef): mid_a's edge lies between the
// faces that were across the two sides (f1, f2). Its vertices go where the faces meet.
std::string collapse_strip(Body& b, HalfedgeH mid_a, HalfedgeH mid_b, FaceH f1, FaceH f2, const geo::Vec3& guess1,
                           const geo::Vec3& guess2, const geo::Tolerances& tol, Touched& touched,
                           std::vector<VertexH>* merged) {
  while (b.prev(mid_a) != mid_b) {
    auto r = euler::kev(b, twin(b.prev(mid_a)));
    if (!r) return refused("kev", r.error());
  }
  while (b.next(mid_a) != mid_b) {
    auto r = euler::kev(b, b.next(mid_a));
    if (!r) return refused("kev", r.error());
  }
  auto k = euler::kef(b, twin(mid_b));
  if (!k) return refused("kef", k.error());
  const VertexH v1 = b.origin(mid_a), v2 = b.target(mid_a);
  touched.edges.insert(edge_of(mid_a));
  touch_around(b, v1, touched);
  touch_around(b, v2, touched);
  std::string why = place(b, {{v1, guess1}, {v2, guess2}}, tol, touched, {{f2}, {f1}, {}});
  touch_around(b, v1, touched);
  touch_around(b, v2, touched);
  merged->push_back(v1);
  merged->push_back(v2);
  return why;
}

std::string close_one(Body& b, FaceH f, EdgeH ea, EdgeH eb, const geo::Tolerances& tol, Touched& touched,
                      std::vector<VertexH>* merged) {
  const double t = tol.length;
  if (!b.alive(f) || !b.alive(ea) || !b.alive(eb)) return "no longer present: removed by an earlier repair";
  HalfedgeH ha = side_in(b, ea, f), hb = side_in(b, eb, f);
  if (!ha.valid() || !hb.valid()) return ea.str() + " and " + eb.str() + " are no longer both sides of " + f.str();
  FaceH f1 = b.face(twin(ha)), f2 = b.face(twin(hb));
  if (!f1.valid() || !f2.valid()) return "a side of the pinch borders a gap";
  const bool one_loop = b.loop(ha) == b.loop(hb);
  // Ends joined through a stretch shorter than t: a's end to b's start, b's end to a's start.
  const bool joined_a_end = one_loop && short_stretch(b, b.next(ha), hb, t).has_value();
  const bool joined_a_start = one_loop && short_stretch(b, b.next(hb), ha, t).has_value();
  if (joined_a_end && joined_a_start) {
    // The face is nothing but the two sides and short stretches joining them: what is left
    // of a spike after its pinch was closed further along (several edges on a side). It
    // is the strip itself.
    if (b.loops_of(f).size() != 1) return f.str() + " is narrower than the tolerance everywhere: not a pinch";
    const geo::Vec3 g1 = (b.point(b.origin(ha)) + b.point(b.target(hb))) / 2;
    const geo::Vec3 g2 = (b.point(b.target(ha)) + b.point(b.origin(hb))) / 2;
    touched.faces.insert(f);
    return collapse_strip(b, ha, hb, f1, f2, g1, g2, tol, touched, merged);
  }

  Side A = sample(b, ha, tol), B = sample(b, hb, tol);
  std::vector<double> da(A.p.size()), db(B.p.size());
  for (std::size_t i = 0; i < A.p.size(); ++i) da[i] = geo::point_polyline(A.p[i], B.poly).distance;
  for (std::size_t j = 0; j < B.p.size(); ++j) db[j] = geo::point_polyline(B.p[j], A.poly).distance;
  // The narrowest place, away from joined ends (there the sides meet anyway).
  auto excluded_a = [&](std::size_t i) { return (joined_a_start && A.s[i] < t) || (joined_a_end && A.s[i] > A.length() - t); };
  auto excluded_b = [&](std::size_t j) { return (joined_a_end && B.s[j] < t) || (joined_a_start && B.s[j] > B.length() - t); };
  std::size_t ia = A.p.size(), jb = B.p.size();
  for (std::size_t i = 0; i < A.p.size(); ++i)
    if (!excluded_a(i) && (ia == A.p.size() || da[i] < da[ia])) ia = i;
  for (std::size_t j = 0; j < B.p.size(); ++j)
    if (!excluded_b(j) && (jb == B.p.size() || db[j] < db[jb])) jb = j;
  if (ia == A.p.size() || jb == B.p.size() || da[ia] >= t) return f.str() + " is no longer pinched between " + ea.str() + " and " + eb.str();

  // The stretch of each side closer than t to the other, around the narrowest place.
  std::size_t lo_a = ia, hi_a = ia, lo_b = jb, hi_b = jb;
  while (lo_a > 0 && da[lo_a - 1] < t) --lo_a;
  while (hi_a + 1 < A.p.size() && da[hi_a + 1] < t) ++hi_a;
  while (lo_b > 0 && db[lo_b - 1] < t) --lo_b;
  while (hi_b + 1 < B.p.size() && db[hi_b + 1] < t) ++hi_b;

  const bool lines = std::holds_alternative<geo::Line>(b.curve(ea)) && std::holds_alternative<geo::Line>(b.curve(eb));
  const bool spike = (joined_a_end && A.s[hi_a] > A.length() - t) || (joined_a_start && A.s[lo_a] < t);
  // The faces across both sides pass within t of the other side: one edge can lie on both.
  bool alike = true;
  for (std::size_t i = lo_a; i <= hi_a && alike; ++i) alike = std::abs(geo::signed_distance(b.surface(f2), A.p[i])) < t;
  for (std::size_t j = lo_b; j <= hi_b && alike; ++j) alike = std::abs(geo::signed_distance(b.surface(f1), B.p[j])) < t;
  const bool long_run = A.s[hi_a] - A.s[lo_a] >= t || B.s[hi_b] - B.s[lo_b] >= t;
  const bool zip = spike || (alike && lines && long_run);

  if (!zip) {
    // Complex: the sides meet in one new vertex at the narrowest place.
    for (EdgeH e : {ea, eb})
      if (std::holds_alternative<geo::Circle>(b.curve(e))) {
        std::string why = circle_contact_conflict(b, f, e, tol);
        if (!why.empty()) return why;
      }
    const double sa = A.s[ia];
    const geo::Vec3 pa = point_at(b, A, sa), pb_raw = geo::point_polyline(A.p[ia], B.poly).on_b;
    const double sb = position_of(B, pb_raw);
    const geo::Vec3 pb = point_at(b, B, sb);
    const geo::Vec3 guess = (pa + pb) / 2;
    // The half-edge of f leaving the meeting point on each side (an existing vertex
    // within t/2 of it, or a new one splitting the edge there).
    auto out_at = [&](HalfedgeH h, const Side& S, double s, const geo::Vec3& p, HalfedgeH* out) -> std::string {
      if (s < t / 2 && b.origin(h) != b.target(h)) {
        *out = h;
      } else if (S.length() - s < t / 2 && b.origin(h) != b.target(h)) {
        *out = b.next(h);
      } else {
        auto r = euler::semv(b, h, p);
        if (!r) return refused("semv", r.error());
        touched.edges.insert(r->edge);
        *out = r->next;
      }
      return "";
    };
    HalfedgeH xa, xb;
    std::string why = out_at(ha, A, sa, pa, &xa);
    if (why.empty()) why = out_at(hb, B, sb, pb, &xb);
    if (why.empty() && b.origin(xa) == b.origin(xb)) why = "the sides already meet at " + b.origin(xa).str();
    if (why.empty()) why = join_vertices(b, xa, xb);
    if (!why.empty()) return why;
    VertexH v = b.origin(xa);
    touch_around(b, v, touched);
    why = place(b, {{v, guess}}, tol, touched, {{}, {f2}, {f1}});
    touch_around(b, v, touched);
    return why;
  }

  // Zip: the stretches, each cut back to where the other side's stretch ends (a block's
  // base edge closes its whole length on the plate's edge, not the t beyond its corners).
  // The sides run opposite ways: the start of a's stretch faces the end of b's.
  double sa0 = A.s[lo_a], sa1 = A.s[hi_a], sb0 = B.s[lo_b], sb1 = B.s[hi_b];
  {
    const double pa_of_b1 = position_of(A, B.p[hi_b]), pa_of_b0 = position_of(A, B.p[lo_b]);
    const double pb_of_a1 = position_of(B, A.p[hi_a]), pb_of_a0 = position_of(B, A.p[lo_a]);
    if (pa_of_b1 > pa_of_b0 + tol.precision || pb_of_a0 + tol.precision < pb_of_a1)
      return ea.str() + " and " + eb.str() + " run the same way along the pinch";
    sa0 = std::max(sa0, pa_of_b1);
    sa1 = std::min(sa1, pa_of_b0);
    sb0 = std::max(sb0, pb_of_a1);
    sb1 = std::min(sb1, pb_of_a0);
  }
  // Ends within t of a vertex close there (no edge shorter than t is left).
  auto snap = [&](double& s0, double& s1, double len) {
    if (s0 < t) s0 = 0;
    if (len - s1 < t) s1 = len;
  };
  snap(sa0, sa1, A.length());
  snap(sb0, sb1, B.length());
  if (!(sa1 - sa0 > tol.precision && sb1 - sb0 > tol.precision))
    return "the stretch where " + ea.str() + " and " + eb.str() + " run side by side has no length";

  // Split each side at its stretch's ends: mid_a runs VA1 -> VA2, mid_b VB1 -> VB2, with
  // VB2 facing VA1 and VA2 facing VB1.
  auto cut = [&](HalfedgeH h, const Side& S, double s0, double s1, HalfedgeH* mid) -> std::string {
    const geo::Vec3 p0 = point_at(b, S, s0), p1 = point_at(b, S, s1);
    if (s1 < S.length()) {
      auto r = euler::semv(b, h, p1);
      if (!r) return refused("semv", r.error());
      touched.edges.insert(r->edge);
    }
    *mid = h;
    if (s0 > 0) {
      auto r = euler::semv(b, h, p0);
      if (!r) return refused("semv", r.error());
      touched.edges.insert(r->edge);
      *mid = r->next;
    }
    return "";
  };
  HalfedgeH mid_a, mid_b;
  std::string why = cut(ha, A, sa0, sa1, &mid_a);
  if (why.empty()) why = cut(hb, B, sb0, sb1, &mid_b);
  if (!why.empty()) return why;
  const geo::Vec3 guess1 = (b.point(b.origin(mid_a)) + b.point(b.target(mid_b))) / 2;
  const geo::Vec3 guess2 = (b.point(b.target(mid_a)) + b.point(b.origin(mid_b))) / 2;

  // Join the ends across the pinch where they are not joined already (by a short
  // stretch: the spike's end). Each new edge made in one loop splits a face off; the
  // last one made cuts off the strip between mid_a and mid_b.
  auto joined = [&](HalfedgeH from, HalfedgeH to) { return short_stretch(b, from, to, t).has_value(); };
  bool new_face = false;
  if (!joined(b.next(mid_b), mid_a)) {
    new_face = b.loop(mid_a) == b.loop(mid_b);
    // A joining edge VA1 -> VB2, kept as an edge for now (collapsed below).
    if (new_face) {
      auto r = euler::mef(b, Corner::before(mid_a), Corner::before(b.next(mid_b)));
      if (!r) return refused("mef", r.error());
      b.set_surface(r->face, b.surface(f), b.same_sense(f));
    } else {
      bool b_ring = !b.is_outer(b.loop(mid_b));
      auto r = b_ring ? euler::mekr(b, Corner::before(mid_a), Corner::before(b.next(mid_b)))
                      : euler::mekr(b, Corner::before(b.next(mid_b)), Corner::before(mid_a));
      if (!r) return refused("mekr", r.error());
    }
  }
  if (!joined(b.next(mid_a), mid_b)) {
    if (b.loop(mid_a) != b.loop(mid_b)) return "the two sides are still in different loops";
    auto r = euler::mef(b, Corner::before(mid_b), Corner::before(b.next(mid_a)));
    if (!r) return refused("mef", r.error());
    b.set_surface(r->face, b.surface(f), b.same_sense(f));
    new_face = true;
  }
  if (!new_face || b.face(mid_a) != b.face(mid_b))
    return "no strip between " + ea.str() + " and " + eb.str() + " could be cut off " + f.str();
  return collapse_strip(b, mid_a, mid_b, f1, f2, guess1, guess2, tol, touched, merged);
}

}  // namespace

std::string circle_contact_conflict(const Body& b, FaceH f, EdgeH ce, const geo::Tolerances& tol) {
  const auto* C = std::get_if<geo::Circle>(&b.curve(ce));
  if (!C) return "";
  auto on_circle = [&](EdgeH e) {
    const auto* D = std::get_if<geo::Circle>(&b.curve(e));
    return D && std::abs(D->radius - C->radius) <= tol.precision &&
           (D->frame.origin - C->frame.origin).norm() <= tol.precision && std::abs(D->frame.z.dot(C->frame.z)) > 1 - 1e-9;
  };
  std::vector<HalfedgeH> on, others;
  std::map<VertexH, int> visits;
  for (LoopH l : b.loops_of(f))
    for (HalfedgeH h : b.loop_halfedges(l)) {
      (on_circle(edge_of(h)) ? on : others).push_back(h);
      visits[b.origin(h)]++;
    }
  std::set<VertexH> circle_vertices;
  std::vector<std::vector<geo::Vec3>> arcs;
  for (HalfedgeH h : on) {
    circle_vertices.insert(b.origin(h));
    circle_vertices.insert(b.target(h));
    arcs.push_back(halfedge_polyline(b, h, tol.length * 0.01));
  }
  // Contacts made already: circle vertices the face's boundary passes more than once.
  std::vector<geo::Vec3> points;
  std::vector<std::string> names;
  for (VertexH v : circle_vertices)
    if (visits[v] >= 2) {
      points.push_back(b.point(v));
      names.push_back(v.str());
    }
  // Contacts still to make: other sides within t of the circle, away from its vertices;
  // sides meeting at a vertex close one pinch together (a block's corner).
  struct Near {
    HalfedgeH h;
    double d;
    geo::Vec3 p;
  };
  std::vector<Near> near;
  for (HalfedgeH g : others) {
    if (circle_vertices.count(b.origin(g)) || circle_vertices.count(b.target(g))) continue;
    auto poly = halfedge_polyline(b, g, tol.length * 0.01);
    Near best{g, HUGE_VAL, geo::Vec3::Zero()};
    for (const auto& arc : arcs) {
      geo::ClosestPair c = geo::polyline_polyline(poly, arc);
      if (c.distance < best.d) best = {g, c.distance, c.on_a};
    }
    if (best.d < tol.length) near.push_back(best);
  }
  std::vector<std::size_t> group(near.size());
  for (std::size_t i = 0; i < near.size(); ++i) group[i] = i;
  std::function<std::size_t(std::size_t)> root = [&](std::size_t i) { return group[i] == i ? i : group[i] = root(group[i]); };
  // Sides meeting at a vertex that is itself within t of the circle close one pinch (a
  // block's corner); the corners of a block around the circle are far from it.
  auto close_to_circle = [&](VertexH v) {
    for (const auto& arc : arcs)
      if (geo::point_polyline(b.point(v), arc).distance < tol.length) return true;
    return false;
  };
  for (std::size_t i = 0; i < near.size(); ++i)
    for (std::size_t j = 0; j < i; ++j) {
      HalfedgeH x = near[i].h, y = near[j].h;
      for (VertexH v : {b.origin(x), b.target(x)})
        if ((v == b.origin(y) || v == b.target(y)) && close_to_circle(v)) group[root(i)] = root(j);
    }
  std::map<std::size_t, std::size_t> best_of;
  for (std::size_t i = 0; i < near.size(); ++i) {
    auto [it, fresh] = best_of.emplace(root(i), i);
    if (!fresh && near[i].d < near[it->second].d) it->second = i;
  }
  for (auto [r, i] : best_of) {
    points.push_back(near[i].p);
    names.push_back("the pinch at " + edge_of(near[i].h).str());
  }
  if (points.size() <= 3) return "";
  // The circle in C's plane nearest all the points (algebraic fit), and how far off it
  // the worst point is.
  const geo::Vec3 o = C->frame.origin, x = C->frame.x, y = C->frame.y(), z = C->frame.z;
  Eigen::MatrixXd M(points.size(), 3);
  Eigen::VectorXd r(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    double u = (points[i] - o).dot(x), v = (points[i] - o).dot(y);
    M(Eigen::Index(i), 0) = 2 * u;
    M(Eigen::Index(i), 1) = 2 * v;
    M(Eigen::Index(i), 2) = 1;
    r(Eigen::Index(i)) = u * u + v * v;
  }
  Eigen::Vector3d sol = M.colPivHouseholderQr().solve(r);
  const double radius = std::sqrt(std::max(0.0, sol(2) + sol(0) * sol(0) + sol(1) * sol(1)));
  double off = 0;
  for (const geo::Vec3& p : points) {
    double u = (p - o).dot(x), v = (p - o).dot(y);
    off = std::max(off, std::abs(std::hypot(u - sol(0), v - sol(1)) - radius));
    off = std::max(off, std::abs((p - o).dot(z)));
  }
  if (off <= tol.precision) return "";
  std::ostringstream why;
  why << "unrealisable (paper Figure 32(b)): closing the pinches against the circle of " << ce.str() << " would put "
      << points.size() << " vertices on that one circle (";
  for (std::size_t i = 0; i < names.size(); ++i) why << (i ? ", " : "") << names[i];
  why << "), but a circle is fixed by three points and these lie up to " << off << " off any one circle";
  return why.str();
}

}  // namespace kintsugi::detail

// Pinched faces in the three locations and both configurations, with clean twins
// (zoo/defects_pinch.h).
#include "zoo/defects_pinch.h"

#include "geometry/curve.h"
#include "zoo/paper_build.h"

#include <cmath>

namespace kintsugi::zoo::make {

namespace {

// The frame of a straight edge of a planar face: P(s, in) is arc length s along h from
// origin(h), `in` into the face.
struct EdgeFrame {
  FaceH f;
  Vec3 p, d, u, n;
  Vec3 operator()(double s, double in) const { return p + s * d + in * u; }
};

EdgeFrame frame_of(const Body& b, HalfedgeH h) {
  FaceH f = b.face(h);
  if (!f.valid() || !plane_of(b, f) || !std::holds_alternative<geo::Line>(b.curve(edge_of(h))))
    throw Unsuitable("not a straight edge of a planar face");
  EdgeFrame e;
  e.f = f;
  e.p = b.point(b.origin(h));
  e.d = (b.point(b.target(h)) - e.p).normalized();
  e.n = outward_normal(b, f);
  e.u = e.n.cross(e.d);
  return e;
}

double length_of(const Body& b, HalfedgeH h) { return (b.point(b.target(h)) - b.point(b.origin(h))).norm(); }

// Splits h at arc lengths s0 < s1 from its origin: the piece between them.
HalfedgeH piece(Body& b, HalfedgeH h, const EdgeFrame& e, double s0, double s1) {
  if (!(0 < s0 && s0 < s1 && s1 < length_of(b, h))) throw Unsuitable("the block does not fit along " + edge_of(h).str());
  must(euler::semv(b, h, e(s1, 0)), "semv (pinch)");
  return must(euler::semv(b, h, e(s0, 0)), "semv (pinch)").next;
}

// The block's near side from (s0, off0) to (s1, off1), bent in the middle if asked.
std::vector<Vec3> near_side(const EdgeFrame& e, const PinchBlock& k, double s0, double s1, double base) {
  std::vector<Vec3> pts{e(s0, base + k.off0)};
  if (k.kink) pts.push_back(e((s0 + s1) / 2, base + (k.off0 + k.off1) / 2 + k.kink_bump));
  pts.push_back(e(s1, base + k.off1));
  return pts;
}

// The edge of f between the vertices at p and q.
EdgeH edge_between(const Body& b, FaceH f, const Vec3& p, const Vec3& q) { return edge_of(halfedge_in(b, f, p, q)); }

// The half-edge of f's outer loop whose straight edge holds both points.
HalfedgeH halfedge_through(const Body& b, FaceH f, const Vec3& p, const Vec3& q) {
  for (HalfedgeH h : b.loop_halfedges(b.outer_loop(f))) {
    Vec3 a = b.point(b.origin(h)), c = b.point(b.target(h));
    double len = (c - a).norm();
    auto on = [&](const Vec3& x) {
      double s = (x - a).dot(c - a) / (len * len);
      return s > 0 && s < 1 && (a + s * (c - a) - x).norm() < 1e-9 * (1 + len);
    };
    if (std::holds_alternative<geo::Line>(b.curve(edge_of(h))) && on(p) && on(q)) return h;
  }
  throw Unsuitable("no edge of " + f.str() + " runs through both points");
}

// Raises region face r by `height` and merges the block's faces over the given half-edges
// of r's loop into the faces across them (flush).
void raise_flush(Body& b, FaceH r, const Vec3& up, const std::vector<HalfedgeH>& flush) {
  extrude(b, r, up);
  for (HalfedgeH m : flush) must(euler::kef(b, twin(m)), "kef (flush)");
}

}  // namespace

KnownDefect pinch_bossing(Body& b, HalfedgeH h, const PinchBlock& k, double w) {
  EdgeFrame e = frame_of(b, h);
  const double far = std::max(k.off0, k.off1) + w;
  std::vector<Vec3> pts = near_side(e, k, k.s0, k.s1, 0);
  pts.push_back(e(k.s1, far));
  pts.push_back(e(k.s0, far));
  FaceH g = add_ring_face(b, e.f, pts);
  EdgeH near = edge_between(b, g, pts[0], pts[1]);
  extrude(b, g, k.height * e.n);
  return {ProblemType::pinched_face, {e.f.str(), edge_of(h).str(), near.str()}, std::min(k.off0, k.off1)};
}

KnownDefect pinch_necking(Body& b, HalfedgeH h, const PinchBlock& k, double across) {
  EdgeFrame e = frame_of(b, h);
  HalfedgeH opposite = halfedge_through(b, e.f, e(k.s0, across), e(k.s1, across));
  HalfedgeH mid = piece(b, h, e, k.s0, k.s1);
  // The far side runs across, off0..off1 short of the opposite edge.
  PinchBlock back = k;
  back.off0 = -k.off0;
  back.off1 = -k.off1;
  back.kink_bump = -k.kink_bump;
  std::vector<Vec3> pts = near_side(e, back, k.s0, k.s1, across);
  FaceH r = cut_off(b, mid, pts);
  EdgeH near = edge_between(b, e.f, pts[0], pts[1]);
  raise_flush(b, r, k.height * e.n, {mid});
  return {ProblemType::pinched_face, {e.f.str(), edge_of(opposite).str(), near.str()}, std::min(k.off0, k.off1)};
}

void pinch_necking_clean(Body& b, HalfedgeH h, const PinchBlock& k, double across) {
  EdgeFrame e = frame_of(b, h);
  HalfedgeH opposite = halfedge_through(b, e.f, e(k.s0, across), e(k.s1, across));
  HalfedgeH mid = piece(b, h, e, k.s0, k.s1);
  // The opposite edge runs the other way: split at s1 first, then s0.
  Vec3 q1 = e(k.s1, across), q0 = e(k.s0, across);
  must(euler::semv(b, opposite, q1), "semv (pinch)");  // opposite ends at q1, then q1 -> old end
  must(euler::semv(b, b.next(opposite), q0), "semv (pinch)");
  HalfedgeH mid2 = b.next(opposite);  // q1 -> q0
  FaceH f = e.f;
  MefResult right = must(euler::mef(b, Corner::before(b.next(mid)), Corner::before(mid2)), "mef (pinch)");
  b.set_surface(right.face, b.surface(f), b.same_sense(f));
  set_line(b, right.edge);
  MefResult left = must(euler::mef(b, Corner::before(b.next(mid2)), Corner::before(mid)), "mef (pinch)");
  b.set_surface(left.face, b.surface(f), b.same_sense(f));
  set_line(b, left.edge);
  raise_flush(b, f, k.height * e.n, {mid, mid2});
}

KnownDefect pinch_spiking(Body& b, HalfedgeH h, const PinchBlock& k, double depth) {
  EdgeFrame e = frame_of(b, h);
  HalfedgeH h0 = b.prev(h);
  Vec3 d0 = (b.point(b.target(h0)) - b.point(b.origin(h0))).normalized();
  if (std::abs(d0.dot(e.d)) > 1e-9) throw Unsuitable("the corner at " + b.origin(h).str() + " is not square");
  HalfedgeH mid = piece(b, h, e, k.s0, k.s1);
  // The near side runs from (s0, 0) into the face, off0..off1 from the previous edge.
  std::vector<Vec3> pts;
  if (k.kink) pts.push_back(e((k.off0 + k.off1) / 2 + k.kink_bump, depth / 2));
  pts.push_back(e(k.off1, depth));
  pts.push_back(e(k.s1, depth));
  FaceH r = cut_off(b, mid, pts);
  EdgeH near = edge_between(b, e.f, e(k.s0, 0), pts[0]);
  raise_flush(b, r, k.height * e.n, {mid});
  return {ProblemType::pinched_face, {e.f.str(), edge_of(h0).str(), near.str()}, std::min(k.off0, k.off1)};
}

void pinch_spiking_clean(Body& b, HalfedgeH h, const PinchBlock& k, double depth) {
  EdgeFrame e = frame_of(b, h);
  FaceH f = e.f;
  HalfedgeH h0 = b.prev(h);
  if (!(k.s1 < length_of(b, h) && depth < length_of(b, h0))) throw Unsuitable("the block does not fit in the corner");
  must(euler::semv(b, h, e(k.s1, 0)), "semv (pinch)");
  HalfedgeH mid1 = h;
  HalfedgeH mid0 = must(euler::semv(b, h0, e(0, depth)), "semv (pinch)").next;
  MevResult s = must(euler::mev(b, Corner::before(b.next(mid1)), e(k.s1, depth)), "mev (pinch)");
  MefResult m = must(euler::mef(b, Corner::before(s.y), Corner::before(mid0)), "mef (pinch)");
  b.set_surface(m.face, b.surface(f), b.same_sense(f));
  set_line(b, s.edge);
  set_line(b, m.edge);
  const VertexH corner = b.origin(h);
  raise_flush(b, f, k.height * e.n, {mid0, mid1});
  // The corner is left between the plate's and the block's vertical edges, on one line:
  // they are one edge.
  if (b.degree(corner) == 2) {
    HalfedgeH in = twin(b.out(corner));
    must(euler::jekv(b, in), "jekv (pinch)");
    set_line(b, edge_of(in));
  }
}

}  // namespace kintsugi::zoo::make

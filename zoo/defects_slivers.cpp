// Slivers and chains of small faces the way surface fitting makes them (spec/defects.md):
// a chamfer plane or a narrow cylindrical fillet that fitting invented along an edge,
// tapered or not, on convex and concave edges; a small notch along an edge (an end face,
// one or more faces along the edge, an end face: all below the tolerance).
#include "zoo/defects_slivers.h"

#include "geometry/curve.h"
#include "geometry/surface.h"

#include <cmath>

namespace kintsugi::zoo {

namespace {

Vec3 dir_of(const Body& b, HalfedgeH h) { return (b.point(b.target(h)) - b.point(b.origin(h))).normalized(); }

bool straight(const Body& b, EdgeH e) { return std::holds_alternative<geo::Line>(b.curve(e)); }

FaceH face_named(const std::string& s) { return FaceH(FaceH::Index(std::stoul(s.substr(1)))); }

// The two planar faces of a straight edge and the directions into them, square to it.
struct EdgeFrame {
  HalfedgeH hA;
  FaceH A, B;
  Vec3 p, q, d, nA, nB, uA, uB;
  bool convex;
};

EdgeFrame edge_frame(const Body& b, EdgeH e, FaceH A) {
  HalfedgeH hA = side_in_face(b, e, A);
  if (!hA.valid() || !straight(b, e)) throw Unsuitable(e.str() + " is not a straight edge of " + A.str());
  FaceH B = b.face(twin(hA));
  if (!B.valid() || B == A || !plane_of(b, A) || !plane_of(b, B)) throw Unsuitable(e.str() + " is not between two planar faces");
  EdgeFrame f{hA, A, B, b.point(b.origin(hA)), b.point(b.target(hA)), dir_of(b, hA), outward_normal(b, A), outward_normal(b, B), {}, {}, false};
  f.uA = f.nA.cross(f.d);   // into A, square to the edge (A's loop turns left)
  f.uB = f.nB.cross(-f.d);  // into B
  f.convex = f.uA.dot(f.nB) < 0;
  if (std::abs(f.nA.dot(f.nB)) > 1 - 1e-6) throw Unsuitable(e.str() + " joins two parallel faces");
  return f;
}

// Why no fillet fits along e (empty if one does): its ends are arcs, so the faces at the
// edge's ends must be planes square to it.
std::string fillet_unsuitable(const Body& b, EdgeH e, const EdgeFrame& f) {
  for (HalfedgeH h : {b.next(twin(b.next(twin(f.hA)))), b.next(twin(b.next(f.hA)))}) {
    FaceH end = b.face(h);
    if (!end.valid() || !plane_of(b, end) || std::abs(outward_normal(b, end).dot(f.d)) < 1 - 1e-9)
      return "the faces at the ends of " + e.str() + " are not square to it";
  }
  return "";
}

}  // namespace

namespace make {

KnownDefect tapered_chamfer(Body& b, EdgeH e, FaceH A, double wa0, double wb0, double wa1) {
  EdgeFrame f = edge_frame(b, e, A);
  Vec3 a0 = f.p + wa0 * f.uA, b0 = f.p + wb0 * f.uB, a1 = f.q + wa1 * f.uA;
  return chamfer_plane(b, e, A, a0, (b0 - a0).cross(a1 - a0));
}

KnownDefect fillet(Body& b, EdgeH e, FaceH A, double radius) {
  EdgeFrame f = edge_frame(b, e, A);
  // The axis at distance `radius` from both planes, inside the solid at a convex edge
  // (material taken off) and outside at a concave one (material added).
  const double s = f.convex ? -1.0 : 1.0;
  const double na_ub = f.nA.dot(f.uB), nb_ua = f.nB.dot(f.uA);
  if (std::abs(na_ub) < 1e-6 || std::abs(nb_ua) < 1e-6) throw Unsuitable(e.str() + " is too flat for a fillet");
  Vec3 c = f.p + (s * radius / nb_ua) * f.uA + (s * radius / na_ub) * f.uB;
  Vec3 tA = c - s * radius * f.nA, tB = c - s * radius * f.nB;
  if (const std::string why = fillet_unsuitable(b, e, f); !why.empty()) throw Unsuitable(why);
  KnownDefect d = chamfer_plane(b, e, A, tA, f.d.cross(tB - tA));
  FaceH sliver = face_named(d.elements[0]);
  geo::Cylinder cyl;
  cyl.frame.origin = c;
  cyl.frame.z = f.d;
  cyl.frame.x = (tA - c).normalized();
  cyl.radius = radius;
  b.set_surface(sliver, cyl, f.convex);
  for (HalfedgeH h : b.loop_halfedges(b.outer_loop(sliver))) {
    Vec3 x = b.point(b.origin(h)), y = b.point(b.target(h));
    if (std::abs((y - x).normalized().dot(f.d)) > 0.5) continue;  // a long side: a line on A or B
    Vec3 centre = c + (x - c).dot(f.d) * f.d;
    set_circle(b, h, centre, (x - centre).cross(y - centre).normalized());
  }
  double theta = std::acos(std::clamp((tA - c).normalized().dot((tB - c).normalized()), -1.0, 1.0));
  d.size = radius * theta;  // the width
  return d;
}

KnownDefect notch(Body& b, EdgeH e, FaceH A, double s0, const std::vector<double>& lengths,
                  const std::vector<double>& wa, double wb0) {
  EdgeFrame f = edge_frame(b, e, A);
  if (!f.convex) throw Unsuitable(e.str() + " is not a convex edge");
  if (wa.size() != lengths.size() + 1) throw std::logic_error("notch: one width per cross section");
  double total = 0;
  for (double l : lengths) total += l;
  const double len = (f.q - f.p).norm();
  if (!(s0 > 0 && s0 + total < len)) throw Unsuitable("the notch does not fit on " + e.str());
  for (VertexH v : {b.origin(f.hA), b.target(f.hA)})
    if (b.degree(v) < 3) throw Unsuitable("an end of " + e.str() + " lies on too few edges");
  // Cross sections: a_i on A, b_i on B; each face along the edge is the plane through
  // a_i, b_i and a_{i+1}, which fixes b_{i+1} on B.
  std::vector<double> at{s0};
  for (double l : lengths) at.push_back(at.back() + l);
  std::vector<Vec3> pa, pb;
  pb.push_back(f.p + s0 * f.d + wb0 * f.uB);
  for (std::size_t i = 0; i < at.size(); ++i) pa.push_back(f.p + at[i] * f.d + wa[i] * f.uA);
  std::vector<std::pair<Vec3, Vec3>> floor;  // (point, normal) of each face along
  for (std::size_t i = 0; i + 1 < at.size(); ++i) {
    Vec3 n = (pb[i] - pa[i]).cross(pa[i + 1] - pa[i]);
    if (n.dot(f.nA + f.nB) < 0) n = -n;
    floor.push_back({pa[i], n.normalized()});
    auto x = meet3(pa[i], n, f.p, f.nB, f.p + at[i + 1] * f.d, f.d);
    if (!x) throw Unsuitable("the notch's faces do not meet");
    pb.push_back(*x);
  }
  for (std::size_t i = 0; i < pb.size(); ++i) {
    Vec3 r = pb[i] - (f.p + at[i] * f.d);
    if (!(r.dot(f.uB) > 0) || r.norm() > 4 * (wb0 + wa[0])) throw Unsuitable("the notch leaves face " + f.B.str());
  }
  // The edge loses [s0, s0 + total]; each side of that stretch is cut off its face along
  // a path through the cross sections, and the two strips, joined, are split across.
  SemvResult s1 = must(euler::semv(b, f.hA, f.p + s0 * f.d), "semv (notch)");
  must(euler::semv(b, s1.next, f.p + at.back() * f.d), "semv (notch)");
  HalfedgeH mid = s1.next;  // in A, from the notch's start to its end
  VertexH end = b.target(mid);
  cut_off(b, mid, pa);
  std::vector<Vec3> back(pb.rbegin(), pb.rend());
  cut_off(b, twin(mid), back);
  FaceH all = b.face(mid);
  must(euler::kef(b, mid), "kef (notch)");  // the strip in B joins the strip in A
  // Vertices of the cross sections, found by position in the strip's loop.
  auto vertex_near = [&](const Vec3& x) {
    for (VertexH v : b.loop_vertices(b.outer_loop(all)))
      if ((b.point(v) - x).norm() < 1e-9 * (1 + x.norm())) return v;
    throw std::logic_error("notch: lost a vertex");
  };
  std::vector<FaceH> chain;
  FaceH rest = all;
  for (std::size_t i = 0; i < at.size(); ++i) {
    VertexH va = vertex_near(pa[i]), vb = vertex_near(pb[i]);
    MefResult m = must(euler::mef(b, Corner::before(out_in_loop(b, va, b.outer_loop(rest))),
                                  Corner::before(out_in_loop(b, vb, b.outer_loop(rest)))),
                       "mef (notch)");
    // The new face is the side holding `start` on the first cut, and the side behind the
    // previous cut after that: whichever of the two does not hold `end`.
    bool new_has_end = false;
    for (VertexH v : b.loop_vertices(b.outer_loop(m.face))) new_has_end = new_has_end || v == end;
    FaceH piece = new_has_end ? rest : m.face;
    rest = new_has_end ? m.face : rest;
    set_line(b, m.edge);
    chain.push_back(piece);
  }
  chain.push_back(rest);
  // Planes: end walls square to the edge, the faces along through their cross sections.
  set_plane(b, chain.front(), f.p + at.front() * f.d, f.d);  // the material is behind it
  set_plane(b, chain.back(), f.p + at.back() * f.d, -f.d);
  for (std::size_t i = 0; i + 1 < at.size(); ++i) set_plane(b, chain[i + 1], floor[i].first, floor[i].second);
  KnownDefect d{ProblemType::small_face_chain, {}, 0.0};
  for (FaceH g : chain) {
    d.elements.push_back(g.str());
    d.size = std::max(d.size, polygon_area(loop_points(b, b.outer_loop(g))));
  }
  return d;
}

}  // namespace make

namespace {

// The Y-shaped face that replaces the three edges at convex corner v near v: tips `arm`
// along each edge, inner corners `width` inside both edges of each face.
struct YFace {
  FaceH face;
  std::vector<VertexH> tips, inner;
  Vec3 axis;
};

YFace y_face(Body& b, VertexH v, double arm, double width) {
  auto axis = convex_corner_axis(b, v);
  std::vector<HalfedgeH> outs = b.outgoing(v);
  if (!axis || outs.size() != 3) throw Unsuitable(v.str() + " is not a convex corner of three planar faces");
  const Vec3 P = b.point(v);
  std::vector<Vec3> dir;
  for (HalfedgeH o : outs) {
    if ((b.point(b.target(o)) - P).norm() < 3 * arm) throw Unsuitable("the arms do not fit at " + v.str());
    dir.push_back(dir_of(b, o));
  }
  YFace y;
  y.axis = *axis;
  // Edge o_i runs between face(o_i) and face(o_{i+1}); face(o_i) holds o_{i-1} and o_i.
  for (std::size_t i = 0; i < 3; ++i) y.tips.push_back(must(euler::semv(b, outs[i], P + arm * dir[i]), "semv (Y)").vertex);
  for (std::size_t i = 0; i < 3; ++i) {
    const std::size_t j = (i + 2) % 3;  // o_{i-1}
    FaceH f = b.face(outs[i]);
    const double sine = dir[i].cross(dir[j]).norm();
    const Vec3 k = P + (width / sine) * (dir[i] + dir[j]);
    // A path tips[i] -> k -> tips[j] inside f cuts its corner at v off.
    HalfedgeH after = b.next(outs[i]);  // leaves tips[i] in f
    MevResult s = must(euler::mev(b, Corner::before(after), k), "mev (Y)");
    MefResult m = must(euler::mef(b, Corner::before(s.y), Corner::before(twin(outs[j]))), "mef (Y)");
    b.set_surface(m.face, b.surface(f), b.same_sense(f));
    y.inner.push_back(s.vertex);
  }
  // The three corner pieces become one face, and v goes.
  must(euler::kef(b, outs[0]), "kef (Y)");
  must(euler::kef(b, outs[1]), "kef (Y)");
  y.face = b.face(outs[2]);
  must(euler::kev(b, twin(outs[2])), "kev (Y)");
  std::vector<VertexH> all = y.tips;
  all.insert(all.end(), y.inner.begin(), y.inner.end());
  refit_lines(b, all);
  return y;
}

}  // namespace

namespace make {

KnownDefect branched_sliver(Body& b, VertexH v, double arm, double width) {
  YFace y = y_face(b, v, arm, width);
  // Its plane holds the three tips; a Y cannot be planar (its inner corners lie on the
  // faces around it, off that plane by about the width): only its measure uses it.
  const std::vector<VertexH>& t = y.tips;
  Vec3 n = (b.point(t[1]) - b.point(t[0])).cross(b.point(t[2]) - b.point(t[0]));
  if (n.dot(y.axis) < 0) n = -n;
  set_plane(b, y.face, b.point(t[0]), n.normalized());
  return {ProblemType::sliver_face, {y.face.str()}, width};
}

KnownDefect corner_network(Body& b, VertexH v, double arm, double width) {
  YFace y = y_face(b, v, arm, width);
  // Chords between the inner corners: a middle triangle and one triangle per arm.
  std::vector<FaceH> faces{y.face};
  for (std::size_t i = 0; i < 3; ++i) {
    VertexH k1 = y.inner[i], k2 = y.inner[(i + 1) % 3];
    bool done = false;
    for (FaceH f : std::vector<FaceH>(faces)) {
      HalfedgeH h1 = out_in_loop(b, k1, b.outer_loop(f)), h2 = out_in_loop(b, k2, b.outer_loop(f));
      if (!h1.valid() || !h2.valid() || b.next(h1) == h2 || b.next(h2) == h1) continue;
      MefResult m = must(euler::mef(b, Corner::before(h1), Corner::before(h2)), "mef (network)");
      set_line(b, m.edge);
      faces.push_back(m.face);
      done = true;
      break;
    }
    if (!done) throw std::logic_error("corner network: no face holds both inner corners");
  }
  KnownDefect d{ProblemType::small_face_chain, {}, 0.0};
  for (FaceH f : faces) {
    fit_plane(b, f);
    d.elements.push_back(f.str());
    d.size = std::max(d.size, polygon_area(loop_points(b, b.outer_loop(f))));
  }
  return d;
}


namespace {
// A band round circle c: a cone (chamfer, into_cap and into_side) or a quarter torus
// (fillet of radius into_cap = into_side, tangent to both faces).
KnownDefect ring_band(Body& b, EdgeH c, double into_cap, double into_side, bool round) {
  // c: a circle, closed at one vertex v, between a cylinder's side A and a plane P square
  // to its axis (a cap, or a plate round a boss's foot); A's seam leaves v.
  HalfedgeH hc = halfedge_of(c, 0);
  if (b.origin(hc) != b.target(hc) || !std::holds_alternative<geo::Circle>(b.curve(c)))
    throw Unsuitable(c.str() + " is not a closed circle");
  if (std::holds_alternative<geo::Cylinder>(b.surface(b.face(twin(hc))))) hc = twin(hc);
  const FaceH A = b.face(hc), P = b.face(twin(hc));
  const auto* cyl = std::get_if<geo::Cylinder>(&b.surface(A));
  const auto* plane = P.valid() ? std::get_if<geo::Plane>(&b.surface(P)) : nullptr;
  if (!cyl || !plane) throw Unsuitable(c.str() + " is not between a cylinder and a plane");
  // By value: the surfaces' storage grows when mef makes the band below, and a pointer
  // into it then dangles (AddressSanitizer, Detect.NearOfOneTypeIsNearFilteredToIt).
  const double radius = cyl->radius;
  const Vec3 axis = cyl->frame.z.normalized();
  if (std::abs(std::abs(plane->frame.z.normalized().dot(axis)) - 1) > 1e-9)
    throw Unsuitable(c.str() + ": the plane is not square to the cylinder's axis");
  const VertexH v = b.origin(hc);
  const HalfedgeH seam = b.next(hc);  // v → the seam's other end, along A
  if (b.origin(seam) != v || !std::holds_alternative<geo::Line>(b.curve(edge_of(seam))) ||
      b.face(twin(seam)) != A)
    throw Unsuitable(c.str() + ": no seam of " + A.str() + " leaves " + v.str());
  const Vec3 pv = b.point(v), along = (b.point(b.target(seam)) - pv).normalized();
  if ((b.point(b.target(seam)) - pv).norm() < 4 * into_side) throw Unsuitable(A.str() + " is too short");
  const geo::Circle old = std::get<geo::Circle>(b.curve(c));
  // The direction hc runs round, and into P's interior from the circle: a cap lies inside
  // its outer circle, a plate outside the hole round a boss.
  const Vec3 about = hc == halfedge_of(c, 0) ? old.frame.z : Vec3(-old.frame.z);
  const Vec3 centre = old.frame.origin;
  const Vec3 radial = (pv - centre).normalized();
  const double inward = b.is_outer(b.loop(twin(hc))) ? -1.0 : 1.0;
  if (inward < 0 && old.radius < 4 * into_cap) throw Unsuitable(P.str() + " is too small");

  const SemvResult split = must(euler::semv(b, seam, pv + into_side * along), "semv (ring chamfer)");
  const VertexH v2 = split.vertex;  // on the seam, into_side from v
  // A's loop is [hc, seam, next, ..., twin(next), twin(seam)]: the new circle through v2
  // cuts [twin(seam), hc, seam] off as the band.
  const MefResult m = must(euler::mef(b, Corner::before(twin(seam)), Corner::before(split.next)), "mef (ring chamfer)");
  b.set_point(v, pv + inward * into_cap * radial);
  set_circle(b, hc, centre, about);
  set_circle(b, m.a, centre + into_side * along, about);
  set_line(b, edge_of(split.next));
  // The band: a cone through its two circles, or a torus whose tube touches the side
  // along the new circle and the plane along the moved one; its seam where A's is.
  geo::Surface band_surface;
  if (round) {
    geo::Torus torus;
    torus.frame.origin = centre + into_side * along;
    torus.frame.z = -along;
    torus.frame.x = radial;
    torus.major_radius = radius + inward * into_cap;
    torus.minor_radius = into_cap;
    band_surface = torus;
    // The seam along the tube: a quarter circle about the tube's centre.
    const Vec3 tube = torus.frame.origin + torus.major_radius * radial;
    const Vec3 n = (b.point(v) - tube).cross(b.point(v2) - tube);
    set_circle(b, seam, tube, n);
  } else {
    geo::Cone cone;
    cone.frame.origin = centre + into_side * along;
    cone.frame.z = -along;
    cone.frame.x = radial;
    cone.radius = radius;
    cone.half_angle = std::atan2(inward * into_cap, into_side);
    band_surface = cone;
    set_line(b, edge_of(seam));
  }
  const FaceH band = m.face;
  // Outward between A's and P's outward normals.
  const Vec3 mid = 0.5 * (b.point(v) + b.point(v2));
  auto outward = [&](FaceH f) {
    const geo::Surface& s = b.surface(f);
    return Vec3(geo::normal(s, geo::parameters(s, mid)) * (b.same_sense(f) ? 1.0 : -1.0));
  };
  const Vec3 want = outward(A) + outward(P);
  b.set_surface(band, band_surface, geo::normal(band_surface, geo::parameters(band_surface, mid)).dot(want) > 0);
  const double width = round ? 0.5 * M_PI * into_cap : std::hypot(into_cap, into_side);
  return {ProblemType::sliver_face, {band.str()}, width};
}
}  // namespace

KnownDefect ring_chamfer(Body& b, EdgeH c, double into_cap, double into_side) {
  return ring_band(b, c, into_cap, into_side, false);
}

KnownDefect ring_fillet(Body& b, EdgeH c, double radius) { return ring_band(b, c, radius, radius, true); }

}  // namespace make
}  // namespace kintsugi::zoo

namespace kintsugi::zoo {

namespace {

double straight_length(const Body& b, EdgeH e) {
  HalfedgeH h = halfedge_of(e, 0);
  return (b.point(b.target(h)) - b.point(b.origin(h))).norm();
}

bool planar_sides(const Body& b, EdgeH e) {
  HalfedgeH h = halfedge_of(e, 0);
  FaceH f = b.face(h), g = b.face(twin(h));
  return straight(b, e) && f.valid() && g.valid() && f != g && plane_of(b, f) && plane_of(b, g);
}

}  // namespace

std::vector<Maker> sliver_makers(const Body& b, const std::vector<EdgeH>& edges, double tol, Rng& rng) {
  std::vector<Maker> out;
  auto w = [&] { return tol * rng.uniform(0.1, 0.4); };  // a width well below the tolerance
  for (EdgeH e : edges) {
    if (!planar_sides(b, e)) continue;
    HalfedgeH h = halfedge_of(e, 0);
    if (b.degree(b.origin(h)) != 3 || b.degree(b.target(h)) != 3) continue;
    // A scanned chamfer or fillet rounds a real edge. Between two faces within 10° of one
    // plane (a face fitted twice, another defect) the chamfer plane meets its neighbours
    // ill-conditioned and the "sliver" came out 0.003 tolerances wide and a whole edge
    // long: a small face by area that no vertex can replace (found by
    // Beautify.InjectedDefectsOfTypes7To11AreRepaired).
    if (std::abs(outward_normal(b, b.face(h)).dot(outward_normal(b, b.face(twin(h))))) > std::cos(10 * M_PI / 180))
      continue;
    if (straight_length(b, e) < 10 * tol) continue;  // a sliver is long: area / diagonal < tol
    FaceH a = b.face(h);
    std::uint64_t kind = rng.below(3);
    // A fillet only where one fits (its ends are arcs on faces square to the edge): else a
    // chamfer, so a solid with no such edge (a pyramid) still gets a sliver wherever the
    // draw would have put a fillet on every edge.
    if (kind == 2) {
      try {
        if (!fillet_unsuitable(b, e, edge_frame(b, e, a)).empty()) kind = rng.below(2);
      } catch (const Unsuitable&) {
        kind = rng.below(2);
      }
    }
    const double w0 = w(), w1 = w(), w2 = w();
    if (kind == 0)
      out.push_back({[=](Body& x) { return make::chamfer(x, e, a, 0.7 * w0, 0.7 * w1); }, e.str()});
    else if (kind == 1)
      out.push_back({[=](Body& x) { return make::tapered_chamfer(x, e, a, 0.7 * w0, 0.7 * w1, 0.7 * w2); }, e.str()});
    else
      out.push_back({[=](Body& x) { return make::fillet(x, e, a, 0.6 * w0); }, e.str()});
  }
  return out;
}

std::vector<Maker> notch_makers(const Body& b, const std::vector<EdgeH>& edges, double tol, Rng& rng) {
  std::vector<Maker> out;
  for (EdgeH e : edges) {
    if (!planar_sides(b, e)) continue;
    const double len = straight_length(b, e);
    const std::size_t along = 1 + rng.below(3);  // chains of 3 to 5 faces
    std::vector<double> lengths, wa;
    double total = 0;
    for (std::size_t i = 0; i < along; ++i) total += lengths.emplace_back(tol * rng.uniform(0.3, 0.8));
    for (std::size_t i = 0; i <= along; ++i) wa.push_back(tol * rng.uniform(0.15, 0.4));
    const double wb = tol * rng.uniform(0.15, 0.4);
    if (len < total + 4 * tol) continue;
    const double s0 = rng.uniform(0.3, 0.7) * (len - total);
    FaceH a = b.face(halfedge_of(e, 0));
    out.push_back({[=](Body& x) { return make::notch(x, e, a, s0, lengths, wa, wb); }, e.str()});
  }
  return out;
}

}  // namespace kintsugi::zoo

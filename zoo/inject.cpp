// The defect injector: picks a suitable place for a defect type (or takes the one named
// by `at`), makes the defect inside a transaction, and keeps it only if the body is
// still valid and consistent (spec/defects.md).
#include "geometry/box.h"
#include "geometry/curve.h"
#include "geometry/tolerance.h"
#include "invariants/element_geometry.h"
#include "invariants/region_validity.h"
#include "invariants/topology_check.h"
#include "kernel/transaction.h"
#include "zoo/defects.h"
#include "zoo/defects_gaps.h"
#include "zoo/defects_pinch.h"
#include "zoo/defects_slivers.h"
#include "zoo/paper_build.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <functional>
#include <set>

namespace kintsugi::zoo {

namespace {

bool straight(const Body& b, EdgeH e) { return std::holds_alternative<geo::Line>(b.curve(e)); }

double edge_len(const Body& b, EdgeH e) {
  HalfedgeH h = halfedge_of(e, 0);
  const geo::Curve& c = b.curve(e);
  Vec3 p = b.point(b.origin(h)), q = b.point(b.target(h));
  if (const auto* circle = std::get_if<geo::Circle>(&c)) {
    geo::ParameterRange r = geo::parameter_range(c, p, q, 1e-12 * circle->radius);
    return (r.t1 - r.t0) * circle->radius;
  }
  if (std::holds_alternative<geo::Ellipse>(c) || std::holds_alternative<geo::BSplineCurve>(c)) {
    geo::ParameterRange r = geo::parameter_range(c, p, q, 1e-12);
    return geo::arc_length(c, r.t0, r.t1);
  }
  return (q - p).norm();
}

// Curves an edge can be split on or cut into pieces along (make::split_edge, cut_edge).
bool splittable(const geo::Curve& c) {
  return std::holds_alternative<geo::Line>(c) || std::holds_alternative<geo::Circle>(c) ||
         std::holds_alternative<geo::Ellipse>(c) || std::holds_alternative<geo::BSplineCurve>(c);
}

// A planar face with a convex outer loop and no rings, all edges straight.
bool convex_planar(const Body& b, FaceH f) {
  if (!plane_of(b, f) || b.next_in_face(b.outer_loop(f)).valid() || b.is_lone(b.outer_loop(f))) return false;
  Vec3 n = outward_normal(b, f);
  std::vector<HalfedgeH> hs = b.loop_halfedges(b.outer_loop(f));
  if (hs.size() < 3) return false;
  for (std::size_t i = 0; i < hs.size(); ++i) {
    if (!straight(b, edge_of(hs[i]))) return false;
    Vec3 d1 = b.point(b.target(hs[i])) - b.point(b.origin(hs[i]));
    HalfedgeH nx = hs[(i + 1) % hs.size()];
    Vec3 d2 = b.point(b.target(nx)) - b.point(b.origin(nx));
    if (!(n.dot(d1.cross(d2)) > 1e-12 * d1.norm() * d2.norm())) return false;
  }
  return true;
}

// Distance from x to the nearest edge line of f's outer loop (x inside a convex face).
double inset(const Body& b, FaceH f, const Vec3& x) {
  double best = 1e300;
  for (HalfedgeH h : b.loop_halfedges(b.outer_loop(f))) {
    Vec3 p = b.point(b.origin(h)), d = (b.point(b.target(h)) - p).normalized();
    Vec3 r = x - p;
    best = std::min(best, (r - r.dot(d) * d).norm());
  }
  return best;
}

Vec3 centroid(const Body& b, FaceH f) {
  Vec3 c = Vec3::Zero();
  std::vector<VertexH> vs = b.loop_vertices(b.outer_loop(f));
  for (VertexH v : vs) c += b.point(v);
  return c / double(vs.size());
}

struct Site {
  std::function<KnownDefect(Body&)> make;
  std::string where;
  // Where the designer's model is not the body before the defect (a pinch's block is a
  // feature the designer made flush): makes it from the body before the defect.
  std::function<void(Body&)> clean = {};
  // Tried only after every other site failed (in an order of their own), so that a site
  // kind added later leaves the choices made on bodies that have the earlier kinds as
  // they were: the Table 1 audit's saved recipes rebuild their models exactly.
  bool later = false;
};

template <class H>
std::optional<H> parse_handle(const std::string& s, char prefix) {
  if (s.size() < 2 || s[0] != prefix) return std::nullopt;
  std::uint64_t v = 0;
  for (std::size_t i = 1; i < s.size(); ++i) {
    if (s[i] < '0' || s[i] > '9' || v > 0xffffffffull) return std::nullopt;
    v = v * 10 + std::uint64_t(s[i] - '0');
  }
  if (v >= 0xffffffffull) return std::nullopt;
  return H(static_cast<typename H::Index>(v));
}

// All places in b where a defect of type t fits, each with its maker; sizes drawn from rng.
std::vector<Site> sites(const Body& b, ProblemType t, double tol, Rng& rng, const std::optional<std::string>& at,
                        std::string* why) {
  std::vector<FaceH> faces = b.faces();
  std::vector<EdgeH> edges = b.edges();
  std::vector<VertexH> vertices = b.vertices();
  if (at) {
    // Restrict the candidates to the named element (or, for a face, its edges and vertices).
    faces.clear(), edges.clear(), vertices.clear();
    if (auto f = parse_handle<FaceH>(*at, 'f'); f && b.alive(*f)) {
      faces = {*f};
      for (LoopH l : b.loops_of(*f))
        for (HalfedgeH h : b.loop_halfedges(l)) edges.push_back(edge_of(h)), vertices.push_back(b.origin(h));
    } else if (auto e = parse_handle<EdgeH>(*at, 'e'); e && b.alive(*e)) {
      edges = {*e};
    } else if (auto v = parse_handle<VertexH>(*at, 'v'); v && b.alive(*v)) {
      vertices = {*v};
    } else {
      *why = "'" + *at + "' names no live face (fN), edge (eN) or vertex (vN) of the model";
      return {};
    }
  }
  std::vector<Site> out;
  auto u = [&] { return rng.uniform(0.3, 0.8); };
  switch (t) {
    case ProblemType::face_gap:
    case ProblemType::edge_gap:
    case ProblemType::multi_face_gap:  // made the way a scanner makes them: zoo/defects_gaps.cpp
      for (GapSite& g : gap_sites(b, t, tol, rng, faces, edges, vertices)) out.push_back({std::move(g.make), g.where});
      break;
    case ProblemType::small_face:
    case ProblemType::small_face_chain:
      for (VertexH v : vertices) {
        if (!convex_corner_axis(b, v)) continue;
        std::uint64_t seed = rng.raw();
        double scale = u();
        if (t == ProblemType::small_face)
          out.push_back({[=](Body& x) {
                           Rng r(seed);
                           return make::small_face(x, v, 0.5 * tol * tol * scale, &r);
                         },
                         v.str()});
        else
          out.push_back({[=](Body& x) {
                           Rng r(seed);
                           return make::small_face_chain(x, v, 0.25 * tol * scale, r);
                         },
                         v.str()});
      }
      if (t == ProblemType::small_face_chain)
        for (Maker& m : notch_makers(b, edges, tol, rng)) out.push_back({std::move(m.make), m.where});
      break;
    case ProblemType::short_edge:
      for (VertexH v : vertices) {
        if (b.degree(v) < 4 || !convex_corner_axis(b, v)) continue;
        std::uint64_t seed = rng.raw();
        double len = tol * u();
        out.push_back({[=](Body& x) {
                         Rng r(seed);
                         try {
                           return make::apex_short_edge(x, v, len, r);
                         } catch (const Unsuitable&) {
                         }
                         for (HalfedgeH o : x.outgoing(v))
                           if (x.loop_halfedges(x.loop(o)).size() == 3) return make::tilt_short_edge(x, v, x.face(o), len);
                         throw Unsuitable(v.str() + " has no triangular face");
                       },
                       v.str()});
      }
      break;
    case ProblemType::sliver_face:
      for (Maker& m : sliver_makers(b, edges, tol, rng)) out.push_back({std::move(m.make), m.where});
      // A chamfer round a circle (a cylinder's end, a boss's foot): later sites, sized
      // without draws from rng (see Site::later), by a hash of the edge and the tolerance.
      for (EdgeH e : edges) {
        if (!std::holds_alternative<geo::Circle>(b.curve(e))) continue;
        std::uint64_t h = e.idx() * 0x9E3779B97F4A7C15ull ^ std::bit_cast<std::uint64_t>(tol);
        auto fraction = [&h] {
          h += 0x9E3779B97F4A7C15ull;
          std::uint64_t z = (h ^ (h >> 30)) * 0xBF58476D1CE4E5B9ull;
          z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
          return double((z ^ (z >> 31)) >> 11) * 0x1.0p-53;
        };
        const double into_cap = tol * (0.1 + 0.3 * fraction()), into_side = tol * (0.1 + 0.3 * fraction());
        if (fraction() < 0.5)
          out.push_back({[=](Body& x) { return make::ring_chamfer(x, e, into_cap, into_side); }, e.str(), {}, true});
        else  // a fillet whose width (a quarter circle) is as wide as a chamfer's
          out.push_back({[=](Body& x) { return make::ring_fillet(x, e, 0.6 * into_cap); }, e.str(), {}, true});
      }
      break;
    case ProblemType::same_geometry_faces:
      for (FaceH f : faces) {
        if (!convex_planar(b, f)) continue;
        std::vector<HalfedgeH> hs = b.loop_halfedges(b.outer_loop(f));
        if (hs.size() < 4) continue;
        bool corners3 = true;
        for (HalfedgeH h : hs) corners3 = corners3 && b.degree(b.origin(h)) == 3;
        if (!corners3) continue;
        // A scan fits a face twice only where the face is large enough to be fitted: a
        // face a few tolerances across (another defect's small face) is not split.
        geo::Box box;
        for (HalfedgeH h : hs) box.add(b.point(b.origin(h)));
        if (box.diagonal() < 10 * tol) continue;
        std::size_t i = rng.below(hs.size()), j = (i + 2 + rng.below(hs.size() - 3)) % hs.size();
        EdgeH e1 = edge_of(hs[i]), e2 = edge_of(hs[j]);
        // The split runs between the two edges' midpoints; passing within 2 tol of a
        // corner of the face it would also make a narrow piece (a pinch or a sliver: a
        // face split twice, the second line beside the first), another defect than the
        // one asked for (found by Beautify.InjectedDefectsOfTypes7To11AreRepaired).
        auto mid = [&](HalfedgeH h) { return (b.point(b.origin(h)) + b.point(b.target(h))) / 2; };
        const Vec3 m1 = mid(hs[i]), m2 = mid(hs[j]);
        bool narrow = false;
        for (HalfedgeH h : hs) {
          const Vec3 p = b.point(b.origin(h)), d = m2 - m1;
          const double s = std::clamp((p - m1).dot(d) / d.squaredNorm(), 0.0, 1.0);
          narrow = narrow || (p - (m1 + s * d)).norm() < 2 * tol;
        }
        if (narrow) continue;
        double dev = tol * u();
        out.push_back({[=](Body& x) { return make::split_and_tilt(x, f, e1, e2, dev); }, f.str()});
      }
      // A curved face split along a ruling, one surface on both halves (no draws from rng:
      // see Site::later).
      for (FaceH f : faces) {
        const geo::Surface& s = b.surface(f);
        if (!std::holds_alternative<geo::Cylinder>(s) && !std::holds_alternative<geo::Cone>(s)) continue;
        out.push_back({[=](Body& x) { return make::split_along_ruling(x, f, 2 * tol); }, f.str(), {}, true});
      }
      break;
    case ProblemType::mergeable_edges:
      for (EdgeH e : edges) {
        if (!splittable(b.curve(e))) continue;
        if (edge_len(b, e) < 4 * tol) continue;
        double at_ = rng.uniform(0.3, 0.7);
        out.push_back({[=](Body& x) { return make::split_edge(x, halfedge_of(e, 0), at_); }, e.str()});
      }
      break;
    case ProblemType::short_edge_chain:
      for (EdgeH e : edges) {
        if (!splittable(b.curve(e))) continue;
        double len = edge_len(b, e);
        std::vector<double> pieces(2 + rng.below(3));
        double total = 0;
        for (double& p : pieces) total += (p = tol * u());
        if (len < total + 4 * tol) continue;
        double start = rng.uniform(0.3, 0.7) * (len - total);
        out.push_back({[=](Body& x) { return make::cut_edge(x, halfedge_of(e, 0), start, pieces); }, e.str()});
      }
      break;
    case ProblemType::pinched_face:
      for (FaceH f : faces) {
        if (!convex_planar(b, f)) continue;
        double room = inset(b, f, centroid(b, f));
        for (HalfedgeH h : b.loop_halfedges(b.outer_loop(f))) {
          double len = edge_len(b, edge_of(h));
          // Fitted a little tapered: the block's near side is off0..off1 inside h.
          double offset = tol * u(), off1 = tol * u(), w = std::min(0.3 * room, 0.3 * len);
          if (w < 2 * tol) continue;
          double s0 = 0.35 * len, s1 = 0.65 * len;
          // The block must stay inside f: its far corners are checked against every edge.
          Vec3 p = b.point(b.origin(h)), d = (b.point(b.target(h)) - p).normalized();
          Vec3 uu = outward_normal(b, f).cross(d);
          Vec3 c0 = p + s0 * d + (std::max(offset, off1) + w) * uu, c1 = p + s1 * d + (std::max(offset, off1) + w) * uu;
          if (inset(b, f, c0) < tol || inset(b, f, c1) < tol) continue;
          make::PinchBlock k;
          k.s0 = s0, k.s1 = s1, k.off0 = offset, k.off1 = off1, k.height = w;
          out.push_back({[=](Body& x) { return make::pinch_bossing(x, h, k, w); }, f.str(),
                         [=](Body& x) { add_flush_block(x, h, k.s0, k.s1, std::max(k.off0, k.off1) + w, k.height); }});
        }
      }
      break;
  }
  if (out.empty() && why->empty())
    *why = std::string("no place in the model suits a ") + problem_name(t) + " of size below the tolerance " +
           std::to_string(tol) + (at ? " at " + *at : std::string());
  return out;
}

}  // namespace

std::optional<Injected> inject(Body& b, ProblemType t, std::uint64_t seed, const std::optional<std::string>& at,
                               double tolerance, std::string* error, Body* clean) {
  std::string why;
  auto fail = [&](const std::string& m) -> std::optional<Injected> {
    if (error) *error = m;
    return std::nullopt;
  };
  if (!(tolerance > 0) || !std::isfinite(tolerance)) return fail("the tolerance must be a positive number");
  Rng rng(seed);
  std::vector<Site> candidates = sites(b, t, tolerance, rng, at, &why);
  // Try the candidates in a random order; keep the first that leaves a valid body.
  const auto first_later =
      std::stable_partition(candidates.begin(), candidates.end(), [](const Site& s) { return !s.later; });
  auto shuffle = [&](auto from, auto to) {
    for (auto n = to - from; n > 1; --n) std::swap(from[n - 1], from[rng.below(std::size_t(n))]);
  };
  shuffle(candidates.begin(), first_later);
  shuffle(first_later, candidates.end());
  geo::Tolerances tols = geo::Tolerances::for_model(tolerance, model_size(b));
  // Loops that cross themselves or each other in a face's parameter domain: a defect made
  // by moving corners to where tilted planes meet can throw a corner across the face (a
  // split of a face beside an earlier split, whose planes are nearly parallel: found by
  // Beautify.InjectedDefectsOfTypes7To11AreRepaired). Only crossings the body did not
  // already have count against the defect.
  auto crossings = [&] {
    std::set<std::string> out;
    const std::vector<FaceH> fs = b.faces();
    for (const Violation& v : loop_violations(b, std::set<FaceH>(fs.begin(), fs.end()), tols)) out.insert(to_string(v));
    return out;
  };
  const std::set<std::string> crossed_before = candidates.empty() ? std::set<std::string>{} : crossings();
  std::string last;
  for (const Site& s : candidates) {
    Transaction tx(b);
    try {
      std::optional<Body> before;
      if (clean && s.clean) before = b;
      KnownDefect d = s.make(b);
      std::vector<Violation> bad = check_topology(b);
      std::vector<std::string> off = geometry_offences(b, tols.precision);
      if (bad.empty() && off.empty())
        for (const std::string& c : crossings())
          if (!crossed_before.count(c)) {
            off.push_back(c);
            break;
          }
      if (bad.empty() && off.empty() && before) {
        // The clean twin must be a consistent model too: a block made flush with the face
        // across an edge is one face with it only when that face is square to the block's
        // face (on a roof's slope the "designer" had a face off its own plane, and the
        // scan-parts score counted the repair's correct extra face as a failure).
        s.clean(*before);
        if (std::vector<std::string> twin = geometry_offences(*before, tols.precision); !twin.empty())
          off.push_back("the clean twin is not consistent: " + twin[0]);
      }
      if (bad.empty() && off.empty()) {
        if (before) *clean = std::move(*before);
        tx.commit();
        return Injected{d, std::string(problem_name(t)) + " at " + s.where + " (size " + std::to_string(d.size) + ")"};
      }
      last = s.where + ": " + (bad.empty() ? off[0] : to_string(bad[0]));
    } catch (const std::exception& e) {
      last = s.where + ": " + e.what();
    }
    tx.rollback();
  }
  if (!candidates.empty()) why = "no place suits a " + std::string(problem_name(t)) + " (last tried " + last + ")";
  return fail(why);
}

}  // namespace kintsugi::zoo

#include "repair/detect.h"

#include "invariants/region_validity.h"

#include "invariants/element_geometry.h"
#include "repair/detect_detail.h"
#include "repair/freeform_groups.h"
#include "repair/detect_threads.h"

#include <algorithm>
#include <cmath>
#include <set>
#include <thread>
#include <type_traits>

namespace kintsugi {

namespace detail {

DetectContext::DetectContext(const Body& body, const geo::Tolerances& t, Scope s, bool w)
    : b(body), tol(t), chordal(t.measure_chordal()), scope(std::move(s)), whole(w) {
  if (whole) {
    face_dense_.resize(b.face_slots());
    face_done_.assign(b.face_slots(), 0);
    length_dense_.assign(b.edge_slots(), -1.0);
  }
}

FaceInfo measure_face(const Body& b, FaceH f, const geo::Tolerances& tol, double chordal) {
  FaceInfo fi;
  std::optional<AreaAndBounds> m = face_area_and_bounds(b, f, chordal);
  if (!m) return fi;  // unmeasurable faces are neither small nor slivers
  fi.measured = true;
  fi.area = m->area;
  fi.bbox_diagonal = m->bounds.diagonal();
  fi.length = sliver_length(b, f, fi.bbox_diagonal, [&](EdgeH e) { return edge_length(b, e); });
  fi.small = m->area < tol.length * tol.length;
  fi.sliver = !fi.small && fi.length > 0 && m->area / fi.length < tol.length;
  return fi;
}

// Most faces are far from small and far from thin: a boundary sampled coarsely tells
// them apart as surely as one at 0.001 · length, with far fewer points (each projected
// onto the surface, then triangulated). The sampled boundary lies within the chordal
// error e of the true one, so a measure moves by at most the perimeter P times e in area
// and 2√3·e in the box diagonal; with a factor 4 for the parameter plane's distortion of
// the chords, a coarse area A and diagonal d with
//   A − 4P(e + e_fine) ≥ length²   and   (A − 4P(e + e_fine)) / (d + 4(e + e_fine)) ≥ length
// mean the fine measure finds the face neither small nor a sliver. Any other face (and
// every face reported, whose measure the report shows) is measured again finely.
// e is 0.05 · length, or P / (400 · loops) where that is larger: a face far larger than
// the tolerance is then sampled with a number of points that depends on its shape, not
// on the tolerance (a boss's circle at a fine tolerance took hundreds), and the bound
// above still holds with room (for one loop, 4P·P/400 is a sixth of a square's area;
// dividing by the loops keeps a plate's many rings from widening it). Both scale with
// the model, so scaling model and tolerance together changes nothing.
// On free-form surfaces the coarse pass also takes a coarser grid of Steiner points
// (8 × 8 cells over the region's parameter box instead of 16 × 16; measured, the grid's
// triangles were most of a B-spline face's measure whatever the chordal error). It
// integrates a smooth area element with a degree-5 rule, its error far inside the margin
// 4P·e above; and the bounds, from the grid's points and the boundary's, can miss a bulge
// between grid points by about cell² / (8 R) for a radius of curvature R, within 4e
// (≥ P/100) for faces up to about 20 R across.
constexpr int kCoarseFreeformGrid = 8;
namespace {
// The coarse pass's sampling step for f and f's perimeter (see above); `length` measures
// an edge (the context's cache, or element_geometry's edge_length).
struct CoarseStep {
  double chordal, perimeter;
};
template <class Length>
CoarseStep coarse_step(const Body& b, FaceH f, const geo::Tolerances& tol, Length length) {
  double perimeter = 0.0;
  std::size_t loops = 0;
  for (LoopH l = b.outer_loop(f); l.valid(); l = b.next_in_face(l)) {
    ++loops;
    b.for_each_halfedge(l, [&](HalfedgeH h) { perimeter += length(edge_of(h)); });
  }
  constexpr double kPerimeterShare = 400;
  return {std::max(tol.coarse_measure_chordal(), perimeter / (kPerimeterShare * double(std::max<std::size_t>(1, loops)))),
          perimeter};
}
}  // namespace

FaceInfo DetectContext::measure(FaceH f) const {
  const auto [coarse, perimeter] = coarse_step(b, f, tol, [&](EdgeH e) { return edge_length(e); });
  // The coarse step, then a tenth of it, and a tenth of that, while above the fine step:
  // a face far larger than the tolerance whose bound the coarse step leaves too wide (a
  // long strip or a ring: P²/100 above its area) is shown ordinary by a step between
  // rather than measured at the fine step, which on a face 10⁴ times the fine step across
  // costs a hundred times the points (OpenCASCADE's Bottom.brep: an 83-mm strip 2.3
  // tolerances wide, shown ordinary at a thousandth of the coarse step, cost a fifth of
  // its detection at the fine one). A face shown small or a sliver at a step goes to the
  // fine step from there.
  double step = coarse;
  for (; step > chordal && std::isfinite(step); step /= 10) {
    std::optional<AreaAndBounds> m = face_area_and_bounds(b, f, step, kCoarseFreeformGrid);
    if (!m) break;
    const double e = step + chordal;
    const double area_lo = m->area - 4 * perimeter * e;
    // A band's length (sliver_length) comes from its edges' lengths, not the sampling.
    auto length_of = [&](double diagonal) { return sliver_length(b, f, diagonal, [&](EdgeH x) { return edge_length(x); }); };
    const double diagonal_hi = length_of(m->bounds.diagonal() + 4 * e);
    const double t = tol.length;
    if (std::isfinite(area_lo) && area_lo >= t * t && area_lo >= t * diagonal_hi) {
      FaceInfo fi;
      fi.measured = true;
      fi.area = m->area;
      fi.bbox_diagonal = m->bounds.diagonal();
      fi.length = length_of(fi.bbox_diagonal);
      return fi;
    }
    // Small or a sliver whatever the step (the measure's upper bound fails): straight to
    // the fine step, which measures it for the report. Not on the raw measure: a coarse
    // step can lose nearly all of a strip's area (that strip of Bottom.brep measured
    // 3e-12 mm² at its coarse step).
    const double area_hi = m->area + 4 * perimeter * e;
    const double diagonal_lo = length_of(std::max(0.0, m->bounds.diagonal() - 4 * e));
    if (!(area_hi >= t * t && area_hi >= t * diagonal_lo)) break;
  }
  return measure_face(b, f, tol, chordal);
}

void DetectContext::know(FaceH f, const FaceInfo& fi) {
  if (whole) {
    face_dense_[f.idx()] = fi;
    face_done_[f.idx()] = 1;
  } else {
    face_sparse_[f.idx()] = fi;
  }
}

const FaceInfo& DetectContext::face(FaceH f) const {
  if (whole) {
    FaceInfo& fi = face_dense_[f.idx()];
    if (!face_done_[f.idx()]) {
      fi = measure(f);
      face_done_[f.idx()] = 1;
    }
    return fi;
  }
  auto it = face_sparse_.find(f.idx());
  if (it == face_sparse_.end()) it = face_sparse_.emplace(f.idx(), measure(f)).first;
  return it->second;
}

double DetectContext::edge_length(EdgeH e) const {
  if (whole) {
    double& l = length_dense_[e.idx()];
    if (l < 0) l = kintsugi::edge_length(b, e);
    return l;
  }
  auto it = length_sparse_.find(e.idx());
  if (it == length_sparse_.end()) it = length_sparse_.emplace(e.idx(), kintsugi::edge_length(b, e)).first;
  return it->second;
}

namespace {

// Runs work(i) for i in [0, n) on `threads` threads, each a contiguous block.
template <class F>
void in_blocks(std::size_t n, int threads, const F& work) {
  const std::size_t t = std::size_t(std::max(1, threads));
  std::vector<std::thread> pool;
  for (std::size_t k = 1; k < t; ++k)
    pool.emplace_back([&, k] {
      for (std::size_t i = n * k / t; i < n * (k + 1) / t; ++i) work(i);
    });
  for (std::size_t i = 0; i < n / t; ++i) work(i);
  for (std::thread& th : pool) th.join();
}

}  // namespace

void DetectContext::measure_ahead(int threads) {
  // Below this, starting threads costs more than it saves.
  constexpr std::size_t kMinElements = 512;
  if (!whole || threads <= 1) return;
  std::vector<EdgeH> edges;
  for (EdgeH e : scope.edges)
    if (!geo::is_freeform(b.curve(e))) edges.push_back(e);
  bool all_analytic = edges.size() == scope.edges.size();
  // Every analytic edge's length first (the faces' measures below read them, and none is
  // written while those threads run).
  in_blocks(edges.size(), edges.size() >= kMinElements ? threads : 1,
            [&](std::size_t i) { length_dense_[edges[i].idx()] = kintsugi::edge_length(b, edges[i]); });
  std::vector<FaceH> faces;
  for (FaceH f : scope.faces) {
    if (face_done_[f.idx()]) continue;  // known already (DetectContext::know)
    bool analytic = !geo::is_freeform(b.surface(f));
    for (LoopH l : b.loops_of(f))
      for (HalfedgeH h : b.loop_halfedges(l)) analytic = analytic && !geo::is_freeform(b.curve(edge_of(h)));
    if (analytic) faces.push_back(f);
    all_analytic = all_analytic && analytic;
  }
  measure_freeform_ahead(threads);
  if (faces.size() < kMinElements) return;
  in_blocks(faces.size(), threads, [&](std::size_t i) {
    face_dense_[faces[i].idx()] = measure(faces[i]);
    face_done_[faces[i].idx()] = 1;
  });
  // Every face and edge measured (the detectors' walks read the measures of elements
  // across the scope's edges too, which a whole-body scope holds): from here on the
  // context is only read.
  if (all_analytic) detector_threads_ = threads;
}

void DetectContext::measure_freeform_ahead(int threads) {
  // Groups below this many are measured as the detectors ask (a thread costs more).
  constexpr std::size_t kMinGroups = 32;
  std::vector<FaceH> faces;
  for (FaceH f : scope.faces) {
    if (face_done_[f.idx()]) continue;
    bool freeform = geo::is_freeform(b.surface(f));
    for (LoopH l : b.loops_of(f))
      for (HalfedgeH h : b.loop_halfedges(l)) freeform = freeform || geo::is_freeform(b.curve(edge_of(h)));
    if (freeform) faces.push_back(f);
  }
  const std::vector<std::vector<FaceH>> groups = evaluation_groups(b, faces);
  if (groups.size() < kMinGroups) return;
  prepare_freeform(b, faces);
  // Every edge length the measures read, first (they are cached as read).
  for (FaceH f : faces)
    for (LoopH l : b.loops_of(f))
      for (HalfedgeH h : b.loop_halfedges(l)) (void)edge_length(edge_of(h));
  for_each_grouped(groups, threads, [&](FaceH f) {
    face_dense_[f.idx()] = measure(f);
    face_done_[f.idx()] = 1;
  });
}

}  // namespace detail

namespace {

// The problems in the paper's order of types, counted by type.
Detection in_order(std::vector<Problem> problems) {
  Detection d;
  d.problems = std::move(problems);
  std::stable_sort(d.problems.begin(), d.problems.end(),
                   [](const Problem& a, const Problem& b) { return problem_order(a.type) < problem_order(b.type); });
  for (const Problem& p : d.problems) d.counts[std::size_t(problem_order(p.type) - 1)]++;
  return d;
}

// Runs detector(c, out, block) over `items` split into contiguous blocks, one per thread
// the context allows, and appends the blocks' problems in block order: what one thread
// over all of `items` would find, in the same order.
template <class H, class Detector>
void in_blocks_of(detail::DetectContext& c, const std::vector<H>& items, const Detector& detector,
                  std::vector<Problem>& out) {
  const std::size_t t = std::size_t(std::max(1, c.threads_for_detectors()));
  if (t == 1) {
    detector(c, out, std::span<const H>(items));
    return;
  }
  std::vector<std::vector<Problem>> found(t);
  // in_blocks over the t block numbers: block k on thread k.
  detail::in_blocks(t, int(t), [&](std::size_t k) {
    const std::size_t lo = items.size() * k / t, hi = items.size() * (k + 1) / t;
    detector(c, found[k], std::span<const H>(items).subspan(lo, hi - lo));
  });
  for (std::vector<Problem>& f : found) out.insert(out.end(), std::make_move_iterator(f.begin()), std::make_move_iterator(f.end()));
}

void pinched(detail::DetectContext& c, std::vector<Problem>& out) {
  in_blocks_of(c, c.scope.faces, [](auto& cc, auto& o, std::span<const FaceH> fs) { detail::detect_pinched(cc, o, fs); }, out);
}

// A pair of faces with several common edges may be found in two blocks: kept where the
// first block found it, as one thread would.
void same_geometry(detail::DetectContext& c, std::vector<Problem>& out) {
  std::vector<Problem> found;
  in_blocks_of(c, c.scope.edges, [](auto& cc, auto& o, std::span<const EdgeH> es) { detail::detect_same_geometry(cc, o, es); },
               found);
  std::set<std::vector<Element>> seen;
  for (Problem& p : found)
    if (seen.insert(p.elements).second) out.push_back(std::move(p));
}

Detection run(detail::DetectContext& c) {
  std::vector<Problem> all;
  detail::detect_gaps(c, all);
  pinched(c, all);
  detail::detect_small_and_sliver(c, all);
  detail::detect_short_edges(c, all);
  same_geometry(c, all);
  detail::detect_mergeable(c, all);
  return in_order(std::move(all));
}

// Which detector finds problems of type t: types with the same number share one.
int detector_of(ProblemType t) {
  switch (t) {
    case ProblemType::face_gap:
    case ProblemType::edge_gap:
    case ProblemType::multi_face_gap: return 0;
    case ProblemType::pinched_face: return 1;
    case ProblemType::small_face_chain:
    case ProblemType::sliver_face:
    case ProblemType::small_face: return 2;
    case ProblemType::short_edge_chain:
    case ProblemType::short_edge: return 3;
    case ProblemType::same_geometry_faces: return 4;
    case ProblemType::mergeable_edges: return 5;
  }
  return -1;
}

// The detector that finds problems of type t (each finds its types whatever the others
// found: they share the context's measures only).
void run_for(detail::DetectContext& c, ProblemType t, std::vector<Problem>& out) {
  switch (detector_of(t)) {
    case 0: detail::detect_gaps(c, out); break;
    case 1: pinched(c, out); break;
    case 2: detail::detect_small_and_sliver(c, out); break;
    case 3: detail::detect_short_edges(c, out); break;
    case 4: same_geometry(c, out); break;
    case 5: detail::detect_mergeable(c, out); break;
  }
}

template <class H>
std::vector<H> sorted(const std::unordered_set<H>& s) {
  std::vector<H> v(s.begin(), s.end());
  std::sort(v.begin(), v.end());
  return v;
}

}  // namespace

Detection detect(const Body& b, const geo::Tolerances& tol) {
  detail::Scope s{b.faces(), b.edges(), b.vertices(), b.border_cycles()};
  detail::DetectContext c(b, tol, std::move(s), true);
  c.measure_ahead(detect_threads());
  return run(c);
}

namespace {
Detection detect_types_in(detail::DetectContext& c, const std::vector<ProblemType>& types) {
  std::vector<Problem> all, wanted;
  std::set<int> ran;
  for (ProblemType t : types)
    if (ran.insert(detector_of(t)).second) run_for(c, t, all);
  for (Problem& p : all)
    if (std::find(types.begin(), types.end(), p.type) != types.end()) wanted.push_back(std::move(p));
  return in_order(std::move(wanted));
}
}  // namespace

Detection detect_types(const Body& b, const geo::Tolerances& tol, const std::vector<ProblemType>& types) {
  detail::Scope s{b.faces(), b.edges(), b.vertices(), b.border_cycles()};
  detail::DetectContext c(b, tol, std::move(s), true);
  c.measure_ahead(detect_threads());
  return detect_types_in(c, types);
}

Detection detect_types(const Body& b, const geo::Tolerances& tol, const std::vector<ProblemType>& types,
                       const std::vector<std::optional<AreaAndBounds>>& measured) {
  detail::Scope s{b.faces(), b.edges(), b.vertices(), b.border_cycles()};
  detail::DetectContext c(b, tol, std::move(s), true);
  const double t = tol.length;
  for (FaceH f : b.faces()) {
    if (f.idx() >= measured.size()) continue;
    detail::FaceInfo fi;
    if (const std::optional<AreaAndBounds>& m = measured[f.idx()]) {
      // As detail::measure_face decides.
      fi.measured = true;
      fi.area = m->area;
      fi.bbox_diagonal = m->bounds.diagonal();
      fi.length = detail::sliver_length(b, f, fi.bbox_diagonal, [&](EdgeH e) { return edge_length(b, e); });
      fi.small = m->area < t * t;
      fi.sliver = !fi.small && fi.length > 0 && m->area / fi.length < t;
    }
    c.know(f, fi);
  }
  c.measure_ahead(detect_threads());
  return detect_types_in(c, types);
}

void Neighbourhood::add_face(const Body& b, FaceH f, const std::vector<LoopH>* loops) {
  if (!b.alive(f)) return;
  const bool had = !faces.insert(f).second;
  if (had && !partial.count(f)) return;  // already whole
  if (loops) {
    partial.insert(f);
  } else {
    partial.erase(f);
  }
  for (LoopH l : loops ? *loops : b.loops_of(f)) {
    if (b.is_lone(l)) vertices.insert(b.lone_vertex(l));
    for (HalfedgeH h : b.loop_halfedges(l)) {
      edges.insert(edge_of(h));
      vertices.insert(b.origin(h));
      if (b.is_border(twin(h))) borders.insert(b.loop(twin(h)));
    }
  }
}

void Neighbourhood::add_elements_of(const Body& b, const Problem& p) {
  for (const Element& e : p.elements)
    std::visit(
        [&](auto h) {
          using H = decltype(h);
          if (!b.alive(h)) return;
          if constexpr (std::is_same_v<H, FaceH>) add_face(b, h);
          if constexpr (std::is_same_v<H, EdgeH>) edges.insert(h);
          if constexpr (std::is_same_v<H, VertexH>) vertices.insert(h);
          if constexpr (std::is_same_v<H, LoopH>)
            if (b.is_border(h)) borders.insert(h);
        },
        e);
}

namespace {
// Whether face f, changed only inside `box`, is neither small nor a sliver now and was
// neither before: whether an edge on it counts as short did not change anywhere on it
// (spec/problems.md, "A face with many loops"). Measured coarsely, as
// DetectContext::measure does first, with the same bound on the error (area within 4·P·e,
// diagonal within 4·e); false where that cannot tell. Its area before was at least the
// area now less what fits in the box (at most the box's diagonal squared), and its box
// diagonal at most the one now plus the box's. With a memo, bounds from an earlier
// measure, shrunk by every change since, serve while they still decide.
bool stays_ordinary(const Body& b, FaceH f, const geo::Box& box, const geo::Tolerances& tol, FaceBoundsMemo* memo,
                    FaceBoundsMemo::Bounds* bounds) {
  const double d = box.diagonal(), t = tol.length;
  auto decides = [&](const FaceBoundsMemo::Bounds& k) {
    return std::isfinite(k.area_lo) && k.area_lo >= t * t && k.area_lo >= t * k.diagonal_hi;
  };
  if (memo)
    if (auto it = memo->faces.find(f); it != memo->faces.end()) {
      it->second.area_lo -= d * d;
      it->second.diagonal_hi += d;
      if (decides(it->second)) return *bounds = it->second, true;
      memo->faces.erase(it);
    }
  const auto [coarse, perimeter] = detail::coarse_step(b, f, tol, [&](EdgeH e) { return edge_length(b, e); });
  const double chordal = tol.measure_chordal();
  std::optional<AreaAndBounds> m = face_area_and_bounds(b, f, coarse, detail::kCoarseFreeformGrid);
  if (!m) return false;
  const double e = coarse + chordal;
  const FaceBoundsMemo::Bounds k{m->area - 4 * perimeter * e - d * d, m->bounds.diagonal() + 4 * e + d};
  if (!decides(k)) return false;
  if (memo) memo->faces[f] = k;
  *bounds = k;
  return true;
}
}  // namespace

Neighbourhood neighbourhood(const Body& b, const Touched& t, const geo::Tolerances& tol, FaceBoundsMemo* memo) {
  if (memo)
    for (FaceH f : t.reshaped) memo->faces.erase(f), memo->loops.forget(f);
  Neighbourhood n;
  std::set<FaceH> seen;
  // A face with many loops whose surface stayed: its loops near the change only (see the
  // header; spec/problems.md, "Detecting near a repair").
  auto add = [&](FaceH f) {
    if (!b.alive(f) || !seen.insert(f).second) return;
    const bool reshaped = t.reshaped.count(f) != 0;
    const std::optional<geo::Box> box = reshaped ? std::nullopt : near_change(b, t.vertices, t.edges, f, tol);
    // With the memo, the index of the face's loops learns of every committed change to it
    // (whether this neighbourhood takes the face whole or not), as its contract requires.
    if (box && memo) memo->loops.committed(b, f, t.vertices, t.edges, loop_chordal(tol));
    FaceBoundsMemo::Bounds bounds{};
    if (box && stays_ordinary(b, f, *box, tol, memo, &bounds)) {
      n.ordinary[f] = bounds;
      const std::vector<LoopH> loops = memo && memo->loops.has(f)
                                           ? memo->loops.near(b, f, *box, t.vertices, t.edges, loop_chordal(tol))
                                           : loops_near(b, f, *box);
      n.add_face(b, f, &loops);
      return;
    }
    n.add_face(b, f);
  };
  auto add_faces_of_edge = [&](EdgeH e) {
    for (unsigned s = 0; s < 2; ++s) {
      FaceH f = b.face(halfedge_of(e, s));
      if (f.valid()) add(f);
    }
  };
  for (FaceH f : t.faces) add(f);
  for (EdgeH e : t.edges)
    if (b.alive(e)) add_faces_of_edge(e);
  for (VertexH v : t.vertices)
    if (b.alive(v))
      for (HalfedgeH h : b.outgoing(v)) add_faces_of_edge(edge_of(h));
  return n;
}

void drop_anchored(const Body& b, Neighbourhood& n, const std::vector<std::vector<Problem>*>& lists,
                   const std::vector<const Problem*>& grow_only) {
  // Anchoring is judged against n as it was (a problem sharing a face with a dropped one
  // is not itself changed by the repair), then against the grown n.
  std::vector<const Problem*> anchored;
  for (const std::vector<Problem>* list : lists)
    for (const Problem& p : *list)
      if (n.anchors(b, p)) anchored.push_back(&p);
  for (const Problem* p : grow_only)
    if (n.anchors(b, *p)) anchored.push_back(p);
  for (const Problem* p : anchored) n.add_elements_of(b, *p);
  for (std::vector<Problem>* list : lists) {
    std::vector<Problem> keep;
    for (Problem& p : *list)
      if (!n.anchors(b, p)) keep.push_back(std::move(p));
    *list = std::move(keep);
  }
}

bool Neighbourhood::anchors(const Body& b, const Problem& p) const {
  for (const Element& e : p.elements) {
    const bool dead = std::visit([&](auto h) { return !b.alive(h); }, e);
    if (dead) return true;
  }
  switch (p.type) {
    case ProblemType::face_gap:
    case ProblemType::edge_gap:
    case ProblemType::multi_face_gap:
      return borders.count(p.first<LoopH>()) != 0;
    case ProblemType::short_edge_chain:
    case ProblemType::short_edge:
      for (EdgeH e : p.all<EdgeH>())
        if (edges.count(e)) return true;
      return false;
    case ProblemType::mergeable_edges:
      return vertices.count(p.first<VertexH>()) != 0;
    default:  // pinched, small, sliver, chains of small faces, same geometry: their faces
      for (FaceH f : p.all<FaceH>())
        if (faces.count(f)) return true;
      return false;
  }
}

namespace {
// The scope a local detection starts from, in handle order (so results do not depend on
// hash order).
detail::Scope scope_of(const Neighbourhood& n) {
  return {sorted(n.faces), sorted(n.edges), sorted(n.vertices), sorted(n.borders)};
}
}  // namespace

namespace {
// A local detection's context, told what the neighbourhood knows of faces with many loops.
detail::DetectContext near_context(const Body& b, const geo::Tolerances& tol, const Neighbourhood& n) {
  detail::DetectContext c(b, tol, scope_of(n), false);
  // Neither small nor a sliver is all the detectors read of such a face; its area and box
  // diagonal stand in as the bounds that showed it.
  for (const auto& [f, k] : n.ordinary) {
    detail::FaceInfo fi;
    fi.measured = true;
    fi.area = k.area_lo;
    fi.bbox_diagonal = k.diagonal_hi;
    c.know(f, fi);
  }
  return c;
}
}  // namespace

Detection detect_near(const Body& b, const geo::Tolerances& tol, const Neighbourhood& n) {
  detail::DetectContext c = near_context(b, tol, n);
  return run(c);
}

std::vector<Problem> detect_near_of_type(const Body& b, const geo::Tolerances& tol, const Neighbourhood& n,
                                         ProblemType t) {
  detail::DetectContext c = near_context(b, tol, n);
  std::vector<Problem> all, mine;
  run_for(c, t, all);
  for (Problem& p : all)
    if (p.type == t) mine.push_back(std::move(p));
  return mine;
}

}  // namespace kintsugi

#include "repair/suggest_tolerance.h"

#include "geometry/tolerance.h"
#include "invariants/element_geometry.h"
#include "repair/detect.h"
#include "repair/detect_threads.h"
#include "repair/freeform_groups.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace kintsugi {

namespace {

// The probe: problems up to this fraction of the model's size are measured, for the
// sizes that are no single element's (pinch distances, surface deviations, chain totals).
constexpr double kProbe = 0.05;
// Sizes below this fraction of the model's size are noise, spurious at any tolerance
// (two faces on exactly the same surface, coincident vertices); gaps are searched above.
constexpr double kNoise = 1e-6;
// Boundaries are sampled this finely (a fraction of the model's size) for face measures.
constexpr double kChordal = 1e-5;
// A gap of this factor between consecutive sizes is wide: the spurious sizes below it
// are well apart from the features above.
constexpr double kWide = 10;
// How many sizes either side are kept as evidence.
constexpr std::size_t kEvidence = 5;
// Faces are measured on threads from this many groups (repair/freeform_groups.h).
constexpr std::size_t kMinGroupsForThreads = 32;

std::string fmt(double d) {
  std::ostringstream os;
  os.precision(3);
  os << d;
  return os.str();
}

// The size at which a problem found by the probe stops being one, for the problems whose
// measure is no single edge's length or face's width (those are collected from every
// element); < 0: not a size the tolerance decides. Chains are not: their elements are
// short or small one by one (a chain's total can exceed the tolerance). Gaps are border
// cycles, found at any tolerance; mergeable edges do not depend on it either.
double probe_size(const Problem& p) {
  return p.type == ProblemType::pinched_face || p.type == ProblemType::same_geometry_faces ? p.measure : -1;
}

// Every face's area and bounds (by face slot), on the threads detection may use
// (detect_threads), grouped by free-form evaluation state (repair/freeform_groups.h).
std::vector<std::optional<AreaAndBounds>> measure_faces(const Body& b, double chordal) {
  std::vector<std::optional<AreaAndBounds>> measured(b.face_slots());
  const std::vector<FaceH> faces = b.faces();
  prepare_freeform(b, faces);
  const std::vector<std::vector<FaceH>> groups = evaluation_groups(b, faces);
  // Below a few dozen faces a thread costs more than it saves.
  for_each_grouped(groups, groups.size() >= kMinGroupsForThreads ? detect_threads() : 1,
                   [&](FaceH f) { measured[f.idx()] = face_area_and_bounds(b, f, chordal); });
  return measured;
}

}  // namespace

ToleranceSuggestion suggest_tolerance(const Body& b) {
  ToleranceSuggestion s;
  const double size = model_size(b);
  if (!(size > 0)) {
    s.explanation = "the model has no extent";
    return s;
  }
  const double probe = kProbe * size, floor = kNoise * size;
  // Every element's own size, intended or not: an edge's length; a face's width
  // (area / bounding-box diagonal, the sliver measure) or, when smaller, the square root
  // of its area (the small-face measure). Intended features have to be measured too: a
  // gap can only be seen between the sizes on both of its sides.
  std::vector<SizeEvidence> sizes;
  // Where a face narrower than the tolerance stops reading as a sliver (an edge) and
  // reads as a small face (a vertex): the square root of its area. Not a size of a
  // feature: where it falls inside the gap, it only decides where in the gap to be.
  std::vector<std::pair<double, double>> readings;  // (sqrt area, width)
  for (EdgeH e : b.edges()) {
    // Along a gap: gaps are found by topology, not by size.
    if (b.is_border(halfedge_of(e, 0)) || b.is_border(halfedge_of(e, 1))) continue;
    sizes.push_back({"edge " + e.str() + " (length)", edge_length(b, e)});
  }
  // Kept for the probe below, which would measure every face again.
  const std::vector<std::optional<AreaAndBounds>> measured = measure_faces(b, kChordal * size);
  for (FaceH f : b.faces()) {
    const std::optional<AreaAndBounds>& m = measured[f.idx()];
    if (!m || !(m->area > 0)) continue;
    const double root = std::sqrt(m->area), width = m->area / std::max(m->bounds.diagonal(), 1e-300);
    sizes.push_back(width < root ? SizeEvidence{"face " + f.str() + " (width)", width}
                                 : SizeEvidence{"face " + f.str() + " (sqrt area)", root});
    if (width < root) readings.push_back({root, width});
  }
  // Only the types whose sizes are no single element's (probe_size): the other
  // detectors would be run at the probe's large tolerance for nothing.
  // The faces' measures above are finer than the probe's own (kChordal · size against
  // Tolerances::measure_chordal, 1e-3 of the probe's 5% of the size).
  static_assert(kChordal <= geo::Tolerances::kMeasureChordalRatio * kProbe);
  Detection d = detect_types(b, geo::Tolerances::for_model(probe, size),
                             {ProblemType::pinched_face, ProblemType::same_geometry_faces}, measured);
  for (const Problem& p : d.problems) {
    const double x = probe_size(p);
    if (x < 0) continue;
    std::string what = std::string(problem_name(p.type));
    for (const std::string& e : element_names(p)) what += " " + e;
    sizes.push_back({what + " (" + measure_name(p.measure_kind) + ")", x});
  }
  std::sort(sizes.begin(), sizes.end(), [](const SizeEvidence& a, const SizeEvidence& c) { return a.size < c.size; });
  // Noise sizes are spurious whatever the tolerance; the gap is searched above them.
  std::size_t first = 0;
  while (first < sizes.size() && sizes[first].size <= floor) ++first;
  if (sizes.size() - first < 2) {
    s.explanation = "the model has too few features above the noise level " + fmt(floor) + " to compare";
    return s;
  }
  // Gaps between consecutive sizes (as ratios), below the probe: features larger than
  // 5% of the model's size are intended (a model whose design features are all spurious
  // is not a model).
  std::vector<double> ratio;  // ratio[k]: between sizes[first + k] and the next
  for (std::size_t i = first; i + 1 < sizes.size() && sizes[i].size < probe; ++i)
    ratio.push_back(sizes[i + 1].size / sizes[i].size);
  // The boundary of the intended features is the highest wide gap (a factor 10): below
  // it, further wide gaps only part spurious sizes from each other (noise-level slivers
  // from defects at the scanner's scale). Without one, the widest gap.
  std::size_t k = ratio.size();
  for (std::size_t i = ratio.size(); i-- > 0 && k == ratio.size();)
    if (ratio[i] >= kWide) k = i;
  const bool wide = k < ratio.size();
  if (!wide)
    for (std::size_t i = 0; i < ratio.size(); ++i)
      if (k == ratio.size() || ratio[i] > ratio[k]) k = i;
  const std::size_t best = first + (k < ratio.size() ? k : 0);
  double r1 = k < ratio.size() ? ratio[k] : 0, r2 = 0;  // r2: the widest other gap that competes
  for (std::size_t i = wide ? k + 1 : 0; i < ratio.size(); ++i)
    if (i != k) r2 = std::max(r2, ratio[i]);
  s.ratio = r1;
  s.next_ratio = r2;
  const bool clear = r1 >= kWide && r1 >= 3 * r2;
  const bool fair = r1 >= 4 && r1 >= 1.5 * r2;
  const bool low = r1 >= 2 && r1 >= 1.5 * r2;
  const double smallest = sizes[first].size;
  if (!low) {
    if (smallest >= probe) {
      // Nothing is small: no feature to doubt.
      s.confidence = "no defects";
      s.tolerance = std::sqrt(floor * smallest);
      s.above = smallest;
      s.ratio = smallest / floor;
      for (std::size_t i = first; i < sizes.size() && s.intentional.size() < kEvidence; ++i) s.intentional.push_back(sizes[i]);
      s.explanation = "no feature is smaller than " + fmt(probe) + " (5% of the model's size): nothing looks spurious";
      if (first > 0) {
        // Defects at the noise level (a sliver a scanner's rounding left) are spurious at
        // any tolerance, and the suggestion repairs them: say so rather than "nothing".
        s.below = sizes[first - 1].size;
        for (std::size_t i = first; i-- > 0 && s.spurious.size() < kEvidence;) s.spurious.push_back(sizes[i]);
        s.explanation = std::to_string(first) + " size(s) up to " + fmt(s.below) + " are at the noise level (below " +
                        fmt(floor) + ", 1e-6 of the model's size) and spurious at any tolerance; above them no feature is "
                        "smaller than " + fmt(probe) + " (5% of the model's size)";
      }
      return s;
    }
    s.confidence = "none";
    s.explanation = "no clear gap between the sizes of features: the widest is a factor " + fmt(r1) + " (between " +
                    fmt(sizes[best].size) + " and " + fmt(sizes[best + 1].size) + "), the next a factor " + fmt(r2);
    return s;
  }
  s.below = sizes[best].size;
  s.above = sizes[best + 1].size;
  s.tolerance = std::sqrt(s.below * s.above);
  // A narrow face below the gap reads as a sliver (an edge) up to the square root of its
  // area and as a small face (a vertex) above it. When that reading lies in the gap, the
  // sizes do not decide it; the face's shape does: a long face (its area's root far
  // above its width, as sqrt(width x length) is for a rectangle) stays a sliver unless
  // the gap above the reading is wider still than the face is long (length / width);
  // a compact one (the root within a small factor of the width) reads as a small face.
  // The tolerance is kept between the readings so chosen, when they allow it.
  double lo = s.below, hi = s.above;
  for (const auto& [root, width] : readings) {
    if (!(root > s.below && root < s.above) || width > s.below) continue;
    const double length_over_width = (root / width) * (root / width);
    if (s.above / root < length_over_width)
      hi = std::min(hi, root);
    else
      lo = std::max(lo, root);
  }
  if (lo < hi) s.tolerance = std::sqrt(lo * hi);
  const std::size_t split = best + 1;  // sizes[0..split) are below the gap
  for (std::size_t i = split; i-- > 0 && s.spurious.size() < kEvidence;) s.spurious.push_back(sizes[i]);
  for (std::size_t i = split; i < sizes.size() && s.intentional.size() < kEvidence; ++i) s.intentional.push_back(sizes[i]);
  s.confidence = clear ? "high" : fair ? "medium" : "low";
  s.explanation = std::to_string(split) + " size(s) up to " + fmt(s.below) + " look spurious, the next is " + fmt(s.above) +
                  " (a gap of a factor " + fmt(r1) + "; " + (r2 == 0 ? std::string("no other gap below 5% of the model's size")
                                   : std::string(wide ? "the widest above it" : "the next widest") + " is a factor " + fmt(r2)) + ")";
  if (!s.trusted()) s.explanation += "; a narrow gap: not used unless given with --tol";
  return s;
}

}  // namespace kintsugi

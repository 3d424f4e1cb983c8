#include "repair/suggest_tolerance.h"

#include "geometry/tolerance.h"
#include "invariants/element_geometry.h"
#include "repair/detect.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace kintsugi {

namespace {

// The probe: features up to this fraction of the model's size are measured. Larger
// ones are intended (a model whose design features are all spurious is not a model).
constexpr double kProbe = 0.05;
// Sizes below this fraction of the model's size are noise, spurious at any tolerance
// (two faces on exactly the same surface, coincident vertices); the bottom of the range
// the gap is searched in.
constexpr double kNoise = 1e-6;
// How many sizes either side are kept as evidence.
constexpr std::size_t kEvidence = 5;

std::string fmt(double d) {
  std::ostringstream os;
  os.precision(3);
  os << d;
  return os.str();
}

// The size at which a problem stops being one (see the header); < 0: none (mergeable
// edges do not depend on the tolerance).
double deciding_size(const Problem& p, double probe) {
  switch (p.type) {
    case ProblemType::mergeable_edges: return -1;
    case ProblemType::small_face:
    case ProblemType::small_face_chain: return std::sqrt(std::max(p.measure, 0.0));
    case ProblemType::face_gap:
    case ProblemType::edge_gap:
    case ProblemType::multi_face_gap: return p.measure < probe ? p.measure : -1;  // larger: an opening
    default: return p.measure;
  }
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
  Detection d = detect(b, geo::Tolerances::for_model(probe, size));
  std::vector<SizeEvidence> sizes;
  for (const Problem& p : d.problems) {
    double x = deciding_size(p, probe);
    if (x < 0) continue;
    std::string what = std::string(problem_name(p.type));
    for (const std::string& e : element_names(p)) what += " " + e;
    sizes.push_back({what + " (" + (p.type == ProblemType::small_face || p.type == ProblemType::small_face_chain ? std::string("sqrt area") : std::string(measure_name(p.measure_kind))) + ")",
                     x});
  }
  std::sort(sizes.begin(), sizes.end(), [](const SizeEvidence& a, const SizeEvidence& c) { return a.size < c.size; });
  // Noise sizes are spurious whatever the tolerance; the gap is searched above them.
  std::size_t first = 0;
  while (first < sizes.size() && sizes[first].size <= floor) ++first;
  // Gaps between consecutive sizes, with the noise floor below and the probe above.
  std::vector<double> v{floor};
  for (std::size_t i = first; i < sizes.size(); ++i) v.push_back(sizes[i].size);
  v.push_back(probe);
  std::size_t best = 0;
  double r1 = 0, r2 = 0;
  for (std::size_t i = 0; i + 1 < v.size(); ++i) {
    double r = v[i + 1] / std::max(v[i], 1e-300);
    if (r > r1) {
      r2 = r1;
      r1 = r;
      best = i;
    } else if (r > r2) {
      r2 = r;
    }
  }
  s.ratio = r1;
  s.next_ratio = r2;
  s.below = best == 0 ? (first > 0 ? sizes[first - 1].size : 0.0) : v[best];
  s.above = v[best + 1];
  s.tolerance = std::sqrt(v[best] * v[best + 1]);
  // Evidence: sizes in sizes[] up to the gap are spurious, the rest intended.
  const std::size_t split = first + best;  // sizes[0..split) are below the gap
  for (std::size_t i = split; i-- > 0 && s.spurious.size() < kEvidence;) s.spurious.push_back(sizes[i]);
  for (std::size_t i = split; i < sizes.size() && s.intentional.size() < kEvidence; ++i) s.intentional.push_back(sizes[i]);
  const bool clear = r1 >= 10 && r1 >= 3 * r2;
  const bool fair = r1 >= 4 && r1 >= 1.5 * r2;
  if (!clear && !fair) {
    s.confidence = "none";
    s.explanation = "no clear gap between the sizes of features: the widest is a factor " + fmt(r1) +
                    " (between " + fmt(v[best]) + " and " + fmt(v[best + 1]) + "), the next a factor " + fmt(r2);
    return s;
  }
  if (split == 0) {
    s.confidence = "no defects";
    s.explanation = sizes.empty() ? "no feature is smaller than " + fmt(probe) + " (5% of the model's size): nothing looks spurious"
                                  : "nothing looks spurious: the smallest feature, " + fmt(s.above) + ", is a factor " + fmt(r1) +
                                        " above the noise level " + fmt(floor);
    return s;
  }
  s.confidence = clear ? "high" : "medium";
  s.explanation = std::to_string(split) + " feature(s) up to " + fmt(s.below) + " look spurious, the next is " +
                  fmt(s.above) + " (a gap of a factor " + fmt(r1) + "; the next widest is a factor " + fmt(r2) + ")";
  return s;
}

}  // namespace kintsugi

// The tolerance model (spec/tolerances.md).
//
// Two lengths, because the paper (section 3.1) needs one tolerance for *decisions*
// ("this face is small", "these edges have the same geometry") and the arithmetic
// needs a much smaller one for "this point lies on that surface":
//   length     the user's tolerance separating artefacts from intended features;
//   precision  modelling precision, length × 1e-6 by default, but never below
//              1e-12 × model size, so that it stays above floating-point noise for the
//              coordinates of a large model.
// Both scale with the model: scaling the model and the length tolerance by k scales
// both values by k, so every decision stays the same.
#pragma once

#include <algorithm>
#include <cmath>

namespace kintsugi::geo {

struct Tolerances {
  double length = 1e-3;
  double precision = 1e-9;

  // Ratio of the default precision to the length tolerance.
  static constexpr double kPrecisionRatio = 1e-6;
  // Smallest meaningful precision relative to the model size (double has ~16 digits;
  // we keep four for sums and differences of coordinates).
  static constexpr double kRelativeFloor = 1e-12;

  // `model_size` is the model's characteristic size: kintsugi::model_size(body)
  // (invariants/element_geometry.h), the one function that measures it.
  static Tolerances for_model(double length_tol, double model_size) {
    const double p = std::max(length_tol * kPrecisionRatio, kRelativeFloor * std::abs(model_size));
    return Tolerances{length_tol, p};
  }

  // The tolerance when the user gives none: 1e-3 × model size. Reverse-engineered
  // models are fitted to scans whose noise is around a thousandth of the part's size
  // (paper section 5 uses tolerances of that order); a model of size 0 gets 1e-3.
  static constexpr double kDefaultLengthRatio = 1e-3;
  static Tolerances default_for_model(double model_size) {
    const double t = model_size > 0 ? kDefaultLengthRatio * model_size : kDefaultLengthRatio;
    return for_model(t, model_size);
  }

  // ---- lengths derived from the tolerance (spec/tolerances.md, "Derived lengths") ----
  // Every other length a decision or a repair uses is one of these; none is written out
  // as a literal elsewhere.

  // Chordal error when sampling curved boundaries for a measure that a decision compares
  // with `length` (areas with length², lengths, widths, distances): 1e-3 · length. The
  // sampling error then moves a measure by about a thousandth of the decision's margin,
  // so no decision depends on it, while sampling stays coarse enough to be cheap.
  static constexpr double kMeasureChordalRatio = 1e-3;
  double measure_chordal() const { return kMeasureChordalRatio * length; }

  // Chordal error of detection's first, coarse measure of a face: 0.05 · length (about
  // seven times fewer boundary points than measure_chordal()). The face is measured again
  // at measure_chordal() unless the coarse measure, widened by its error bound, already
  // decides that it is neither small nor a sliver (repair/detect.cpp): the decisions are
  // the fine measure's.
  static constexpr double kCoarseMeasureChordalRatio = 0.05;
  double coarse_measure_chordal() const { return kCoarseMeasureChordalRatio * length; }

  // Chordal error of the boundary points that are compared with a surface (does a face
  // have the same geometry as its neighbour; how far a repaired edge is from its faces):
  // 0.1 · length. A point of the sampled boundary is then within 0.1 · length of the true
  // boundary, small against the `length` the deviation is compared with, and a face
  // gives few enough points for a least-squares fit.
  static constexpr double kProbeChordalRatio = 0.1;
  double probe_chordal() const { return kProbeChordalRatio * length; }

  // Chordal error of curves sampled only to bound the region they span (the box in which
  // two surfaces are intersected): `length` itself, since the box is then grown by
  // intersection_margin(), ten times more.
  double region_chordal() const { return length; }

  // Margin around that box: 10 · length (callers also add a quarter of the box's size).
  // A new edge's curve lies within max_vertex_move() of the old edge's vertices, well
  // inside; a branch further away is not the edge's and is rejected anyway.
  static constexpr double kIntersectionMarginRatio = 10;
  double intersection_margin() const { return kIntersectionMarginRatio * length; }

  // Chordal accuracy of marched intersection curves (geo::IntersectOptions): 0.01 · length,
  // ten times finer than the probes that compare them with the faces' surfaces.
  static constexpr double kIntersectionChordalRatio = 0.01;
  double intersection_chordal() const { return kIntersectionChordalRatio * length; }

  // The largest distance a repair may move a vertex when it collapses a feature (short
  // edge, small face): 2 · length. The vertex travels across the feature (shorter than
  // `length`) and then to where the fitted surfaces actually meet (within `length` of the
  // feature, or the surfaces would not be a repair's to join); more is a different model.
  // An edge's curve derived anew after a repair may stray from where the edge was by as
  // much and no more (repair/beautify_geometry.cpp, strays_from).
  static constexpr double kMaxVertexMoveRatio = 2;
  double max_vertex_move() const { return kMaxVertexMoveRatio * length; }

  // The largest distance a vertex may slide when faces of the same geometry are merged
  // and it moves onto the common surface: `length`, the deviation the faces were allowed.
  double max_refit_move() const { return length; }

  // Chordal error for the polygon whose turn decides a planar face's sense in the
  // geometric check, which only knows the precision: 1e5 · precision (0.1 · length at
  // the default ratio). The sense of a polygon changes only when the sampling error is
  // comparable to the face's size, and faces smaller than `length` are a repair's work.
  static constexpr double kOrientationChordalRatio = 1e5;
  static double orientation_chordal(double precision) { return kOrientationChordalRatio * precision; }
};

}  // namespace kintsugi::geo

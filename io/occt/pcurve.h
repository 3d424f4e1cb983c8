// The curve in a free-form face's parameter plane (pcurve) of an edge on it, by our own
// projection, for the writer (to_occt.cpp). ShapeFix_Wire would project every sample by
// ShapeAnalysis_Surface::ValueOfUV's grid search: measured, most of writing a B-spline
// part (a second for OpenCASCADE's terrain.brep, one face).
#pragma once

#include "geometry/types.h"

#include <Geom2d_Curve.hxx>
#include <Geom_Curve.hxx>
#include <Geom_Surface.hxx>

namespace kintsugi::io::occt {

// The pcurve of curve `c` over [t0, t1] on `s` (`gs`: the same surface as OpenCASCADE's
// object), parameterised like `c`. The curve is sampled (4 per C2 span, at least 9), each
// sample projected (geo::parameters: Newton from the last foot) and continued across the
// seam of a periodic surface. It is cut where it is less smooth (the bounds of its C2
// spans) and where its feet cross a parameter line along which the surface is (a double
// knot of a bicubic B-spline; found by a secant search between samples), and a 2D
// B-spline interpolated through the samples of each piece; a piece is kept when, at a
// quarter, half and three quarters of every interval between samples, the surface at the
// pcurve's point is near enough the foot of the curve's point, else made again with
// twice the samples, up to 1025 (4100 over all pieces). The pieces are joined with a
// knot of multiplicity 3 where they meet. Near enough is `within` for a curve on the surface (every
// sample within `within` of it) and the curve's own distance for one clearly off it (a
// sample farther than 4 `within`, twice the edge's tolerance when `within` is half of it):
// BRepCheck reports such an edge off its face whatever its pcurve, and feet held at a
// bound of the domain turn where the curve leaves it, a corner no sampling follows to
// `within`. Null for a curve near the surface but not on it (ShapeFix's pcurve can pass
// where the curve's own miss leaves the feet's no room), a foot at a degenerate point of
// the surface (|S_u x S_v| vanishing: a pole's parameters are not the point's), or no
// sampling passing: the caller then leaves the edge to ShapeFix.
Handle(Geom2d_Curve) projected_pcurve(const geo::Surface& s, const Handle(Geom_Surface)& gs, const Handle(Geom_Curve)& c,
                                     double t0, double t1, double within);

// The same, remembered: the last few hundred answers, by the surface, the edge's own curve
// `of` (from which `c` was made), c's ends, t0, t1 and `within` — the answer is a function
// of these alone. The validity gate writes the touched region again for every repair it
// judges, so the same edges of a free-form face's boundary were projected again and again
// (a fifth of beautify's time on OpenCASCADE's linkrods.step).
Handle(Geom2d_Curve) projected_pcurve_remembered(const geo::Surface& s, const geo::Curve& of,
                                                const Handle(Geom_Surface)& gs, const Handle(Geom_Curve)& c,
                                                double t0, double t1, double within);

}  // namespace kintsugi::io::occt

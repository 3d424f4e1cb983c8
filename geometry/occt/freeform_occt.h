// The free-form backend (geometry/freeform.h) on OpenCASCADE's geometry classes, and the
// exact conversions between our free-form data and OpenCASCADE's objects. Compiled into
// kintsugi_occt (geometry/ itself never links OpenCASCADE).
#pragma once

#include "geometry/types.h"

#include <Geom_BSplineCurve.hxx>
#include <Geom_BSplineSurface.hxx>
#include <Geom_Curve.hxx>
#include <GeomAdaptor_Surface.hxx>
#include <Geom_Surface.hxx>

#include <optional>
#include <string>

namespace kintsugi::geo::occt {

// Registers the backend (idempotent). The CLI calls it at start-up; import_cad too.
void register_freeform_backend();

// Exact conversions. `to_bspline` of a curve or surface that is not a B-spline converts it
// with GeomConvert (exact for conics and surfaces of revolution and extrusion; a curve or
// surface unbounded in a direction must be trimmed first). nullopt with *why on failure.
BSplineCurve bspline_data(const Handle(Geom_BSplineCurve)& c);
BSplineSurface bspline_data(const Handle(Geom_BSplineSurface)& s);
std::optional<BSplineCurve> to_bspline(const Handle(Geom_Curve)& c, std::string* why);
std::optional<BSplineSurface> to_bspline(const Handle(Geom_Surface)& s, std::string* why);

// Loads `a` with `s` to evaluate it from its span cache: when its bounds are finite and
// not empty, with bounds a hair (1e-9 of the range) outside them, since the adaptor
// evaluates a point exactly on one of its bounds by de Boor's algorithm
// (Geom_BSplineSurface::LocalD1, the span inside the bounds) rather than from the cache,
// and projections clamped to the bounds land exactly there. At the surface's own ends the
// cache's span is that same inside span. True when the bounds are finite.
bool load_for_evaluation(GeomAdaptor_Surface& a, const Handle(Geom_Surface)& s);

// Our free-form geometry as OpenCASCADE objects (built from the data, cached on it).
Handle(Geom_Surface) geom_surface(const Surface& s);  // free-form alternatives only; null otherwise
Handle(Geom_Curve) geom_curve(const Curve& c);        // BSplineCurve only; null otherwise

// How the projections onto a free-form surface went (geo::closest_point and the
// parameters of its points): how many there were, how many did not follow the last foot
// and searched the seed grid, and how many of those found no foot there and were left to
// ShapeAnalysis_Surface::ValueOfUV (a costly grid search; its memo's hits not counted),
// and how many were answered by the nearest seed instead, being over a thousand times
// the surface's extent away from it.
struct ProjectionCounts {
  long projections = 0, seeded = 0, value_of_uv = 0, far = 0;
};
ProjectionCounts projection_counts(const Surface& s);

}  // namespace kintsugi::geo::occt

// Swept surfaces that are elementary ones exactly: a circle or a line revolved about an
// axis in its plane (torus, sphere, cylinder, cone, plane) or a line or a circle extruded
// (plane, cylinder). A modeller that revolves a sketch writes a rounded ridge as a
// surface of revolution of an arc (OpenCASCADE's BRepPrimAPI_MakeRevol does), which is a
// torus; recognised, it is repaired like one instead of refused as free-form.
// OpenCASCADE's ShapeCustom_Surface recognises B-splines as planes, cylinders, cones and
// spheres, but not tori, and not from the swept surface's own data.
#pragma once

#include <Geom_Surface.hxx>

namespace kintsugi::io::occt {

// The elementary surface `s` is, over the parameter box [u0, u1] x [v0, v1], within `tol`
// (checked on a grid of points of `s`), or a null handle. Only swept surfaces (surfaces of
// revolution and of linear extrusion) are considered; its parametrisation is not `s`'s.
Handle(Geom_Surface) swept_elementary(const Handle(Geom_Surface)& s, double u0, double u1, double v0, double v1,
                                      double tol);

}  // namespace kintsugi::io::occt

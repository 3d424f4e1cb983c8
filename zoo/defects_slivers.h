// Makers of slivers and of small-face chains along an edge (zoo/defects_slivers.cpp),
// and the sites the injector offers for them.
#pragma once

#include "zoo/defects.h"

#include <functional>
#include <string>
#include <vector>

namespace kintsugi::zoo {

namespace make {

// sliver_face: a chamfer plane along straight edge e (between planar faces A and B, both
// ends of degree 3) cutting wa0 into A and wb0 into B at e's start and wa1 into A at its
// end: wider at one end.
KnownDefect tapered_chamfer(Body& b, EdgeH e, FaceH A, double wa0, double wb0, double wa1);

// sliver_face: a cylindrical fillet of `radius` along e, tangent to A and B (material
// taken off a convex edge, added to a concave one); the faces at e's ends must be square
// to it (its ends are circular arcs). size = the fillet's width (arc length).
KnownDefect fillet(Body& b, EdgeH e, FaceH A, double radius);

// sliver_face round a circle: closed circle c between a cylinder's side and a plane square
// to its axis (a cap, or a plate round a boss's foot) chamfered into a cone band,
// `into_cap` into the plane and `into_side` along the cylinder (a scanned chamfer of a
// turned part's edge). size = the band's width.
KnownDefect ring_chamfer(Body& b, EdgeH c, double into_cap, double into_side);
// The same rounded: a quarter torus of `radius` tangent to the side and the plane (a
// scanned fillet). size = its width (arc length).
KnownDefect ring_fillet(Body& b, EdgeH c, double radius);

// small_face_chain: a notch along convex edge e starting `s0` from its start (in A's
// direction): an end wall, lengths.size() faces along the edge (the i-th cross section
// cuts wa[i] into A; the first wb0 into B), an end wall. The chain has lengths.size() + 2
// faces.
KnownDefect notch(Body& b, EdgeH e, FaceH A, double s0, const std::vector<double>& lengths,
                  const std::vector<double>& wa, double wb0);

// sliver_face, branched (paper 7, Figure 32(a)): the three edges at convex corner v (three
// planar faces) replaced near v by one Y-shaped face, `arm` long along each edge and
// `width` into each face. Not consistent: its plane holds the three tips, but its inner
// corners lie off it (a Y along three edges cannot be planar), so only tests that build
// it on purpose use it, not the injector.
KnownDefect branched_sliver(Body& b, VertexH v, double arm, double width);

// small_face_chain, a network (paper 7): the same Y split by chords between its inner
// corners into a middle triangle and one triangle per arm, each on the plane through its
// corners (consistent): four small faces whose adjacency is a star. arm and width small
// enough that each is below tol².
KnownDefect corner_network(Body& b, VertexH v, double arm, double width);

}  // namespace make

struct Maker {
  std::function<KnownDefect(Body&)> make;
  std::string where;
};

// Sliver sites on `edges` (a chamfer, a tapered chamfer or a fillet, 0.1-0.4 tol wide)
// and notch sites for chains (3 to 5 faces), sizes drawn from rng.
std::vector<Maker> sliver_makers(const Body& b, const std::vector<EdgeH>& edges, double tol, Rng& rng);
std::vector<Maker> notch_makers(const Body& b, const std::vector<EdgeH>& edges, double tol, Rng& rng);

}  // namespace kintsugi::zoo

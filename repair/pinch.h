// Closing a pinch (paper 4.2): the two sides of a face that come closer than the
// tolerance are made to meet, in a new vertex or along a new edge, with Euler operators.
// Used by pass 4 (repair/pass_pinched_face.cpp).
#pragma once

#include "geometry/tolerance.h"
#include "kernel/body.h"
#include "repair/beautify_detail.h"

#include <string>

namespace kintsugi::detail {

// Closes the pinch of face f between its edges ea and eb (each has a side in f).
//
// Where the two sides run side by side (straight sides, or a spike) they are zipped:
// each is split where the other side stops being close, the split points are joined
// across the pinch (mef in one loop, mekr between loops: the loops become one), the thin
// strip between them becomes its own face, its short sides are collapsed (kev) and it is
// killed across one side (kef): the other side is then the edge between the faces that
// were across the two sides. Where they only come close at a narrowest place (a curved
// side, or sides at an angle), each side is split there and the two split points are
// joined and collapsed into one new vertex (paper: "making the appropriate pair of edges
// next to it, one from either side, meet in a new vertex").
//
// Necking therefore splits the face (a new face), spiking collapses the stretch at the
// spike's end (the end faces lose those short edges), bossing joins the ring to the outer
// loop. New vertices go where the faces around them meet; edges at them get curves from
// their faces. Returns "" or why not; the caller's transaction rolls back on failure.
std::string close_pinch(Body& b, FaceH f, EdgeH ea, EdgeH eb, const geo::Tolerances& tol, Touched& touched);

// The constraint the paper's Figure 32(b) breaks: a pinch against a circular edge puts a
// vertex on that circle. With the contacts the circle already has and the pinches still
// pending against it, more than three points that do not lie on one circle (within the
// precision) cannot all be on it. Returns that reason, or "".
std::string circle_contact_conflict(const Body& b, FaceH f, EdgeH circle_edge, const geo::Tolerances& tol);

}  // namespace kintsugi::detail

// Pinched faces the way reverse engineering makes them (paper 4.2, issue 14): a block
// whose side should be flush with a side of the face it stands on, fitted a fraction of
// the tolerance inside it (and slightly tapered: the offset runs from off0 to off1 along
// it), so the face it stands on keeps a strip narrower than the tolerance there. Each in
// the paper's three locations; `kink` makes the block's near side two faces (the
// "complex" configuration: several edges on one side of the pinch). Each has a clean
// twin: the block flush, its near face one face with the face across the edge.
//
// The face the block stands on is planar; h is a straight edge of it (its half-edge in
// that face), s is arc length from origin(h) and "in" is the distance from h's line into
// the face.
#pragma once

#include "zoo/defects.h"

namespace kintsugi::zoo::make {

struct PinchBlock {
  double s0 = 0, s1 = 0;        // where along h
  double off0 = 0, off1 = 0;    // the near side's distance from the edge it should be flush with
  bool kink = false;            // near side bent in the middle (two faces), offset there (off0+off1)/2 + kink_bump
  double kink_bump = 0;
  double height = 1;
};

// Bossing: a block [s0, s1] x [off, off + w] inside the face: a ring of it, its near side
// off0..off1 from h. Clean twin: add_flush_block(h, s0, s1, off + w, height).
KnownDefect pinch_bossing(Body& b, HalfedgeH h, const PinchBlock& k, double w);

// Necking: a block standing flush on h (its face over h one face with the face across h)
// over [s0, s1], reaching across the face to off0..off1 short of the opposite edge, which
// is parallel to h at distance `across`: the face is almost cut in two.
KnownDefect pinch_necking(Body& b, HalfedgeH h, const PinchBlock& k, double across);
// Clean twin: the block reaches the opposite edge and is flush there too (the face is cut
// in two).
void pinch_necking_clean(Body& b, HalfedgeH h, const PinchBlock& k, double across);

// Spiking: a block standing flush on h from s0 (< t) to s1, `depth` deep, in the corner
// at origin(h); its side towards the previous edge of the loop (which must be at right
// angles to h) is off0..off1 inside that edge (off0 = s0): a spike of the face runs
// between them, ending in the short stretch [0, s0] of h.
KnownDefect pinch_spiking(Body& b, HalfedgeH h, const PinchBlock& k, double depth);
// Clean twin: the block fills the corner, flush with both edges.
void pinch_spiking_clean(Body& b, HalfedgeH h, const PinchBlock& k, double depth);

}  // namespace kintsugi::zoo::make

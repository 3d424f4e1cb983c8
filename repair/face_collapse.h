// Collapsing a face onto edges: what passes 5 (chains of small faces) and 6 (sliver
// faces) share. Both replace a thin or tiny region of the surface by a graph of edges and
// let the faces around it meet along that graph (paper 4.3, 4.4; branched slivers and
// networks, paper section 7). Topology only through Euler operators; geometry is left
// to the caller (place_vertices).
#pragma once

#include "geometry/tolerance.h"
#include "kernel/body.h"

#include <string>
#include <utility>
#include <vector>

namespace kintsugi::detail {

// Why face f cannot be collapsed at all (rings, a gap or a seam along it), or "".
std::string collapsible(const Body& b, FaceH f);

// Joins away the vertices of f's outer loop that lie on no other edge (jekv): they have
// nothing that must survive, and the paper's edge sequence passes only through vertices
// "which are also connected to some other edge". Returns "" or why not.
std::string drop_bare_vertices(Body& b, FaceH f);

// Collapses face f (outer loop only, every vertex on another edge) onto a plane tree
// spanning the vertices of its loop: `tree` lists its edges as vertex pairs; pairs that
// are already joined by an edge of the loop keep that edge, the others become chords
// (mef). Each piece the chords cut f into then borders exactly one edge of the loop
// outside the tree, and is killed across it (kef) into the face beyond; the tree's edges
// are left separating the faces on either side. A junction vertex not on the loop
// (a branched sliver) is given as `junction` with its position: it is made first, as a
// strut from its first tree neighbour (mev), and it must have two or more tree edges.
// Returns "" or why not (the caller's transaction rolls back).
std::string collapse_onto_tree(Body& b, FaceH f, const std::vector<std::pair<VertexH, VertexH>>& tree,
                               VertexH* junction = nullptr, const geo::Vec3& junction_at = geo::Vec3::Zero());

// Whether the chords of `path` (consecutive pairs not adjacent on the loop) cross, for
// vertices in loop order `loop`: a path whose chords cross has no plane embedding in f.
bool chords_cross(const std::vector<VertexH>& loop, const std::vector<std::pair<VertexH, VertexH>>& tree);

}  // namespace kintsugi::detail

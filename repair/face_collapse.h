// Collapsing a face onto edges: what passes 5 (chains of small faces) and 6 (sliver
// faces) share. Both replace a thin or tiny region of the surface by a graph of edges and
// let the faces around it meet along that graph (paper 4.3, 4.4; branched slivers and
// networks, paper section 7). Topology only through Euler operators; geometry is left
// to the caller (place_vertices).
#pragma once

#include "geometry/tolerance.h"
#include "kernel/body.h"
#include "repair/touched.h"

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

// Replaces face f (an outer loop only, every neighbour across it a face) by one vertex
// where the faces around it meet (pass 9, paper 4.6). Topology: kev along f's loop until
// it has two edges, kef to kill f across one of them, kev of the last; the vertex goes to
// the neighbours' meeting point (place_vertices, from the centroid of f's vertices) and
// the edges at it get curves through it. Refused when a neighbour would be left with
// fewer than three sides. Returns "" or why not.
std::string collapse_to_vertex(Body& b, FaceH f, const geo::Tolerances& tol, Touched& touched);

// Joins a patch of small faces whose adjacency has a cycle (three small triangles round a
// cut corner) into one face: kef across the edges between them, kev of the struts this
// leaves inside it, jekv of vertices on no other edge. Refused when the patch is not a
// disc (it encloses something, or its faces meet along more than one stretch). Returns
// the face, or sets *why.
FaceH join_patch(Body& b, const std::vector<FaceH>& faces, std::string* why);

// Whether the chords of `path`// Whether the chords of `path` (consecutive pairs not adjacent on the loop) cross, for
// vertices in loop order `loop`: a path whose chords cross has no plane embedding in f.
bool chords_cross(const std::vector<VertexH>& loop, const std::vector<std::pair<VertexH, VertexH>>& tree);

}  // namespace kintsugi::detail

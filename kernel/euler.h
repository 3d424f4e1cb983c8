// Euler operators: the only way topology changes (spec/operators.md has the same
// contracts as a table, with the change each makes to V, E, F, L, S, B, R and H).
//
// Every operator
//   * checks its preconditions first and, when one fails, returns a typed error and
//     leaves the body exactly as it was; nothing passed in can cause undefined
//     behaviour (dead or out-of-range handles are refused);
//   * is journaled with its arguments and results (kernel/journal.h);
//   * runs the local invariant check over everything it touched afterwards (cheap, on
//     in release builds); a violation there is a kernel bug: the operator undoes
//     itself and returns Error::postcondition with the violation;
//   * has an inverse, named in its contract; "op then inverse" gives an equal body.
//
// A *corner* names where a new edge is inserted into a loop: before a half-edge
// (`Corner::before(h)`), or into a lone-vertex loop (`Corner::lone(l)`).
//
// Half-edge directions: x = halfedge_of(e, 0) and y = halfedge_of(e, 1); the curve of
// an edge runs along x. Outer loops run counter-clockwise seen from outside the face
// (the face normal by the right-hand rule).
#pragma once

#include "kernel/body.h"

#include <string>
#include <variant>

namespace kintsugi {

enum class ErrorCode {
  dead_handle,        // a handle that is out of range or names a killed element
  wrong_vertex,       // half-edges that should leave the same vertex do not
  wrong_loop,         // elements that should share a loop do not (or must not)
  wrong_face,         // loops that should share a face do not (or must not)
  not_lone,           // a loop that must be a lone-vertex loop is not
  is_lone,            // a loop that must have edges has none
  not_strut,          // an edge/vertex configuration the operator does not accept
  self_loop,          // an edge from a vertex to itself where one is not allowed
  degree,             // a vertex of the wrong degree
  border,             // the result would leave an edge with no face on either side
  outer_loop,         // a loop that must be a ring is the outer loop, or vice versa
  has_rings,          // a face that must have only its outer loop has rings
  last_face,          // the shell would be left without faces
  different_shell,    // faces in different shells
  genus,              // no through-hole to close
  disconnects,        // the result would split a shell in two
  transaction_open,   // refused while a transaction is open
  postcondition,      // the operator's result broke an invariant (a kernel bug)
};
const char* error_code_name(ErrorCode c);

struct Error {
  ErrorCode code;
  std::string message;  // names the elements involved
};

// The value an operator returns, or why it refused.
template <class T>
class Result {
 public:
  Result(T v) : v_(std::move(v)) {}
  Result(Error e) : v_(std::move(e)) {}
  bool ok() const { return std::holds_alternative<T>(v_); }
  explicit operator bool() const { return ok(); }
  const T& value() const { return std::get<T>(v_); }
  const T& operator*() const { return value(); }
  const T* operator->() const { return &value(); }
  const Error& error() const { return std::get<Error>(v_); }

 private:
  std::variant<T, Error> v_;
};

struct Done {};  // result of an operator that creates nothing

struct Corner {
  HalfedgeH he;  // insert before this half-edge ...
  LoopH lone;    // ... or into this lone-vertex loop
  static Corner before(HalfedgeH h) { return {h, LoopH{}}; }
  static Corner in_lone(LoopH l) { return {HalfedgeH{}, l}; }
};

// ---- results ---------------------------------------------------------------------
struct MvfsResult { ShellH shell; FaceH face; LoopH loop; VertexH vertex; };
struct MevResult { VertexH vertex; EdgeH edge; HalfedgeH x, y; };  // x: old → new vertex
struct MefResult { EdgeH edge; HalfedgeH a, b; FaceH face; LoopH loop; };
struct MekrResult { EdgeH edge; HalfedgeH a, b; };
struct KemrResult { LoopH ring; };
struct MfkrhResult { FaceH face; };
struct MfkbResult { FaceH face; };
struct KfmbResult { LoopH border; };
struct SemvResult { VertexH vertex; EdgeH edge; HalfedgeH next; };

namespace euler {

// mvfs — make vertex, face, shell.  ΔV+1 ΔF+1 ΔL+1 ΔS+1.
//   pre:  none.
//   post: a new shell with one face whose only loop is the lone vertex at `p`.
//   inverse: kvfs(face).
Result<MvfsResult> mvfs(Body& b, const geo::Vec3& p);

// kvfs — kill vertex, face, shell.  ΔV−1 ΔF−1 ΔL−1 ΔS−1.
//   pre:  `f` is the only face of its shell, has one loop, and that loop is a lone vertex.
//   inverse: mvfs.
Result<Done> kvfs(Body& b, FaceH f);

// mev — make edge, vertex.  ΔV+1 ΔE+1.
//   mev(b, Corner::in_lone(l), p): the lone vertex v of loop l gets an edge to a new
//     vertex at p; the loop becomes [x, y].
//   mev(b, Corner::before(h), p): a strut v→new inserted before h in h's loop
//     (prev(h) → x → y → h), v = origin(h).
//   mev_split(b, h1, h2, p): splits vertex v = origin(h1) = origin(h2), h1 ≠ h2: the
//     half-edges leaving v from h1 (inclusive) to h2 (exclusive), in rotation order
//     h → next(twin(h)), move to the new vertex; x: v→new is inserted before h1 and
//     y: new→v before h2.
//   pre:  live handles; h1, h2 leave the same vertex and h2 is in h1's rotation; a strut
//         may not go into a border cycle, and a split may not put both x and y into
//         border cycles (that edge would have no face).
//   post: x = halfedge_of(edge, 0) leaves the old vertex; y returns to it.
//   inverse: kev(x).
Result<MevResult> mev(Body& b, Corner c, const geo::Vec3& p);
Result<MevResult> mev_split(Body& b, HalfedgeH h1, HalfedgeH h2, const geo::Vec3& p);

// kev — kill edge, vertex.  ΔV−1 ΔE−1.
//   Collapses edge_of(h) onto origin(h): the vertex target(h) is killed and its other
//   edges move to origin(h). The surviving vertex keeps its point.
//   pre:  live h; h is not a self-loop; origin(h) has degree > 1 unless the loop is
//         just [h, twin(h)] (for a dangling origin, call kev(twin(h))).
//   inverse: mev / mev_split (as recorded).
Result<Done> kev(Body& b, HalfedgeH h);

// mef — make edge, face.  ΔE+1 ΔF+1 ΔL+1.
//   mef(b, before(h1), before(h2)), h1 and h2 in one loop L: new edge a: origin(h1) →
//     origin(h2) stays in L (prev(h1) → a → h2); the half-edges from h1 up to h2
//     (exclusive) with b: origin(h2) → origin(h1) form the new loop of a new face.
//     h1 == h2 makes an empty range: the new face is bounded by the self-loop b alone.
//   mef(b, in_lone(l), in_lone(l)): a self-loop edge at the lone vertex; L = [a], new
//     face [b].
//   If L is a border cycle, the new face fills part of the gap and L stays a border cycle.
//   The new face is in L's shell, with no surface yet.
//   inverse: kef(a).
Result<MefResult> mef(Body& b, Corner c1, Corner c2);

// kef — kill edge, face.  ΔE−1 ΔF−1 ΔL−1 (or ΔB−1 when the killed side is a border cycle).
//   Removes edge_of(h); the loop of twin(h) merges into the loop of h, and its face is
//   killed (its rings move to h's face). If h's side is a border cycle, the face across
//   is absorbed into the gap; if twin(h)'s side is a border cycle, h's face grows over it.
//   pre:  h and twin(h) in different loops of different faces; twin(h)'s loop is its
//         face's outer loop; not (loop of h is [h] alone while twin(h)'s loop is longer):
//         call kef(twin(h)); a face absorbed into a border cycle has no rings, shares no
//         other edge with a border cycle, and is not its shell's last face.
//   inverse: mef.
Result<Done> kef(Body& b, HalfedgeH h);

// kemr — kill edge, make ring.  ΔE−1 ΔL+1 ΔR+1.
//   Removes edge_of(h) whose half-edges are both in loop L of a face: the half-edges
//   from next(h) to prev(twin(h)) become a new ring of that face (a lone-vertex ring at
//   target(h) if that range is empty); the rest stays L.
//   pre:  h and twin(h) in the same face loop.
//   inverse: mekr.
Result<KemrResult> kemr(Body& b, HalfedgeH h);

// mekr — make edge, kill ring.  ΔE+1 ΔL−1 ΔR−1.
//   Joins loop L2 into loop L1 of the same face with a new edge a: v1 → v2 (v1, v2 the
//   corners' vertices): prev(c1) → a → c2 … prev(c2) → b → c1.
//   pre:  corners in different loops of one face (not a border cycle); L2 is a ring.
//   inverse: kemr(a).
Result<MekrResult> mekr(Body& b, Corner c1, Corner c2);

// kfmrh — kill face, make ring and hole.  ΔF−1 ΔR+1 ΔH+1.
//   The outer loop of `kill` becomes a ring of `keep`; the shell gains a through-hole.
//   pre:  distinct live faces of one shell; `kill` has no rings.
//   inverse: mfkrh(ring).
Result<Done> kfmrh(Body& b, FaceH keep, FaceH kill);

// mfkrh — make face, kill ring and hole.  ΔF+1 ΔR−1 ΔH−1.
//   Ring `l` of a face becomes the outer loop of a new face in the same shell (no surface).
//   pre:  l is a ring (not an outer loop, not a border cycle); the shell has genus ≥ 1; the
//         new face stays connected to the ring's old face through other faces (else the
//         ring does not go around a through-hole, and the shell would split instead).
//   inverse: kfmrh.
Result<MfkrhResult> mfkrh(Body& b, LoopH ring);

// kfmb — kill face, make border cycle.  ΔF−1 ΔB+1.  (Opens a gap.)
//   pre:  f has no rings; no edge of f already has a border cycle on its other side or f
//         on both sides (a seam);
//         f is not its shell's last face.
//   inverse: mfkb.
Result<KfmbResult> kfmb(Body& b, FaceH f);

// mfkb — make face, kill border cycle.  ΔF+1 ΔB−1.  (Closes a gap with a new face.)
//   pre:  l is a border cycle. The new face has no surface yet.
//   inverse: kfmb.
Result<MfkbResult> mfkb(Body& b, LoopH border);

// semv — split edge, make vertex.  ΔV+1 ΔE+1.
//   Splits edge_of(h) at a new vertex m at p: h now ends at m, and a new half-edge
//   `next` (m → old target) follows it. The new edge's curve is a copy of the old one,
//   oriented the same way.
//   inverse: jekv(h).
Result<SemvResult> semv(Body& b, HalfedgeH h, const geo::Vec3& p);

// jekv — join edges, kill vertex.  ΔV−1 ΔE−1.
//   Joins edge_of(h) and edge_of(next(h)) at m = target(h); edge_of(h) survives with
//   its curve (set the union's curve afterwards), edge_of(next(h)) and m are killed.
//   pre:  m lies on exactly these two edges, and they are different edges.
//   inverse: semv(h, point(m)).
Result<Done> jekv(Body& b, HalfedgeH h);

}  // namespace euler
}  // namespace kintsugi

// Euler operators: the only way topology changes (spec/operators.md has the same
// contracts as a table, with the change each makes to V, E, F, L, S, B, R and H;
// kernel/operator_list.h lists the operators the kernel exports).
//
// Every operator comes as a query/action pair:
//   * can_<op>(body, same arguments) returns every reason the operator would refuse (as
//     an Error), or nothing; it changes nothing;
//   * <op>(body, arguments) calls can_<op> first and refuses for exactly those reasons,
//     leaving the body exactly as it was; nothing passed in can cause undefined
//     behaviour (dead or out-of-range handles are refused);
//   * <op> is journaled with a named record (kernel/journal_records.h);
//   * <op> runs the local invariant check over everything it touched afterwards
//     (kernel/local_check.h; cheap, on in release builds). A violation there is a kernel
//     bug: the operator undoes itself and returns Error::postcondition, which no caller
//     may treat as an ordinary refusal (tests and fuzz targets fail on it;
//     euler::postcondition_failures() counts them);
//   * has an inverse, named in its contract; "op then inverse" gives an equal body.
// Each operator pair lives in one file, kernel/op_<pair>.cpp: query, raw step, journal
// record and undo, top to bottom.
//
// Counts in the Δ lines: V vertices, E edges, F faces, L face loops, S shells, H genus
// (through-holes), B border cycles, R rings (inner loops). Per shell,
// V − E + F + B − R = 2(1 − H).
//
// A *corner* names where a new edge is inserted into a loop: before a half-edge
// (`Corner::before(h)`), or into a lone-vertex loop (`Corner::in_lone(l)`).
//
// Half-edge directions: x = halfedge_of(e, 0) and y = halfedge_of(e, 1); the curve of
// an edge runs along x. Outer loops run counter-clockwise seen from outside the face
// (the face normal by the right-hand rule).
#pragma once

#include "kernel/body.h"

#include <cstdint>
#include <optional>
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

// mvfs — make vertex, face, shell.
//   pre:  none.
//   post: a new shell with one face whose only loop is the lone vertex at `p`.
//   Δ:    V+1 F+1 L+1 S+1.
//   inverse: kvfs(face) gives an equal body.
std::optional<Error> can_mvfs(const Body& b, const geo::Vec3& p);
Result<MvfsResult> mvfs(Body& b, const geo::Vec3& p);

// kvfs — kill vertex, face, shell.
//   pre:  live `f` is the only face of its shell, has one loop, and that loop is a lone
//         vertex.
//   post: the shell, face, loop and vertex are dead.
//   Δ:    V−1 F−1 L−1 S−1.
//   inverse: mvfs (new handles); the journaled inverse revives the same ones.
std::optional<Error> can_kvfs(const Body& b, FaceH f);
Result<Done> kvfs(Body& b, FaceH f);

// mev — make edge, vertex.
//   mev(b, Corner::in_lone(l), p): the lone vertex v of loop l gets an edge to a new
//     vertex at p; the loop becomes [x, y].
//   mev(b, Corner::before(h), p): a strut v→new inserted before h in h's loop
//     (prev(h) → x → y → h), v = origin(h).
//   mev_split(b, h1, h2, p): splits vertex v = origin(h1) = origin(h2), h1 ≠ h2: the
//     half-edges leaving v from h1 (inclusive) to h2 (exclusive), in rotation order
//     h → next(twin(h)), move to the new vertex; x: v→new is inserted before h1 and
//     y: new→v before h2. h1 == h2 is mev(before(h1)).
//   pre:  live handles (a lone corner: a lone-vertex loop); h1, h2 leave the same vertex
//         and h2 is in h1's rotation; a strut may not go into a border cycle, and a
//         split may not put both x and y into border cycles (that edge would have no face).
//   post: x = halfedge_of(edge, 0) leaves the old vertex; y returns to it.
//   Δ:    V+1 E+1.
//   inverse: kev(x) gives an equal body.
std::optional<Error> can_mev(const Body& b, Corner c, const geo::Vec3& p);
Result<MevResult> mev(Body& b, Corner c, const geo::Vec3& p);
std::optional<Error> can_mev_split(const Body& b, HalfedgeH h1, HalfedgeH h2, const geo::Vec3& p);
Result<MevResult> mev_split(Body& b, HalfedgeH h1, HalfedgeH h2, const geo::Vec3& p);

// kev — kill edge, vertex.
//   Collapses edge_of(h) onto origin(h): the vertex target(h) is killed and its other
//   edges move to origin(h). The surviving vertex keeps its point.
//   pre:  live h; h is not a self-loop; origin(h) has degree > 1 unless the loop is
//         just [h, twin(h)] (for a dangling origin, call kev(twin(h))).
//   post: target(h) and edge_of(h) are dead; a loop that was [h, twin(h)] is the lone
//         vertex origin(h).
//   Δ:    V−1 E−1.
//   inverse: mev / mev_split (as recorded; new handles); the journaled inverse revives
//            the same ones.
std::optional<Error> can_kev(const Body& b, HalfedgeH h);
Result<Done> kev(Body& b, HalfedgeH h);

// mef — make edge, face.
//   mef(b, before(h1), before(h2)), h1 and h2 in one loop L: new edge a: origin(h1) →
//     origin(h2) stays in L (prev(h1) → a → h2); the half-edges from h1 up to h2
//     (exclusive) with b: origin(h2) → origin(h1) form the new loop of a new face.
//     h1 == h2 makes an empty range: the new face is bounded by the self-loop b alone.
//   mef(b, in_lone(l), in_lone(l)): a self-loop edge at the lone vertex; L = [a], new
//     face [b].
//   If L is a border cycle, the new face fills part of the gap and L stays a border cycle.
//   pre:  live corners in one loop, both lone or both half-edges.
//   post: the new face is in L's shell, with no surface yet.
//   Δ:    E+1 F+1 L+1.
//   inverse: kef(a) gives an equal body.
std::optional<Error> can_mef(const Body& b, Corner c1, Corner c2);
Result<MefResult> mef(Body& b, Corner c1, Corner c2);

// kef — kill edge, face.
//   Removes edge_of(h); the loop of twin(h) merges into the loop of h, and its face is
//   killed (its rings move to h's face). If h's side is a border cycle, the face across
//   is absorbed into the gap; if twin(h)'s side is a border cycle, h's face grows over it.
//   pre:  live h; h and twin(h) in different loops of different faces (at most one side
//         a border cycle); twin(h)'s loop is its face's outer loop; not (loop of h is [h]
//         alone while twin(h)'s loop is longer): call kef(twin(h)); a face absorbed into a
//         border cycle has no rings, shares no other edge with a border cycle, has no
//         edge with itself on both sides (a strut or a seam), and is not its shell's
//         last face.
//   post: edge_of(h), twin(h)'s loop and its face are dead.
//   Δ:    E−1 F−1 L−1; when twin(h)'s side is a border cycle: E−1 B−1.
//   inverse: mef (new handles); the journaled inverse revives the same ones.
std::optional<Error> can_kef(const Body& b, HalfedgeH h);
Result<Done> kef(Body& b, HalfedgeH h);

// kemr — kill edge, make ring.
//   Removes edge_of(h) whose half-edges are both in loop L of a face: the half-edges
//   from next(h) to prev(twin(h)) become a new ring of that face (a lone-vertex ring at
//   target(h) if that range is empty); the rest stays L.
//   pre:  live h; h and twin(h) in the same loop of a face (not a border cycle), not a
//         self-loop alone in it.
//   post: edge_of(h) is dead; the new ring is in L's face.
//   Δ:    E−1 L+1 R+1.
//   inverse: mekr (new edge); the journaled inverse revives the same edge.
std::optional<Error> can_kemr(const Body& b, HalfedgeH h);
Result<KemrResult> kemr(Body& b, HalfedgeH h);

// mekr — make edge, kill ring.
//   Joins loop L2 into loop L1 of the same face with a new edge a: v1 → v2 (v1, v2 the
//   corners' vertices): prev(c1) → a → c2 … prev(c2) → b → c1.
//   pre:  live corners in different loops of one face (not border cycles); L2 is a ring.
//   post: L2 is dead; L1 holds its half-edges, a and b.
//   Δ:    E+1 L−1 R−1.
//   inverse: kemr(a) gives an equal body up to the ring's handle; the journaled inverse
//            revives the same ring.
std::optional<Error> can_mekr(const Body& b, Corner c1, Corner c2);
Result<MekrResult> mekr(Body& b, Corner c1, Corner c2);

// kfmrh — kill face, make ring and hole.
//   The outer loop of `kill` becomes a ring of `keep`; the shell gains a through-hole.
//   pre:  distinct live faces of one shell; `kill` has no rings.
//   post: `kill` is dead; its outer loop is a ring of `keep`.
//   Δ:    F−1 R+1 H+1.
//   inverse: mfkrh(ring) (new face); the journaled inverse revives the same face.
std::optional<Error> can_kfmrh(const Body& b, FaceH keep, FaceH kill);
Result<Done> kfmrh(Body& b, FaceH keep, FaceH kill);

// mfkrh — make face, kill ring and hole.
//   Ring `l` of a face becomes the outer loop of a new face in the same shell (no surface).
//   pre:  live l is a ring (not an outer loop, not a border cycle); the shell has genus
//         ≥ 1; the new face stays connected to the ring's old face through other faces
//         (else the ring does not go around a through-hole, and the shell would split).
//   post: a new face whose outer loop is l.
//   Δ:    F+1 R−1 H−1.
//   inverse: kfmrh(old face, new face) gives an equal body.
std::optional<Error> can_mfkrh(const Body& b, LoopH ring);
Result<MfkrhResult> mfkrh(Body& b, LoopH ring);

// kfmb — kill face, make border cycle.  (Opens a gap.)
//   pre:  live f has edges and no rings; no edge of f already has a border cycle on its
//         other side or f on both sides (a seam); f is not its shell's last face.
//   post: f is dead; its outer loop is a border cycle.
//   Δ:    F−1 L−1 B+1.
//   inverse: mfkb(border) (new face); the journaled inverse revives the same face.
std::optional<Error> can_kfmb(const Body& b, FaceH f);
Result<KfmbResult> kfmb(Body& b, FaceH f);

// mfkb — make face, kill border cycle.  (Closes a gap with a new face.)
//   pre:  live l is a border cycle.
//   post: a new face (no surface yet) whose outer loop is l.
//   Δ:    F+1 L+1 B−1.
//   inverse: kfmb(face) gives an equal body.
std::optional<Error> can_mfkb(const Body& b, LoopH border);
Result<MfkbResult> mfkb(Body& b, LoopH border);

// semv — split edge, make vertex.
//   Splits edge_of(h) at a new vertex m at p: h now ends at m, and a new half-edge
//   `next` (m → old target) follows it. The new edge's curve is a copy of the old one,
//   oriented the same way.
//   pre:  live h.
//   post: target(h) = m, next(h) = `next`, m has degree 2.
//   Δ:    V+1 E+1.
//   inverse: jekv(h) gives an equal body.
std::optional<Error> can_semv(const Body& b, HalfedgeH h, const geo::Vec3& p);
Result<SemvResult> semv(Body& b, HalfedgeH h, const geo::Vec3& p);

// jekv — join edges, kill vertex.
//   Joins edge_of(h) and edge_of(next(h)) at m = target(h); edge_of(h) survives with
//   its curve (set the union's curve afterwards), edge_of(next(h)) and m are killed.
//   pre:  live h; m lies on exactly these two edges, and they are different edges.
//   post: h ends where next(h) ended.
//   Δ:    V−1 E−1.
//   inverse: semv(h, point(m)) (new handles); the journaled inverse revives the same ones.
std::optional<Error> can_jekv(const Body& b, HalfedgeH h);
Result<Done> jekv(Body& b, HalfedgeH h);

// Refusals with Error::postcondition since the program started. Each is a kernel bug
// (an operator broke an invariant and undid itself); tests and fuzz targets that run
// operators indirectly compare this before and after.
std::uint64_t postcondition_failures();

}  // namespace euler
}  // namespace kintsugi

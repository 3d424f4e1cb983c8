// The boundary representation: a body of shells, faces, loops, half-edges, edges and
// vertices (spec/entities.md), with geometry attached per element.
//
// Representation (docs/design.md says why):
//   * half-edge h has an origin vertex, next and prev in its loop, and its loop;
//     twin(h) and edge_of(h) are derived from the index;
//   * a loop is a cycle of half-edges, or a single "lone" vertex with no edges
//     (as made by mvfs and by kemr on a strut). A loop belongs to a face, or to no
//     face: then it is a *border cycle*, the far side of a gap in an open shell;
//   * a face has one outer loop and any number of inner loops (rings), chained
//     through LoopRec::next_in_face, outer first;
//   * a shell counts its faces and its genus (through-holes made by kfmrh), which the
//     Euler–Poincaré check compares against V − E + F + B − R.
//
// Topology changes only through the Euler operators in kernel/euler.h; this class
// offers read access, geometry, and the journal. Every mutation is journaled.
#pragma once

#include "geometry/types.h"
#include "kernel/handles.h"
#include "kernel/journal.h"

#include <cstdint>
#include <vector>

namespace kintsugi {

struct VertexRec {
  HalfedgeH out;  // some half-edge leaving this vertex; invalid for a lone vertex
};
struct HalfedgeRec {
  VertexH origin;
  HalfedgeH next, prev;
  LoopH loop;
};
struct LoopRec {
  FaceH face;          // invalid: this loop is a border cycle
  HalfedgeH first;     // invalid: lone-vertex loop
  VertexH lone;        // the vertex of a lone-vertex loop
  LoopH next_in_face;  // next ring of the same face
};
struct FaceRec {
  ShellH shell;
  LoopH outer;  // head of the face's loop chain
};
struct ShellRec {
  std::uint32_t faces = 0;
  std::uint32_t genus = 0;
};

struct Counts {
  std::size_t vertices = 0, edges = 0, faces = 0, loops = 0, shells = 0, border_cycles = 0;
  bool operator==(const Counts&) const = default;
};

class EulerImpl;  // kernel/euler.cpp and kernel/op_*.cpp: the only code that changes topology

class Body {
 public:
  Body() = default;

  // ---- element existence and iteration -------------------------------------------
  bool alive(VertexH v) const { return v.idx() < v_alive_.size() && v_alive_[v.idx()]; }
  bool alive(EdgeH e) const { return e.idx() < e_alive_.size() && e_alive_[e.idx()]; }
  bool alive(HalfedgeH h) const { return h.valid() && alive(edge_of(h)); }
  bool alive(LoopH l) const { return l.idx() < l_alive_.size() && l_alive_[l.idx()]; }
  bool alive(FaceH f) const { return f.idx() < f_alive_.size() && f_alive_[f.idx()]; }
  bool alive(ShellH s) const { return s.idx() < s_alive_.size() && s_alive_[s.idx()]; }

  // Slot counts (live and dead): handles range over [0, n).
  std::size_t vertex_slots() const { return vertices_.size(); }
  std::size_t edge_slots() const { return e_alive_.size(); }
  std::size_t halfedge_slots() const { return halfedges_.size(); }
  std::size_t loop_slots() const { return loops_.size(); }
  std::size_t face_slots() const { return faces_.size(); }
  std::size_t shell_slots() const { return shells_.size(); }

  std::vector<VertexH> vertices() const;
  std::vector<EdgeH> edges() const;
  std::vector<HalfedgeH> halfedges() const;
  std::vector<LoopH> loops() const;  // face loops and border cycles
  std::vector<FaceH> faces() const;
  std::vector<ShellH> shells() const;
  std::vector<LoopH> border_cycles() const;

  Counts counts() const;

  // ---- navigation (callers pass live handles) -----------------------------------
  VertexH origin(HalfedgeH h) const { return halfedges_[h.idx()].origin; }
  VertexH target(HalfedgeH h) const { return origin(twin(h)); }
  HalfedgeH next(HalfedgeH h) const { return halfedges_[h.idx()].next; }
  HalfedgeH prev(HalfedgeH h) const { return halfedges_[h.idx()].prev; }
  LoopH loop(HalfedgeH h) const { return halfedges_[h.idx()].loop; }
  FaceH face(HalfedgeH h) const { return loops_[loop(h).idx()].face; }
  bool is_border(HalfedgeH h) const { return !face(h).valid(); }

  HalfedgeH out(VertexH v) const { return vertices_[v.idx()].out; }

  FaceH face(LoopH l) const { return loops_[l.idx()].face; }
  bool is_border(LoopH l) const { return !loops_[l.idx()].face.valid(); }
  HalfedgeH first(LoopH l) const { return loops_[l.idx()].first; }
  bool is_lone(LoopH l) const { return !loops_[l.idx()].first.valid(); }
  VertexH lone_vertex(LoopH l) const { return loops_[l.idx()].lone; }
  LoopH next_in_face(LoopH l) const { return loops_[l.idx()].next_in_face; }
  bool is_outer(LoopH l) const { return !is_border(l) && faces_[face(l).idx()].outer == l; }

  ShellH shell(FaceH f) const { return faces_[f.idx()].shell; }
  LoopH outer_loop(FaceH f) const { return faces_[f.idx()].outer; }
  std::vector<LoopH> loops_of(FaceH f) const;  // outer first
  std::vector<LoopH> rings_of(FaceH f) const;  // inner loops only

  // The shell a loop is in: its face's, or for a border cycle, the shell of the face
  // across any of its half-edges.
  ShellH shell(LoopH l) const;

  std::uint32_t shell_face_count(ShellH s) const { return shells_[s.idx()].faces; }
  std::uint32_t shell_genus(ShellH s) const { return shells_[s.idx()].genus; }

  // Half-edges of a loop in order (empty for a lone-vertex loop). Bounded: stops after
  // halfedge_slots() steps, so a corrupt cycle cannot hang the caller.
  std::vector<HalfedgeH> loop_halfedges(LoopH l) const;
  // visit(h) for the same half-edges in the same order, without building the list (the
  // whole-model measures walk millions of loops).
  template <class Visit>
  void for_each_halfedge(LoopH l, Visit&& visit) const {
    const HalfedgeH start = first(l);
    if (!start.valid()) return;
    HalfedgeH h = start;
    std::size_t n = 0;
    do {
      visit(h);
      h = next(h);
    } while (h != start && h.valid() && h.idx() < halfedges_.size() && ++n <= halfedges_.size());
  }
  std::vector<VertexH> loop_vertices(LoopH l) const;
  // Half-edges leaving v, walking the rotation h -> next(twin(h)). Bounded likewise.
  std::vector<HalfedgeH> outgoing(VertexH v) const;
  std::size_t degree(VertexH v) const { return outgoing(v).size(); }

  // ---- geometry ----------------------------------------------------------------
  const geo::Vec3& point(VertexH v) const { return points_[v.idx()]; }
  const geo::Curve& curve(EdgeH e) const { return curves_[e.idx()]; }
  const geo::Surface& surface(FaceH f) const { return surfaces_[f.idx()]; }
  // true: the face's outward normal is the surface's normal; false: opposite.
  bool same_sense(FaceH f) const { return senses_[f.idx()] != 0; }

  // Geometry changes are journaled so a transaction rolls them back too.
  void set_point(VertexH v, const geo::Vec3& p);
  void set_curve(EdgeH e, geo::Curve c);
  void set_surface(FaceH f, geo::Surface s, bool same_sense = true);

  // ---- journal --------------------------------------------------------------------
  const Journal& journal() const { return journal_; }
  // Forget recorded history. Refused (returns false) while a transaction is open.
  bool clear_journal();
  // While paused, operators are not recorded (bulk builders that will never be rolled
  // back use this to save memory). Refused while a transaction is open.
  bool set_journaling(bool on);
  bool journaling() const { return journaling_; }

  // ---- compaction -----------------------------------------------------------------
  struct Renumbering {
    std::vector<std::uint32_t> vertex, edge, loop, face, shell;  // old index -> new (or invalid)
  };
  // Removes tombstones, renumbering every handle. Refused (empty maps, no change)
  // while a transaction is open. Clears the journal, whose handles would be stale.
  Renumbering compact();

  // Semantic equality: same live handles with the same incidences and geometry. A loop's
  // `first` half-edge and a vertex's `out` half-edge are representatives of a cycle, so
  // only the cycle they name is compared; so is the order of a face's rings.
  bool equals(const Body& other, std::string* why = nullptr) const;

  // Exact copy of the storage, for tests and for the reader.
  Body clone() const { return *this; }

 private:
  friend class EulerImpl;
  friend class Transaction;
  friend class BodyReader;
  friend struct RawBody;  // tests/invariants/raw_body.h: raw edits that break one invariant

  std::vector<VertexRec> vertices_;
  std::vector<HalfedgeRec> halfedges_;
  std::vector<LoopRec> loops_;
  std::vector<FaceRec> faces_;
  std::vector<ShellRec> shells_;
  std::vector<std::uint8_t> v_alive_, e_alive_, l_alive_, f_alive_, s_alive_;

  std::vector<geo::Vec3> points_;
  std::vector<geo::Curve> curves_;
  std::vector<geo::Surface> surfaces_;
  std::vector<std::uint8_t> senses_;

  Journal journal_;
  bool journaling_ = true;
  int open_transactions_ = 0;
};

}  // namespace kintsugi

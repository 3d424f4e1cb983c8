// What the journal keeps of each operator: one named record per operator, holding the
// handles its inverse needs. The operator's file (kernel/op_<pair>.cpp) makes the record
// and undoes it; the records are declared here, together, because the journal stores
// them by value in one variant. Geometry an operator destroys is not in the record but
// in the journal's side tables (JournalEntry::saved, ::extra).
#pragma once

#include "kernel/handles.h"

#include <cstdint>
#include <variant>

namespace kintsugi {

enum class Op : std::uint8_t {
  mvfs, kvfs, mev, kev, mef, kef, kemr, mekr, kfmrh, mfkrh, semv, jekv, kfmb, mfkb,
  set_point, set_curve, set_surface,
};
const char* op_name(Op op);

// How mev attached the new edge; kev records it so that its undo re-makes the same one.
enum class MevKind : std::uint8_t {
  lone,   // into a lone-vertex loop
  strut,  // a strut before a half-edge
  split,  // a split of a vertex between two half-edges of its rotation
};

// mvfs made these; undo: kvfs(face).
struct MvfsRecord {
  static constexpr Op kOp = Op::mvfs;
  ShellH shell; FaceH face; LoopH loop; VertexH vertex;
};
// kvfs killed these (saved: the vertex's point, the face's surface); undo revives them.
struct KvfsRecord {
  static constexpr Op kOp = Op::kvfs;
  ShellH shell; FaceH face; LoopH loop; VertexH vertex;
};
// mev made `vertex` and `edge`, x leaving the old vertex; undo: kev(x).
struct MevRecord {
  static constexpr Op kOp = Op::mev;
  VertexH vertex; EdgeH edge; HalfedgeH x;
};
// kev killed `killed` and edge_of(x) (saved: the point, the curve); undo re-makes them
// with mev of `kind`: at the corners `before1`, `before2` (strut: both the same), or in
// the loop `lone` when the loop collapsed to the survivor.
struct KevRecord {
  static constexpr Op kOp = Op::kev;
  MevKind kind; VertexH survivor; VertexH killed; HalfedgeH x;
  HalfedgeH before1, before2; LoopH lone;
};
// mef made `edge` (a stays in the old loop), `face` and its `loop`; undo: kef(a).
struct MefRecord {
  static constexpr Op kOp = Op::mef;
  EdgeH edge; HalfedgeH a; FaceH face; LoopH loop;
};
// kef killed edge_of(h), the loop across and its face (`killed_face` is none when that
// side was a border cycle). Saved: the curve and the surface; extra: the rings that moved
// to h's face. Undo re-makes the edge with mef at `before1`, `before2`, or in `lone`.
struct KefRecord {
  enum class Kind : std::uint8_t {
    lone,         // a self-loop between two one-edge loops: h's loop kept the vertex
    empty_range,  // twin(h) bounded its face alone
    general,
  };
  static constexpr Op kOp = Op::kef;
  Kind kind; HalfedgeH h; FaceH killed_face; LoopH killed_loop;
  HalfedgeH before1, before2; LoopH lone;
};
// kemr killed edge_of(x) (saved: the curve) and made `ring` out of `loop`; undo: mekr at
// `before1` (in `loop`, or its lone vertex) and `before2` (in `ring`, or its lone vertex).
struct KemrRecord {
  static constexpr Op kOp = Op::kemr;
  HalfedgeH x; LoopH ring; HalfedgeH before1, before2; LoopH loop;
};
// mekr made `edge` (a: v1 → v2) and killed `ring`; undo: kemr(a), reviving the ring.
struct MekrRecord {
  static constexpr Op kOp = Op::mekr;
  EdgeH edge; HalfedgeH a; LoopH ring;
};
// kfmrh killed `killed` (saved: its surface) whose outer loop became `ring` of `keep`.
struct KfmrhRecord {
  static constexpr Op kOp = Op::kfmrh;
  FaceH keep; FaceH killed; LoopH ring;
};
// mfkrh made `face` out of `ring` of `old_face`; undo: kfmrh(old_face, face).
struct MfkrhRecord {
  static constexpr Op kOp = Op::mfkrh;
  FaceH old_face; FaceH face; LoopH ring;
};
// kfmb killed `killed` (saved: its surface); its loop is now the border cycle `border`.
struct KfmbRecord {
  static constexpr Op kOp = Op::kfmb;
  FaceH killed; LoopH border;
};
// mfkb made `face` over the border cycle `border`; undo: kfmb(face).
struct MfkbRecord {
  static constexpr Op kOp = Op::mfkb;
  FaceH face; LoopH border;
};
// semv split edge_of(h) at `vertex`; the new `edge` starts with `next`. Undo: jekv(h).
struct SemvRecord {
  static constexpr Op kOp = Op::semv;
  HalfedgeH h; VertexH vertex; EdgeH edge; HalfedgeH next;
};
// jekv killed `killed` = target(h) and edge_of(`killed_next`) (saved: point and curve);
// undo: semv(h) reviving them, the new half-edge on the side of `killed_next`.
struct JekvRecord {
  static constexpr Op kOp = Op::jekv;
  HalfedgeH h; VertexH killed; EdgeH killed_edge; HalfedgeH killed_next;
};
// Geometry changes (kernel/body.h); saved: the old value.
struct SetPointRecord {
  static constexpr Op kOp = Op::set_point;
  VertexH vertex;
};
struct SetCurveRecord {
  static constexpr Op kOp = Op::set_curve;
  EdgeH edge;
};
struct SetSurfaceRecord {
  static constexpr Op kOp = Op::set_surface;
  FaceH face;
};

using JournalRecord =
    std::variant<MvfsRecord, KvfsRecord, MevRecord, KevRecord, MefRecord, KefRecord, KemrRecord, MekrRecord,
                 KfmrhRecord, MfkrhRecord, KfmbRecord, MfkbRecord, SemvRecord, JekvRecord, SetPointRecord,
                 SetCurveRecord, SetSurfaceRecord>;

}  // namespace kintsugi

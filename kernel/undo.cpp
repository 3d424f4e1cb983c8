// Rollback: the inverse of each journal entry, applied without journaling. Kill
// operators are undone by the matching make operator told to revive exactly the slots
// that were killed, so handles recorded in later (already undone) entries and held by
// callers mean the same elements again. The layout of each entry's `h` array is
// documented where the entry is made, in kernel/euler.cpp and kernel/body.cpp.
#include "kernel/euler_impl.h"

namespace kintsugi {

namespace {
HalfedgeH H(std::uint32_t i) { return HalfedgeH(i); }
}  // namespace

void EulerImpl::undo(Body& b, const JournalEntry& e) {
  Touched t;
  const auto& h = e.h;
  Journal& j = b.journal_;
  // Puts back the surface and sense this entry saved for face slot `face`.
  auto restore_surface = [&](std::uint32_t face) {
    b.surfaces_[face] = j.surfaces_[e.saved];
    b.senses_[face] = j.senses_[e.saved];
  };
  switch (e.op) {
    case Op::mvfs:
      raw_kvfs(b, FaceH(h[1]), t);
      break;
    case Op::kvfs: {
      Reuse r;
      r.shell = h[0];
      r.face = h[1];
      r.loop = h[2];
      r.vertex = h[3];
      raw_mvfs(b, j.points_[e.saved], r, t);
      restore_surface(h[1]);
      break;
    }
    case Op::mev:
      raw_kev(b, H(h[2]), t);
      break;
    case Op::kev: {
      Reuse r;
      r.vertex = h[1];
      r.edge = h[2] >> 1;
      r.x_side = int(h[2] & 1u);
      auto kind = static_cast<MevKind>(h[6]);
      raw_mev(b, kind, kind == MevKind::lone ? HalfedgeH{} : H(h[3]), kind == MevKind::lone ? HalfedgeH{} : H(h[4]),
              kind == MevKind::lone ? LoopH(h[5]) : LoopH{}, j.points_[e.saved], r, t);
      b.curves_[r.edge] = j.curves_[e.saved];
      break;
    }
    case Op::mef:
      raw_kef(b, H(h[1]), t);
      break;
    case Op::kef: {
      HalfedgeH hh = H(h[0]);
      Reuse r;
      r.edge = hh.idx() >> 1;
      r.x_side = int(hh.idx() & 1u);
      r.loop = h[2];
      r.face = h[1];
      Corner c1, c2;
      if (h[6] == 0) {
        // The edge was a self-loop between two one-edge loops; h's loop kept the vertex.
        LoopH lone = LoopH(h[5]);
        c1 = c2 = Corner::in_lone(lone);
      } else {
        c1 = Corner::before(H(h[3]));
        c2 = Corner::before(H(h[4]));
      }
      FaceH fh = b.face(c1.lone.valid() ? c1.lone : he(b, c1.he).loop);
      MefResult m = raw_mef(b, c1, c2, r, t);
      if (h[1] == kNone) {  // the killed side was a border cycle: it becomes one again
        kill(b, m.face);
        lp(b, m.loop).face = FaceH{};
      } else {
        restore_surface(h[1]);
        if (e.extra != kNone && fh.valid()) {
          for (std::uint32_t ring : j.lists_[e.extra]) {
            remove_ring(b, fh, LoopH(ring));
            add_ring(b, m.face, LoopH(ring));
          }
        }
      }
      b.curves_[r.edge] = j.curves_[e.saved];
      break;
    }
    case Op::kemr: {
      Reuse r;
      r.edge = h[0] >> 1;
      r.x_side = int(h[0] & 1u);
      Corner c1 = h[2] != kNone ? Corner::before(H(h[2])) : Corner::in_lone(LoopH(h[4]));
      Corner c2 = h[3] != kNone ? Corner::before(H(h[3])) : Corner::in_lone(LoopH(h[1]));
      raw_mekr(b, c1, c2, r, t);
      b.curves_[r.edge] = j.curves_[e.saved];
      break;
    }
    case Op::mekr: {
      Reuse r;
      r.loop = h[2];
      raw_kemr(b, H(h[1]), r, t);
      break;
    }
    case Op::kfmrh: {
      Reuse r;
      r.face = h[1];
      raw_mfkrh(b, LoopH(h[2]), r, t);
      restore_surface(h[1]);
      break;
    }
    case Op::mfkrh:
      raw_kfmrh(b, FaceH(h[0]), FaceH(h[1]), t);
      break;
    case Op::kfmb: {
      Reuse r;
      r.face = h[0];
      raw_mfkb(b, LoopH(h[1]), r, t);
      restore_surface(h[0]);
      break;
    }
    case Op::mfkb:
      raw_kfmb(b, FaceH(h[0]), t);
      break;
    case Op::semv:
      raw_jekv(b, H(h[0]), t);
      break;
    case Op::jekv: {
      Reuse r;
      r.vertex = h[1];
      r.edge = h[2];
      r.x_side = int(h[3] & 1u);
      raw_semv(b, H(h[0]), j.points_[e.saved], r, t);
      b.curves_[h[2]] = j.curves_[e.saved];
      break;
    }
    case Op::set_point:
      b.points_[h[0]] = j.points_[e.saved];
      break;
    case Op::set_curve:
      b.curves_[h[0]] = j.curves_[e.saved];
      break;
    case Op::set_surface:
      restore_surface(h[0]);
      break;
  }
}

}  // namespace kintsugi

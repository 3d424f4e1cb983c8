#include "tests/support/random_ops.h"

namespace kintsugi::testing {

Numbers::Numbers(const std::uint8_t* data, std::size_t size) {
  for (std::size_t i = 0; i + 1 < size; i += 2) v_.push_back(std::uint32_t(data[i]) | (std::uint32_t(data[i + 1]) << 8));
}

namespace {

template <class T>
T pick(const std::vector<T>& v, Numbers& n) {
  return v.empty() ? T{} : v[n.below(v.size())];
}

geo::Vec3 point(Numbers& n) {
  double x = n.coord(), y = n.coord(), z = n.coord();
  return {x, y, z};
}

Corner corner_in(const Body& b, LoopH l, Numbers& n) {
  if (b.is_lone(l)) return Corner::in_lone(l);
  return Corner::before(pick(b.loop_halfedges(l), n));
}

// What the query said, before the operator runs.
Applied ask(const char* op, std::string what, OpKind kind, const std::optional<Error>& refusal) {
  Applied a;
  a.op = op;
  a.what = std::move(what);
  a.kind = kind;
  a.query_ok = !refusal;
  if (refusal) a.query_error = error_code_name(refusal->code) + std::string(": ") + refusal->message;
  return a;
}

// What the operator did.
template <class T>
Applied& answer(Applied& a, const Result<T>& r) {
  a.ok = r.ok();
  if (!r.ok()) {
    a.error = r.error().message;
    a.code = r.error().code;
  }
  return a;
}

}  // namespace

Applied apply_random_op(Body& b, Numbers& n) {
  auto faces = b.faces();
  auto loops = b.loops();
  auto hes = b.halfedges();
  auto verts = b.vertices();
  // Sometimes hand over a dead or out-of-range handle: preconditions must refuse it.
  bool junk = n.below(16) == 0;
  auto any_he = [&] { return junk ? HalfedgeH(n.below(hes.size() + 4)) : pick(hes, n); };
  auto any_face = [&] { return junk ? FaceH(n.below(faces.size() + 4)) : pick(faces, n); };
  auto any_loop = [&] { return junk ? LoopH(n.below(loops.size() + 4)) : pick(loops, n); };

  switch (n.below(15)) {
    case 0: {
      if (n.below(4) != 0) break;  // new shells rarely
      geo::Vec3 p = point(n);
      Applied a = ask("mvfs", "mvfs", OpKind::make, euler::can_mvfs(b, p));
      auto r = euler::mvfs(b, p);
      if (answer(a, r).ok) a.inverse = [f = r->face](Body& x) { return euler::kvfs(x, f); };
      return a;
    }
    case 1: {
      FaceH f = any_face();
      Applied a = ask("kvfs", "kvfs(" + f.str() + ")", OpKind::kill, euler::can_kvfs(b, f));
      return answer(a, euler::kvfs(b, f));
    }
    case 2: {
      if (loops.empty()) break;
      LoopH l = any_loop();
      Corner c = b.alive(l) ? corner_in(b, l, n) : Corner::in_lone(l);
      geo::Vec3 p = point(n);
      Applied a = ask("mev", "mev(" + (c.he.valid() ? c.he.str() : c.lone.str()) + ")", OpKind::make,
                      euler::can_mev(b, c, p));
      auto r = euler::mev(b, c, p);
      if (answer(a, r).ok) a.inverse = [x = r->x](Body& body) { return euler::kev(body, x); };
      return a;
    }
    case 3: {
      if (verts.empty()) break;
      VertexH v = pick(verts, n);
      auto outs = b.outgoing(v);
      if (outs.size() < 2) break;
      HalfedgeH h1 = pick(outs, n), h2 = pick(outs, n);
      geo::Vec3 p = point(n);
      Applied a = ask("mev_split", "mev_split(" + h1.str() + ", " + h2.str() + ")", OpKind::make,
                      euler::can_mev_split(b, h1, h2, p));
      auto r = euler::mev_split(b, h1, h2, p);
      if (answer(a, r).ok) a.inverse = [x = r->x](Body& body) { return euler::kev(body, x); };
      return a;
    }
    case 4: {
      HalfedgeH h = any_he();
      Applied a = ask("kev", "kev(" + h.str() + ")", OpKind::kill, euler::can_kev(b, h));
      return answer(a, euler::kev(b, h));
    }
    case 5: case 6: {
      if (loops.empty()) break;
      LoopH l = any_loop();
      Corner c1 = b.alive(l) ? corner_in(b, l, n) : Corner::in_lone(l);
      Corner c2 = b.alive(l) ? corner_in(b, l, n) : Corner::in_lone(l);
      Applied a = ask("mef", "mef(" + l.str() + ")", OpKind::make, euler::can_mef(b, c1, c2));
      auto r = euler::mef(b, c1, c2);
      if (answer(a, r).ok) a.inverse = [h = r->a](Body& body) { return euler::kef(body, h); };
      return a;
    }
    case 7: {
      HalfedgeH h = any_he();
      Applied a = ask("kef", "kef(" + h.str() + ")", OpKind::kill, euler::can_kef(b, h));
      return answer(a, euler::kef(b, h));
    }
    case 8: {
      HalfedgeH h = any_he();
      Applied a = ask("kemr", "kemr(" + h.str() + ")", OpKind::kill, euler::can_kemr(b, h));
      return answer(a, euler::kemr(b, h));
    }
    case 9: {
      if (faces.empty()) break;
      FaceH f = pick(faces, n);
      auto ls = b.loops_of(f);
      if (ls.size() < 2) break;
      LoopH l1 = pick(ls, n), l2 = ls[1 + n.below(ls.size() - 1)];
      Corner c1 = corner_in(b, l1, n), c2 = corner_in(b, l2, n);
      // mekr kills the ring: its public inverse kemr makes a ring with a new handle, so
      // only the journaled inverse restores an equal body (EachOperatorRollsBackAlone).
      Applied a = ask("mekr", "mekr(" + l1.str() + ", " + l2.str() + ")", OpKind::kill, euler::can_mekr(b, c1, c2));
      return answer(a, euler::mekr(b, c1, c2));
    }
    case 10: {
      FaceH f1 = any_face(), f2 = any_face();
      Applied a = ask("kfmrh", "kfmrh(" + f1.str() + ", " + f2.str() + ")", OpKind::kill, euler::can_kfmrh(b, f1, f2));
      return answer(a, euler::kfmrh(b, f1, f2));
    }
    case 11: {
      LoopH l = any_loop();
      FaceH keep = b.alive(l) && !b.is_border(l) ? b.face(l) : FaceH{};
      Applied a = ask("mfkrh", "mfkrh(" + l.str() + ")", OpKind::make, euler::can_mfkrh(b, l));
      auto r = euler::mfkrh(b, l);
      if (answer(a, r).ok) a.inverse = [keep, nf = r->face](Body& body) { return euler::kfmrh(body, keep, nf); };
      return a;
    }
    case 12: {
      FaceH f = any_face();
      Applied a = ask("kfmb", "kfmb(" + f.str() + ")", OpKind::kill, euler::can_kfmb(b, f));
      return answer(a, euler::kfmb(b, f));
    }
    case 13: {
      auto bs = b.border_cycles();
      LoopH l = junk || bs.empty() ? any_loop() : pick(bs, n);
      Applied a = ask("mfkb", "mfkb(" + l.str() + ")", OpKind::make, euler::can_mfkb(b, l));
      auto r = euler::mfkb(b, l);
      if (answer(a, r).ok) a.inverse = [f = r->face](Body& body) {
        auto k = euler::kfmb(body, f);
        return k ? Result<Done>(Done{}) : Result<Done>(k.error());
      };
      return a;
    }
    case 14: {
      HalfedgeH h = any_he();
      if (n.below(2) == 0) {
        geo::Vec3 p = point(n);
        Applied a = ask("semv", "semv(" + h.str() + ")", OpKind::make, euler::can_semv(b, h, p));
        auto r = euler::semv(b, h, p);
        if (answer(a, r).ok) a.inverse = [h](Body& body) { return euler::jekv(body, h); };
        return a;
      }
      Applied a = ask("jekv", "jekv(" + h.str() + ")", OpKind::kill, euler::can_jekv(b, h));
      return answer(a, euler::jekv(b, h));
    }
  }
  Applied none;
  none.what = "none";
  return none;
}

std::string kernel_bug(const Applied& a) {
  if (a.ok || a.code != ErrorCode::postcondition) return "";
  return a.what + " refused with postcondition (a kernel bug): " + a.error;
}

}  // namespace kintsugi::testing

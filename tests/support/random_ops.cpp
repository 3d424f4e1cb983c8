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

template <class T>
Applied done(std::string what, const Result<T>& r, OpKind kind) {
  Applied a;
  a.what = std::move(what);
  a.ok = r.ok();
  a.kind = kind;
  if (!r.ok()) a.error = r.error().message;
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
      auto r = euler::mvfs(b, point(n));
      Applied a = done("mvfs", r, OpKind::make);
      if (r) a.inverse = [f = r->face](Body& x) { return euler::kvfs(x, f); };
      return a;
    }
    case 1: {
      FaceH f = any_face();
      return done("kvfs(" + f.str() + ")", euler::kvfs(b, f), OpKind::kill);
    }
    case 2: {
      if (loops.empty()) break;
      LoopH l = any_loop();
      Corner c = b.alive(l) ? corner_in(b, l, n) : Corner::in_lone(l);
      auto r = euler::mev(b, c, point(n));
      Applied a = done("mev(" + (c.he.valid() ? c.he.str() : c.lone.str()) + ")", r, OpKind::make);
      if (r) a.inverse = [x = r->x](Body& body) { return euler::kev(body, x); };
      return a;
    }
    case 3: {
      if (verts.empty()) break;
      VertexH v = pick(verts, n);
      auto outs = b.outgoing(v);
      if (outs.size() < 2) break;
      HalfedgeH h1 = pick(outs, n), h2 = pick(outs, n);
      auto r = euler::mev_split(b, h1, h2, point(n));
      Applied a = done("mev_split(" + h1.str() + ", " + h2.str() + ")", r, OpKind::make);
      if (r) a.inverse = [x = r->x](Body& body) { return euler::kev(body, x); };
      return a;
    }
    case 4: {
      HalfedgeH h = any_he();
      return done("kev(" + h.str() + ")", euler::kev(b, h), OpKind::kill);
    }
    case 5: case 6: {
      if (loops.empty()) break;
      LoopH l = any_loop();
      Corner c1 = b.alive(l) ? corner_in(b, l, n) : Corner::in_lone(l);
      Corner c2 = b.alive(l) ? corner_in(b, l, n) : Corner::in_lone(l);
      auto r = euler::mef(b, c1, c2);
      Applied a = done("mef(" + l.str() + ")", r, OpKind::make);
      if (r) a.inverse = [h = r->a](Body& body) { return euler::kef(body, h); };
      return a;
    }
    case 7: {
      HalfedgeH h = any_he();
      return done("kef(" + h.str() + ")", euler::kef(b, h), OpKind::kill);
    }
    case 8: {
      HalfedgeH h = any_he();
      auto r = euler::kemr(b, h);
      return done("kemr(" + h.str() + ")", r, OpKind::kill);
    }
    case 9: {
      if (faces.empty()) break;
      FaceH f = pick(faces, n);
      auto ls = b.loops_of(f);
      if (ls.size() < 2) break;
      LoopH l1 = pick(ls, n), l2 = ls[1 + n.below(ls.size() - 1)];
      auto r = euler::mekr(b, corner_in(b, l1, n), corner_in(b, l2, n));
      // mekr kills the ring: its public inverse kemr makes a ring with a new handle, so
      // only the journaled inverse restores an equal body (EachOperatorRollsBackAlone).
      return done("mekr(" + l1.str() + ", " + l2.str() + ")", r, OpKind::kill);
    }
    case 10: {
      FaceH f1 = any_face(), f2 = any_face();
      return done("kfmrh(" + f1.str() + ", " + f2.str() + ")", euler::kfmrh(b, f1, f2), OpKind::kill);
    }
    case 11: {
      LoopH l = any_loop();
      FaceH keep = b.alive(l) && !b.is_border(l) ? b.face(l) : FaceH{};
      auto r = euler::mfkrh(b, l);
      Applied a = done("mfkrh(" + l.str() + ")", r, OpKind::make);
      if (r) a.inverse = [keep, nf = r->face](Body& body) { return euler::kfmrh(body, keep, nf); };
      return a;
    }
    case 12: {
      FaceH f = any_face();
      return done("kfmb(" + f.str() + ")", euler::kfmb(b, f), OpKind::kill);
    }
    case 13: {
      auto bs = b.border_cycles();
      LoopH l = junk || bs.empty() ? any_loop() : pick(bs, n);
      auto r = euler::mfkb(b, l);
      Applied a = done("mfkb(" + l.str() + ")", r, OpKind::make);
      if (r) a.inverse = [f = r->face](Body& body) {
        auto k = euler::kfmb(body, f);
        return k ? Result<Done>(Done{}) : Result<Done>(k.error());
      };
      return a;
    }
    case 14: {
      HalfedgeH h = any_he();
      if (n.below(2) == 0) {
        auto r = euler::semv(b, h, point(n));
        Applied a = done("semv(" + h.str() + ")", r, OpKind::make);
        if (r) a.inverse = [h](Body& body) { return euler::jekv(body, h); };
        return a;
      }
      return done("jekv(" + h.str() + ")", euler::jekv(b, h), OpKind::kill);
    }
  }
  Applied none;
  none.what = "none";
  return none;
}

}  // namespace kintsugi::testing

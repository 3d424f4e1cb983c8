// The scalable family: a plate with a k x k grid of features (blocks, pyramids,
// cylindrical bosses), each feature carrying a defect with probability `defect_rate`.
// Features and defects are chosen one cell at a time so that the face count lands on the
// request (every choice's face count is known in advance), and every step is local: the
// whole build is linear in the number of faces.
#include "kernel/builders.h"
#include "zoo/defects.h"
#include "zoo/paper_build.h"

#include <cmath>
#include <stdexcept>

namespace kintsugi::zoo {

namespace {

constexpr double kCell = 10, kTol = 0.2;

enum class Feature { block, pyramid, cylinder };

struct Choice {
  Feature feature;
  std::optional<ProblemType> defect;
  std::size_t faces;  // faces this adds to the body
};

std::size_t feature_faces(Feature f) { return f == Feature::block ? 5 : f == Feature::pyramid ? 4 : 2; }

// Defects each feature can carry, with the faces each adds.
std::vector<std::pair<ProblemType, std::size_t>> defects_for(Feature f) {
  using P = ProblemType;
  switch (f) {
    case Feature::block:
      return {{P::face_gap, 0},        {P::edge_gap, 0},         {P::multi_face_gap, 0},
              {P::small_face_chain, 2}, {P::sliver_face, 1},      {P::short_edge_chain, 0},
              {P::same_geometry_faces, 1}, {P::small_face, 1},    {P::mergeable_edges, 0}};
    case Feature::pyramid: return {{P::small_face, 1}, {P::short_edge, 0}, {P::mergeable_edges, 0}};
    case Feature::cylinder: return {{P::mergeable_edges, 0}, {P::short_edge_chain, 0}};
  }
  return {};
}

double u(Rng& r) { return r.uniform(0.3, 0.8); }

// The top corner of a block's top face at loop position i, and the half-edge leaving it.
KnownDefect block_defect(Body& b, FaceH top, FaceH side, ProblemType t, Rng& rng) {
  std::vector<HalfedgeH> hs = b.loop_halfedges(b.outer_loop(top));
  HalfedgeH h = hs[rng.below(hs.size())];
  VertexH corner = b.origin(h);
  double len = (b.point(b.target(h)) - b.point(corner)).norm();
  switch (t) {
    case ProblemType::face_gap: {
      Vec3 c = Vec3::Zero();
      for (HalfedgeH x : hs) c += b.point(b.origin(x));
      return make::face_gap(b, top, c / double(hs.size()), 0.5 * kTol * u(rng), 3 + int(rng.below(4)));
    }
    case ProblemType::edge_gap: {
      double g = kTol * u(rng), s0 = rng.uniform(0.3, 0.7) * (len - g);
      return make::edge_gap(b, h, s0, s0 + g, 0.5 * kTol * u(rng), 1 + int(rng.below(3)));
    }
    case ProblemType::multi_face_gap: return make::corner_gap(b, corner, 0.3 * kTol * u(rng));
    case ProblemType::small_face_chain: return make::small_face_chain(b, corner, 0.25 * kTol * u(rng), rng);
    case ProblemType::sliver_face: return make::chamfer(b, edge_of(h), top, 0.5 * kTol * u(rng), 0.5 * kTol * u(rng));
    case ProblemType::short_edge_chain: {
      std::vector<double> pieces(2 + rng.below(3));
      double total = 0;
      for (double& p : pieces) total += (p = kTol * u(rng));
      return make::cut_edge(b, h, rng.uniform(0.3, 0.7) * (len - total), pieces);
    }
    case ProblemType::same_geometry_faces:
      return make::split_and_tilt(b, top, edge_of(h), edge_of(hs[(std::find(hs.begin(), hs.end(), h) - hs.begin() + 2) % 4]),
                                  kTol * u(rng));
    case ProblemType::small_face: return make::small_face(b, corner, 0.5 * kTol * kTol * u(rng), &rng);
    case ProblemType::mergeable_edges: {
      HalfedgeH down = out_in_face(b, corner, side);  // any edge of the block will do
      return make::split_edge(b, down.valid() ? down : h, rng.uniform(0.3, 0.7));
    }
    default: break;
  }
  throw std::logic_error("no such block defect");
}

}  // namespace

ZooModel family(std::size_t faces, double defect_rate, std::uint64_t seed) {
  if (faces < 10 || faces > 10'000'000) throw std::invalid_argument("the family has 10 to 10,000,000 faces");
  if (!(defect_rate >= 0 && defect_rate <= 1)) throw std::invalid_argument("the defect rate is between 0 and 1");
  Rng rng(seed);
  // Enough cells for the smallest features (2 faces each), in a square grid.
  std::size_t cells = (faces - 6) / 2 + 1, k = std::size_t(std::ceil(std::sqrt(double(cells))));
  Body b = build::box(double(k) * kCell, double(k) * kCell, 5);
  b.set_journaling(false);  // a bulk build that is never rolled back
  FaceH plate = face_facing(b, Vec3::UnitZ(), Vec3(0, 0, 5));
  ZooModel m;
  m.tolerance = kTol;
  std::size_t count = 6;
  for (std::size_t cell = 0; cell < k * k && count + 2 <= faces; ++cell) {
    std::size_t room = faces - count;
    // Prefer the mix (blocks, pyramids, cylinders equally); take what still fits.
    std::vector<Feature> fits;
    for (Feature f : {Feature::block, Feature::pyramid, Feature::cylinder})
      if (feature_faces(f) <= room) fits.push_back(f);
    Feature f = fits[rng.below(fits.size())];
    std::optional<ProblemType> defect;
    if (rng.unit() < defect_rate) {
      std::vector<std::pair<ProblemType, std::size_t>> ds, ok;
      for (auto d : defects_for(f))
        if (feature_faces(f) + d.second <= room) ok.push_back(d);
      if (!ok.empty()) {
        auto d = ok[rng.below(ok.size())];
        defect = d.first;
        count += d.second;
      }
    }
    count += feature_faces(f);
    double cx = (double(cell % k) + 0.5) * kCell, cy = (double(cell / k) + 0.5) * kCell;
    Rng local(rng.raw());
    switch (f) {
      case Feature::block: {
        FaceH g = add_ring_face(b, plate, {{cx - 3, cy - 3, 5}, {cx + 3, cy - 3, 5}, {cx + 3, cy + 3, 5}, {cx - 3, cy + 3, 5}});
        std::vector<FaceH> sides = extrude(b, g, Vec3(0, 0, 4));
        if (defect) m.defects.push_back(block_defect(b, g, sides[0], *defect, local));
        break;
      }
      case Feature::pyramid: {
        FaceH g = add_ring_face(b, plate, {{cx - 3, cy - 3, 5}, {cx + 3, cy - 3, 5}, {cx + 3, cy + 3, 5}, {cx - 3, cy + 3, 5}});
        std::vector<FaceH> sides = raise_pyramid(b, g, Vec3(cx, cy, 10));
        HalfedgeH h = b.first(b.outer_loop(sides[0]));
        while (b.point(b.origin(h)).z() < 9.999) h = b.next(h);
        VertexH apex = b.origin(h);
        if (defect == ProblemType::small_face) m.defects.push_back(make::small_face(b, apex, 0.5 * kTol * kTol * u(local), &local));
        if (defect == ProblemType::short_edge) m.defects.push_back(make::apex_short_edge(b, apex, kTol * u(local), local));
        if (defect == ProblemType::mergeable_edges) m.defects.push_back(make::split_edge(b, h, local.uniform(0.3, 0.7)));
        break;
      }
      case Feature::cylinder: {
        FaceH g = add_circle_face(b, plate, Vec3(cx, cy, 5), 3);
        extrude_disc(b, g, Vec3(0, 0, 4), 3, Vec3(cx, cy, 5));
        if (defect) {
          // The top circle: the one edge of the face the disc became.
          HalfedgeH top = HalfedgeH{};
          for (HalfedgeH x : b.loop_halfedges(b.outer_loop(g)))
            if (b.origin(x) == b.target(x) && b.point(b.origin(x)).z() > 8) top = x;
          if (*defect == ProblemType::mergeable_edges) m.defects.push_back(make::split_edge(b, top, local.uniform(0.3, 0.7)));
          else
            m.defects.push_back(make::cut_edge(b, top, local.uniform(2, 8), {kTol * u(local), kTol * u(local)}));
        }
        break;
      }
    }
  }
  m.body = std::move(b);
  m.source = "family faces=" + std::to_string(faces) + " defect_rate=" + std::to_string(defect_rate) +
             " seed=" + std::to_string(seed);
  compact(m);
  m.body.set_journaling(true);
  return m;
}

}  // namespace kintsugi::zoo

// Typed integer handles for the B-rep entities.
//
// A handle is an index into the body's storage for one kind of entity. The tag makes
// a FaceH and an EdgeH different types, so one cannot be passed where the other is
// wanted. Handles are invalid by default and print themselves ("v3", "h7", "f2"), so
// error messages and test failures are readable.
//
// Stability: a handle stays valid while its element lives. Killing an element leaves
// a tombstone; slots are never reused silently. Only Body::compact() renumbers, and it
// returns the old→new maps (spec/entities.md).
#pragma once

#include <compare>
#include <cstdint>
#include <functional>
#include <ostream>
#include <string>

namespace kintsugi {

template <class Tag>
class Handle {
 public:
  using Index = std::uint32_t;
  static constexpr Index kInvalid = ~Index{0};

  constexpr Handle() = default;
  constexpr explicit Handle(Index i) : idx_(i) {}

  constexpr Index idx() const { return idx_; }
  constexpr bool valid() const { return idx_ != kInvalid; }
  constexpr auto operator<=>(const Handle&) const = default;

  std::string str() const {
    return valid() ? std::string(1, Tag::prefix) + std::to_string(idx_)
                   : std::string(1, Tag::prefix) + "-";
  }

 private:
  Index idx_ = kInvalid;
};

template <class Tag>
std::ostream& operator<<(std::ostream& os, Handle<Tag> h) {
  return os << h.str();
}

struct VertexTag { static constexpr char prefix = 'v'; };
struct HalfedgeTag { static constexpr char prefix = 'h'; };
struct EdgeTag { static constexpr char prefix = 'e'; };
struct LoopTag { static constexpr char prefix = 'l'; };
struct FaceTag { static constexpr char prefix = 'f'; };
struct ShellTag { static constexpr char prefix = 's'; };

using VertexH = Handle<VertexTag>;
using HalfedgeH = Handle<HalfedgeTag>;
using EdgeH = Handle<EdgeTag>;
using LoopH = Handle<LoopTag>;
using FaceH = Handle<FaceTag>;
using ShellH = Handle<ShellTag>;

// Half-edges come in pairs: edge e owns half-edges 2e and 2e+1. The twin and the edge
// are derived from the index (as in pmp-library), not stored: less memory and one
// invariant fewer. The curve of edge e runs in the direction of half-edge 2e.
inline HalfedgeH twin(HalfedgeH h) { return HalfedgeH(h.idx() ^ 1u); }
inline EdgeH edge_of(HalfedgeH h) { return EdgeH(h.idx() >> 1); }
inline HalfedgeH halfedge_of(EdgeH e, unsigned side) { return HalfedgeH(2 * e.idx() + (side & 1u)); }

}  // namespace kintsugi

template <class Tag>
struct std::hash<kintsugi::Handle<Tag>> {
  std::size_t operator()(kintsugi::Handle<Tag> h) const noexcept { return std::hash<std::uint32_t>{}(h.idx()); }
};

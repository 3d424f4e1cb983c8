// The paper's eleven topological problem types (section 1.1), in the paper's repair
// order. These names are used everywhere: code, spec/problems.md, JSON, reports, the
// defect injector and `meta.defects` in generated files.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <string_view>

namespace kintsugi {

enum class ProblemType : int {
  face_gap = 1,
  edge_gap = 2,
  multi_face_gap = 3,
  pinched_face = 4,
  small_face_chain = 5,
  sliver_face = 6,
  short_edge_chain = 7,
  same_geometry_faces = 8,
  small_face = 9,
  mergeable_edges = 10,
  short_edge = 11,
};

inline constexpr std::array<ProblemType, 11> kAllProblemTypes = {
    ProblemType::face_gap,         ProblemType::edge_gap,          ProblemType::multi_face_gap,
    ProblemType::pinched_face,     ProblemType::small_face_chain,  ProblemType::sliver_face,
    ProblemType::short_edge_chain, ProblemType::same_geometry_faces, ProblemType::small_face,
    ProblemType::mergeable_edges,  ProblemType::short_edge,
};

inline const char* problem_name(ProblemType t) {
  switch (t) {
    case ProblemType::face_gap: return "face_gap";
    case ProblemType::edge_gap: return "edge_gap";
    case ProblemType::multi_face_gap: return "multi_face_gap";
    case ProblemType::pinched_face: return "pinched_face";
    case ProblemType::small_face_chain: return "small_face_chain";
    case ProblemType::sliver_face: return "sliver_face";
    case ProblemType::short_edge_chain: return "short_edge_chain";
    case ProblemType::same_geometry_faces: return "same_geometry_faces";
    case ProblemType::small_face: return "small_face";
    case ProblemType::mergeable_edges: return "mergeable_edges";
    case ProblemType::short_edge: return "short_edge";
  }
  return "?";
}

inline std::optional<ProblemType> problem_from_name(std::string_view s) {
  for (ProblemType t : kAllProblemTypes)
    if (s == problem_name(t)) return t;
  return std::nullopt;
}

// 1-based position in the paper's order (Table 1's rows and columns).
inline int problem_order(ProblemType t) { return static_cast<int>(t); }

}  // namespace kintsugi

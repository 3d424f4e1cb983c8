// The Euler operators the kernel exports (kernel/euler.h), with the change each makes to
// the counts: one table, so that a test can hold spec/operators.md to it (every operator
// has its row there, with these Δ) and a property can hold the operators to it (a
// successful operator changes the counts by exactly its Δ, or its variant's).
#pragma once

#include <array>
#include <string_view>

namespace kintsugi {

// Change in V vertices, E edges, F faces, L face loops, S shells, B border cycles,
// R rings, H genus.
struct CountDelta {
  int v = 0, e = 0, f = 0, l = 0, s = 0, b = 0, r = 0, h = 0;
  constexpr bool operator==(const CountDelta&) const = default;
};

struct OperatorInfo {
  std::string_view name;   // as in euler::<name> and in spec/operators.md's first column
  std::string_view file;   // kernel/op_<pair>.cpp: its query, raw step, record and undo
  CountDelta delta;
  bool has_variant = false;  // a second case with another Δ (kef into a border cycle)
  CountDelta variant{};
};

inline constexpr std::array<OperatorInfo, 15> kOperators{{
    {"mvfs", "kernel/op_mvfs_kvfs.cpp", {.v = 1, .f = 1, .l = 1, .s = 1}},
    {"kvfs", "kernel/op_mvfs_kvfs.cpp", {.v = -1, .f = -1, .l = -1, .s = -1}},
    {"mev", "kernel/op_mev_kev.cpp", {.v = 1, .e = 1}},
    {"mev_split", "kernel/op_mev_kev.cpp", {.v = 1, .e = 1}},
    {"kev", "kernel/op_mev_kev.cpp", {.v = -1, .e = -1}},
    {"mef", "kernel/op_mef_kef.cpp", {.e = 1, .f = 1, .l = 1}},
    {"kef", "kernel/op_mef_kef.cpp", {.e = -1, .f = -1, .l = -1}, true, {.e = -1, .b = -1}},
    {"kemr", "kernel/op_kemr_mekr.cpp", {.e = -1, .l = 1, .r = 1}},
    {"mekr", "kernel/op_kemr_mekr.cpp", {.e = 1, .l = -1, .r = -1}},
    {"kfmrh", "kernel/op_kfmrh_mfkrh.cpp", {.f = -1, .r = 1, .h = 1}},
    {"mfkrh", "kernel/op_kfmrh_mfkrh.cpp", {.f = 1, .r = -1, .h = -1}},
    {"kfmb", "kernel/op_kfmb_mfkb.cpp", {.f = -1, .l = -1, .b = 1}},
    {"mfkb", "kernel/op_kfmb_mfkb.cpp", {.f = 1, .l = 1, .b = -1}},
    {"semv", "kernel/op_semv_jekv.cpp", {.v = 1, .e = 1}},
    {"jekv", "kernel/op_semv_jekv.cpp", {.v = -1, .e = -1}},
}};

constexpr const OperatorInfo* find_operator(std::string_view name) {
  for (const auto& op : kOperators)
    if (op.name == name) return &op;
  return nullptr;
}

}  // namespace kintsugi

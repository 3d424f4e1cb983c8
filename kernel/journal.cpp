#include "kernel/journal.h"

namespace kintsugi {

const char* op_name(Op op) {
  switch (op) {
    case Op::mvfs: return "mvfs";
    case Op::kvfs: return "kvfs";
    case Op::mev: return "mev";
    case Op::kev: return "kev";
    case Op::mef: return "mef";
    case Op::kef: return "kef";
    case Op::kemr: return "kemr";
    case Op::mekr: return "mekr";
    case Op::kfmrh: return "kfmrh";
    case Op::mfkrh: return "mfkrh";
    case Op::semv: return "semv";
    case Op::jekv: return "jekv";
    case Op::kfmb: return "kfmb";
    case Op::mfkb: return "mfkb";
    case Op::set_point: return "set_point";
    case Op::set_curve: return "set_curve";
    case Op::set_surface: return "set_surface";
  }
  return "?";
}

std::vector<std::string> Journal::op_names(std::size_t from) const {
  std::vector<std::string> out;
  for (std::size_t i = from; i < entries_.size(); ++i) out.emplace_back(op_name(entries_[i].op()));
  return out;
}

void Journal::clear() {
  entries_.clear();
  points_.clear();
  curves_.clear();
  surfaces_.clear();
  senses_.clear();
  lists_.clear();
  firsts_.clear();
  outs_.clear();
}

}  // namespace kintsugi

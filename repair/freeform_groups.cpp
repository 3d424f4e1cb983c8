#include "repair/freeform_groups.h"

#include "geometry/freeform.h"

#include <algorithm>
#include <atomic>
#include <thread>
#include <unordered_map>

namespace kintsugi {
namespace {

// What identifies a free-form surface's evaluation state: its cache, or its slot until
// it has one (the data's own); nullptr for an analytic surface.
const void* freeform_state(const geo::Surface& s) {
  const std::shared_ptr<const void>* slot = geo::cache_slot(s);
  if (!slot) return nullptr;
  return *slot ? slot->get() : static_cast<const void*>(slot);
}

}  // namespace

std::vector<std::vector<FaceH>> evaluation_groups(const Body& b, const std::vector<FaceH>& faces) {
  std::vector<std::vector<FaceH>> groups;
  std::unordered_map<const void*, std::size_t> group_of;
  for (FaceH f : faces) {
    const void* state = freeform_state(b.surface(f));
    if (!state) {
      groups.push_back({f});
      continue;
    }
    auto [it, added] = group_of.emplace(state, groups.size());
    if (added) groups.emplace_back();
    groups[it->second].push_back(f);
  }
  return groups;
}

void prepare_freeform(const Body& b, const std::vector<FaceH>& faces) {
  const geo::FreeformBackend* ff = geo::freeform_backend();
  if (!ff) return;
  for (FaceH f : faces) {
    if (geo::is_freeform(b.surface(f))) (void)ff->surface_problem(b.surface(f));
    for (LoopH l : b.loops_of(f))
      for (HalfedgeH h : b.loop_halfedges(l))
        if (geo::is_freeform(b.curve(edge_of(h)))) (void)ff->curve_problem(b.curve(edge_of(h)));
  }
}

void for_each_grouped(const std::vector<std::vector<FaceH>>& groups, int threads, const std::function<void(FaceH)>& work) {
  std::atomic<std::size_t> next{0};
  auto run = [&] {
    for (std::size_t i; (i = next.fetch_add(1)) < groups.size();)
      for (FaceH f : groups[i]) work(f);
  };
  const int n = std::max(1, std::min<int>(threads, int(groups.size())));
  std::vector<std::thread> pool;
  for (int k = 1; k < n; ++k) pool.emplace_back(run);
  run();
  for (std::thread& t : pool) t.join();
}

}  // namespace kintsugi

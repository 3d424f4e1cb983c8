#include "kernel/huge_pages.h"

#include <cstdint>

#if defined(__linux__)
#include <sys/mman.h>
#include <unistd.h>
#endif

namespace kintsugi {

void advise_huge_pages(void* p, std::size_t n) {
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  if (n < kHugePagesFrom) return;
  static const std::uintptr_t page = std::uintptr_t(::sysconf(_SC_PAGESIZE));
  const std::uintptr_t first = (std::uintptr_t(p) + page - 1) / page * page;
  const std::uintptr_t last = (std::uintptr_t(p) + n) / page * page;
  // The answer is ignored: without huge pages the memory is the same, only slower to fault in.
  if (last > first) (void)::madvise(reinterpret_cast<void*>(first), last - first, MADV_HUGEPAGE);
#else
  (void)p;
  (void)n;
#endif
}

}  // namespace kintsugi

// Memory in huge pages: a large buffer faults in per 2 MiB instead of per 4 KiB.
//
// Where this matters: on the virtual machines this project is measured on, a page fault
// costs about 13 µs (touching a fresh 42 MB buffer: 0.13 s in 4-KiB pages, 0.013 s in
// huge pages; docs/benchmarks.md, "Page faults"). A million-face body is 0.75 GB, and
// reading or building it spent more time faulting pages in than filling them.
#pragma once

#include <cstddef>

namespace kintsugi {

// Asks that the whole pages inside [p, p + n) be backed by huge pages where the system
// allows it (Linux's transparent huge pages set to "madvise" or "always"); for n of 4 MiB
// or more, and before the memory is first touched. Does nothing elsewhere, and never fails.
void advise_huge_pages(void* p, std::size_t n);

// Below this size advise_huge_pages does nothing: a huge page would be mostly empty.
inline constexpr std::size_t kHugePagesFrom = std::size_t(1) << 22;

}  // namespace kintsugi

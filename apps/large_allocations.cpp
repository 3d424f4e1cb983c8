// The programs' operator new: large blocks in huge pages (kernel/huge_pages.h).
//
// Linked into the executables only (kintsugi, kintsugi-bench), not into the libraries: a
// program that embeds kintsugi keeps its own allocator. A block of 4 MiB or more — a
// body's arrays, a reader's descriptions, a detector's index — is advised for huge pages
// before anything touches it, which on a virtual machine halves the time to read a large
// model (docs/benchmarks.md, "Page faults"). Everything else is the standard's: malloc,
// the new-handler loop, std::bad_alloc. The aligned forms are left to the library (they
// pair with their own deletes).
//
// Not under AddressSanitizer or ThreadSanitizer: they bring their own operator new, whose
// checks (a delete that does not match its new) a replacement would switch off.
#include "kernel/huge_pages.h"

#include <cstdlib>
#include <new>

#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
#define KINTSUGI_REPLACE_NEW 0
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer) || __has_feature(memory_sanitizer)
#define KINTSUGI_REPLACE_NEW 0
#endif
#endif
#ifndef KINTSUGI_REPLACE_NEW
#define KINTSUGI_REPLACE_NEW 1
#endif

#if KINTSUGI_REPLACE_NEW

namespace {

void* allocate(std::size_t n) noexcept {
  if (n == 0) n = 1;
  for (;;) {
    if (void* p = std::malloc(n)) {
      if (n >= kintsugi::kHugePagesFrom) kintsugi::advise_huge_pages(p, n);
      return p;
    }
    std::new_handler handler = std::get_new_handler();
    if (!handler) return nullptr;
    handler();  // frees memory, or throws
  }
}

void* allocate_or_throw(std::size_t n) {
  if (void* p = allocate(n)) return p;
  throw std::bad_alloc();
}

}  // namespace

void* operator new(std::size_t n) { return allocate_or_throw(n); }
void* operator new[](std::size_t n) { return allocate_or_throw(n); }
void* operator new(std::size_t n, const std::nothrow_t&) noexcept {
  try {
    return allocate(n);
  } catch (...) {
    return nullptr;
  }
}
void* operator new[](std::size_t n, const std::nothrow_t& t) noexcept { return operator new(n, t); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
void operator delete(void* p, const std::nothrow_t&) noexcept { std::free(p); }
void operator delete[](void* p, const std::nothrow_t&) noexcept { std::free(p); }

#endif

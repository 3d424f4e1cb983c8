#include "kernel/threads.h"

#include <algorithm>
#include <cstdlib>
#include <thread>

namespace kintsugi {

int threads_from_environment() {
  if (const char* v = std::getenv("KINTSUGI_THREADS")) {
    char* end = nullptr;
    const long n = std::strtol(v, &end, 10);
    if (*v && end && *end == '\0' && n >= 1 && n <= 64) return int(n);
  }
  const unsigned hw = std::thread::hardware_concurrency();
  return int(std::clamp(hw, 1u, 8u));
}

}  // namespace kintsugi

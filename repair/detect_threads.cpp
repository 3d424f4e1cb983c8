#include "repair/detect_threads.h"

#include <algorithm>
#include <atomic>
#include <cstdlib>
#include <string>
#include <thread>

namespace kintsugi {

namespace {
std::atomic<int> chosen{0};

int from_environment() {
  if (const char* v = std::getenv("KINTSUGI_THREADS")) {
    char* end = nullptr;
    const long n = std::strtol(v, &end, 10);
    if (*v && end && *end == '\0' && n >= 1 && n <= 64) return int(n);
  }
  const unsigned hw = std::thread::hardware_concurrency();
  return int(std::clamp(hw, 1u, 8u));
}
}  // namespace

int detect_threads() {
  const int n = chosen.load();
  return n > 0 ? n : from_environment();
}

void set_detect_threads(int n) { chosen.store(std::max(n, 0)); }

}  // namespace kintsugi

#include "repair/detect_threads.h"

#include "kernel/threads.h"

#include <algorithm>
#include <atomic>

namespace kintsugi {

namespace {
std::atomic<int> chosen{0};
}  // namespace

int detect_threads() {
  const int n = chosen.load();
  return n > 0 ? n : threads_from_environment();
}

void set_detect_threads(int n) { chosen.store(std::max(n, 0)); }

}  // namespace kintsugi

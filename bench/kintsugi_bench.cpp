// kintsugi-bench: measurements written up in docs/benchmarks.md.
//
//   kintsugi-bench memory --faces N
//     Builds the grid box with about N faces in memory (kernel/builders.h grid_box) and
//     reports the peak resident set size from the operating system (getrusage), as a
//     last line of JSON: {"faces", "half_edges", "peak_rss_bytes", "bytes_per_half_edge",
//     "baseline_rss_bytes", "seconds"}. The peak includes the process's baseline (the
//     binary and its libraries), measured before building and reported separately.
#include "invariants/topology_check.h"
#include "kernel/builders.h"

#include <nlohmann/json.hpp>

#include <chrono>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <string>
#include <sys/resource.h>

namespace {

long long peak_rss_bytes() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return static_cast<long long>(u.ru_maxrss) * 1024;  // Linux reports kilobytes
}

int usage(std::ostream& os, int code) {
  os << "usage: kintsugi-bench memory --faces N [--check]\n"
        "  Builds the grid box with about N faces (6..100000000) and prints its peak memory.\n"
        "  --check  also run the full topology check on the result (adds its own memory)\n";
  return code;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc >= 2 && (std::strcmp(argv[1], "--help") == 0 || std::strcmp(argv[1], "-h") == 0)) return usage(std::cout, 0);
  if (argc < 2 || std::strcmp(argv[1], "memory") != 0) return usage(std::cerr, 2);
  long long faces = -1;
  bool check = false;
  for (int i = 2; i < argc; ++i) {
    std::string a = argv[i];
    if (a == "--faces" && i + 1 < argc) {
      char* end = nullptr;
      faces = std::strtoll(argv[++i], &end, 10);
      if (*end != '\0') faces = -1;
    } else if (a == "--check") {
      check = true;
    } else if (a == "--help") {
      return usage(std::cout, 0);
    } else {
      std::cerr << "kintsugi-bench: unknown argument '" << a << "'\n";
      return usage(std::cerr, 2);
    }
  }
  if (faces < 6 || faces > 100'000'000) {
    std::cerr << "kintsugi-bench memory: --faces needs a whole number from 6 to 100000000\n";
    return 2;
  }
  long long baseline = peak_rss_bytes();
  auto t0 = std::chrono::steady_clock::now();
  kintsugi::Body b = kintsugi::build::grid_box(std::size_t(faces));
  double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  long long peak = peak_rss_bytes();
  auto c = b.counts();
  std::size_t half_edges = 2 * c.edges;
  std::cout << "grid box: " << c.faces << " faces, " << c.edges << " edges, " << c.vertices << " vertices, built in "
            << seconds << " s\n";
  if (check) {
    auto v = kintsugi::check_topology(b);
    std::cout << "topology check: " << v.size() << " violations\n";
    if (!v.empty()) return 1;
  }
  nlohmann::json j = {{"faces", c.faces},
                      {"half_edges", half_edges},
                      {"peak_rss_bytes", peak},
                      {"baseline_rss_bytes", baseline},
                      {"bytes_per_half_edge", double(peak) / double(half_edges)},
                      {"seconds", seconds}};
  std::cout << j.dump() << "\n";
  return 0;
}

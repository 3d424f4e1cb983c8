// kintsugi-bench: measurements written up in docs/benchmarks.md.
//
//   kintsugi-bench memory --faces N
//     Builds the grid box with about N faces in memory (kernel/builders.h grid_box) and
//     reports the peak resident set size from the operating system (getrusage), as a
//     last line of JSON: {"faces", "half_edges", "peak_rss_bytes", "bytes_per_half_edge",
//     "baseline_rss_bytes", "seconds"}. The peak includes the process's baseline (the
//     binary and its libraries), measured before building and reported separately.
//
//   kintsugi-bench solvers
//     The cost of geo::meet_point and geo::fit_surface_like (bench/solvers_bench.h).
//
//   kintsugi-bench io --faces N [--rate R] [--seed S] [--dir D]
//     The native JSON writer and reader on the scalable family (zoo::family, N faces,
//     defect rate R, default 0.1, seed S, default 1). Builds the model once, then runs
//     each step in a child process of its own, so that each step's peak resident set size
//     is its own (it includes the model, which the child shares with the parent: the
//     parent's resident set size after building the model is "model_rss_bytes"):
//       write_string  write_native into a std::string;
//       write_file    write_native_file (streamed into an atomic temporary file in D,
//                     default the system temporary directory, fsynced, renamed);
//       read_file     read_native_file of that file: parse, validate, assemble, and the
//                     full topology check; then, outside the timing, Body::equals;
//       read_file_one_thread  the same with KINTSUGI_THREADS=1 (the text read whole on
//                     one thread rather than in two halves on two).
//     Each read runs twice, taking turns, and the faster of each is reported (the first
//     read after the writes is slower, whichever reader does it).
//     Last line: JSON {"faces", "bytes", "model_seconds", "model_rss_bytes", "steps":
//     {step: {"seconds", "peak_rss_bytes"}}, "read_back_equal"}.
//
//   kintsugi-bench beautify [--faces N,N,...] [--rate R] [--seed S] [--on-plate K] [--detect-only]
//     Detection and beautify on the scalable family (zoo::family; default sizes 10^4 and
//     10^5 faces, rate 0.01, seed 1), each size in a child process of its own: the model
//     is built, detected (timed) and beautified as `kintsugi beautify` does it
//     (api::beautify: the pipeline with the whole-body check once at the end and the
//     validity gate's OpenCASCADE half where it is built). --detect-only stops after
//     the detection. --on-plate K adds K defects on the plate (the face with a hole per
//     feature; short edge chains and mergeable edges, taking turns), where every repair
//     meets the face with the most loops in the model (issue 18).
//     Prints per size the seconds of detection, of beautify and of each pass, the peak
//     resident set size against the size after building the model; then the exponent
//     of a least-squares fit of log(seconds) on log(faces). Last line: JSON {"sizes":
//     [{"faces", "build_seconds", "model_rss_bytes", "detect_seconds",
//     "beautify_seconds", "passes": {type: s}, "repaired", "not_repaired",
//     "peak_rss_bytes"}], "exponent": {"detect", "beautify"}}.
#include "apps/api.h"
#include "bench/bench_child.h"
#include "bench/solvers_bench.h"
#ifdef KINTSUGI_HAVE_OCCT
#include "bench/occt_heal_bench.h"
#endif
#include "invariants/topology_check.h"
#include "io/native_json.h"
#include "repair/beautify.h"
#include "repair/detect.h"
#include "invariants/element_geometry.h"
#include "kernel/builders.h"
#include "zoo/zoo.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <string>
#include <vector>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

namespace {

using kintsugi::bench::current_rss_bytes;
using kintsugi::bench::json_in_child;
using kintsugi::bench::peak_rss_bytes;
using kintsugi::bench::seconds_since;

int usage(std::ostream& os, int code) {
  os << "usage: kintsugi-bench memory --faces N [--check]\n"
        "       kintsugi-bench io --faces N [--rate R] [--seed S] [--dir D]\n"
        "  memory  Builds the grid box with about N faces (6..100000000) and prints its peak memory.\n"
        "          --check  also run the full topology check on the result (adds its own memory)\n"
        "  io      Writes the scalable family with N faces (10..10000000) as native JSON, to a\n"
        "          string and (streamed, atomically) to a file in D, and reads the file back;\n"
        "          prints each step's time and peak memory (each step runs in a child process).\n"
        "       kintsugi-bench read FILE\n"
        "  read    Reads a native file in this process, as a fresh `kintsugi` process does (no\n"
        "          fork from a process that holds a model: a child writing into its parent's\n"
        "          freed heap pays a copy per page); prints the seconds and the peak memory.\n"
        "          KINTSUGI_THREADS=1 reads on one thread.\n"
        "       kintsugi-bench beautify [--faces N,N,...] [--rate R] [--seed S] [--on-plate K] [--detect-only]\n"
        "  beautify  Detects and beautifies the scalable family at each size (default\n"
        "          10000,100000; rate 0.01), each in a child process, as `kintsugi beautify`\n"
        "          does (the validity gate with OpenCASCADE's half where it is built); prints\n"
        "          seconds per pass, peak memory and the fitted exponent of time against faces.\n"
        "          --on-plate K   also inject K defects on the plate, the face with a hole per feature\n"
        "          --detect-only  time the whole-model detection only\n"
        "       kintsugi-bench occt-heal [--faces N] [--rate R] [--seed S] [--dir D]\n"
        "  occt-heal  Writes the family with N faces (default 10000; rate 0.01) to STEP in D\n"
        "          (default the temporary folder; kept there and reused) and heals it twice, each in\n"
        "          a child process: kintsugi (read, beautify) and OpenCASCADE (read, ShapeFix_Shape,\n"
        "          UnifySameDomain); prints both, the counts each left, and the ratio of the heal\n"
        "          times (built with OpenCASCADE only).\n"
        "       kintsugi-bench solvers\n"
        "  solvers Times geo::meet_point (2000 cases, 5 times) and geo::fit_surface_like (400\n"
        "          fits) on fixed random cases; prints the cost per call and checksums of the answers.\n";
  return code;
}

// Runs `step` in a child process; returns {"seconds", "peak_rss_bytes"} or {"error"}.
nlohmann::ordered_json in_child(const std::function<std::string()>& step) {
  return json_in_child([&]() -> nlohmann::ordered_json {
    auto t0 = std::chrono::steady_clock::now();
    std::string error = step();
    if (!error.empty()) return {{"error", error}};
    return {{"seconds", seconds_since(t0)}};
  });
}

int bench_read(int argc, char** argv) {
  if (argc != 3 || std::strcmp(argv[2], "--help") == 0) return usage(argc == 3 ? std::cout : std::cerr, argc == 3 ? 0 : 2);
  const auto t0 = std::chrono::steady_clock::now();
  std::string error;
  auto doc = kintsugi::io::read_native_file(argv[2], &error);
  const double seconds = seconds_since(t0);
  if (!doc) {
    std::cerr << "kintsugi-bench read: " << error << "\n";
    return 2;
  }
  const auto c = doc->body.counts();
  nlohmann::ordered_json out = {{"file", argv[2]},           {"faces", c.faces},
                                {"seconds", seconds},       {"peak_rss_bytes", peak_rss_bytes()}};
  std::cout << out.dump() << "\n";
  return 0;
}

int bench_io(int argc, char** argv) {
  long long faces = -1, seed = 1;
  double rate = 0.1;
  std::string dir = std::filesystem::temp_directory_path().string();
  for (int i = 2; i < argc; ++i) {
    std::string a = argv[i];
    auto value = [&]() -> const char* { return i + 1 < argc ? argv[++i] : ""; };
    char* end = nullptr;
    if (a == "--faces") {
      faces = std::strtoll(value(), &end, 10);
      if (*end != '\0') faces = -1;
    } else if (a == "--seed") {
      seed = std::strtoll(value(), &end, 10);
    } else if (a == "--rate") {
      rate = std::strtod(value(), &end);
    } else if (a == "--dir") {
      dir = value();
    } else if (a == "--help") {
      return usage(std::cout, 0);
    } else {
      std::cerr << "kintsugi-bench: unknown argument '" << a << "'\n";
      return usage(std::cerr, 2);
    }
  }
  if (faces < 10 || faces > 10'000'000) {
    std::cerr << "kintsugi-bench io: --faces needs a whole number from 10 to 10000000\n";
    return 2;
  }
  auto t0 = std::chrono::steady_clock::now();
  kintsugi::zoo::ZooModel m;
  try {
    m = kintsugi::zoo::family(std::size_t(faces), rate, std::uint64_t(seed));
  } catch (const std::exception& e) {
    std::cerr << "kintsugi-bench io: " << e.what() << "\n";
    return 2;
  }
  const double model_seconds = seconds_since(t0);
  const long long model_rss = current_rss_bytes();
  const nlohmann::json meta = m.meta();
  const auto c = m.body.counts();
  std::cout << "family: " << c.faces << " faces, " << c.edges << " edges, " << c.vertices << " vertices, built in "
            << model_seconds << " s, RSS " << model_rss / 1e6 << " MB (in every step's peak)\n";

  const std::string path = (std::filesystem::path(dir) / ("kintsugi-bench-io-" + std::to_string(::getpid()) + ".json")).string();
  nlohmann::ordered_json steps = nlohmann::ordered_json::object();
  steps["write_string"] = in_child([&] {
    std::string text = kintsugi::io::write_native(m.body, meta, "mm");
    return text.empty() ? std::string("empty document") : std::string();
  });
  steps["write_file"] = in_child([&] {
    std::string error;
    return kintsugi::io::write_native_file(path, m.body, meta, "mm", &error) ? std::string() : error;
  });
  std::error_code ec;
  const auto bytes = std::filesystem::file_size(path, ec);
  // Each read runs twice, the two readers taking turns, and the faster of each reader's
  // two is kept: the first read after the writes is slower whichever reader does it (11 s
  // against 5 s at 10^6 faces, also with the file read once beforehand), and a single
  // run would credit or blame whichever reader came first.
  auto read_step = [&](bool one_thread) {
    return in_child([&] {
      if (one_thread) ::setenv("KINTSUGI_THREADS", "1", 1);
      std::string error;
      auto doc = kintsugi::io::read_native_file(path, &error);
      return doc ? std::string() : error;
    });
  };
  auto faster = [](const nlohmann::ordered_json& a, const nlohmann::ordered_json& b) {
    if (a.contains("error") || b.contains("error")) return a.contains("error") ? a : b;
    return a["seconds"].get<double>() <= b["seconds"].get<double>() ? a : b;
  };
  nlohmann::ordered_json whole_first = read_step(true), halves_first = read_step(false);
  nlohmann::ordered_json whole_second = read_step(true), halves_second = read_step(false);
  steps["read_file"] = faster(halves_first, halves_second);
  steps["read_file_one_thread"] = faster(whole_first, whole_second);
  // Outside the timing: what was read is the body that was written.
  bool equal = false;
  {
    std::string error, why;
    auto doc = kintsugi::io::read_native_file(path, &error);
    equal = doc && doc->body.equals(m.body, &why) && doc->meta == meta;
    if (!equal) std::cerr << "kintsugi-bench io: read back differs: " << error << why << "\n";
  }
  std::filesystem::remove(path, ec);
  for (const auto& [name, r] : steps.items()) {
    if (r.contains("error")) {
      std::cout << name << ": " << r["error"].get<std::string>() << "\n";
      continue;
    }
    std::cout << name << ": " << r["seconds"].get<double>() << " s, peak RSS " << r["peak_rss_bytes"].get<double>() / 1e6
              << " MB\n";
  }
  nlohmann::ordered_json j = {{"faces", c.faces},
                              {"bytes", ec ? 0 : bytes},
                              {"model_seconds", model_seconds},
                              {"model_rss_bytes", model_rss},
                              {"steps", steps},
                              {"read_back_equal", equal}};
  std::cout << j.dump() << "\n";
  for (const auto& [name, r] : steps.items())
    if (r.contains("error")) return 1;
  return equal ? 0 : 1;
}

// The slope of the least-squares line through (log x, log y).
double loglog_slope(const std::vector<double>& x, const std::vector<double>& y) {
  const double n = double(x.size());
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double lx = std::log(x[i]), ly = std::log(y[i]);
    sx += lx, sy += ly, sxx += lx * lx, sxy += lx * ly;
  }
  const double d = n * sxx - sx * sx;
  return d > 0 ? (n * sxy - sx * sy) / d : 0.0;
}

// Injects k defects on the face with the most loops (the family's plate), short edge
// chains and mergeable edges taking turns; returns how many found a place.
long long inject_on_plate(kintsugi::zoo::ZooModel& m, long long k) {
  using namespace kintsugi;
  FaceH plate;
  std::size_t most = 0;
  for (FaceH f : m.body.faces())
    if (std::size_t l = m.body.loops_of(f).size(); l > most) most = l, plate = f;
  long long done = 0;
  for (long long i = 0; i < k; ++i) {
    const ProblemType t = i % 2 ? ProblemType::mergeable_edges : ProblemType::short_edge_chain;
    std::string why;
    if (auto d = zoo::inject(m.body, t, std::uint64_t(1 + i), plate.str(), m.tolerance, &why)) {
      m.defects.push_back(d->defect);
      ++done;
    }
  }
  return done;
}

int bench_beautify(int argc, char** argv) {
  std::vector<long long> sizes{10'000, 100'000};
  long long seed = 1;
  double rate = 0.01;
  bool detect_only = false;
  long long on_plate = 0;
  for (int i = 2; i < argc; ++i) {
    std::string a = argv[i];
    auto value = [&]() -> std::string { return i + 1 < argc ? argv[++i] : ""; };
    if (a == "--faces") {
      sizes.clear();
      std::string list = value();
      for (std::size_t at = 0; at <= list.size();) {
        const std::size_t comma = std::min(list.find(',', at), list.size());
        const std::string item = list.substr(at, comma - at);
        char* end = nullptr;
        const long long n = std::strtoll(item.c_str(), &end, 10);
        if (item.empty() || *end != '\0' || n < 10 || n > 10'000'000) {
          std::cerr << "kintsugi-bench beautify: --faces needs whole numbers from 10 to 10000000, comma-separated; got '"
                    << item << "'\n";
          return 2;
        }
        sizes.push_back(n);
        at = comma + 1;
      }
    } else if (a == "--seed") {
      char* end = nullptr;
      std::string v = value();
      seed = std::strtoll(v.c_str(), &end, 10);
      if (v.empty() || *end != '\0') {
        std::cerr << "kintsugi-bench beautify: --seed needs a whole number\n";
        return 2;
      }
    } else if (a == "--rate") {
      char* end = nullptr;
      std::string v = value();
      rate = std::strtod(v.c_str(), &end);
      if (v.empty() || *end != '\0' || !(rate >= 0 && rate <= 1)) {
        std::cerr << "kintsugi-bench beautify: --rate needs a number from 0 to 1\n";
        return 2;
      }
    } else if (a == "--on-plate") {
      char* end = nullptr;
      std::string v = value();
      on_plate = std::strtoll(v.c_str(), &end, 10);
      if (v.empty() || *end != '\0' || on_plate < 0 || on_plate > 100'000) {
        std::cerr << "kintsugi-bench beautify: --on-plate needs a whole number from 0 to 100000\n";
        return 2;
      }
    } else if (a == "--detect-only") {
      detect_only = true;
    } else if (a == "--help") {
      return usage(std::cout, 0);
    } else {
      std::cerr << "kintsugi-bench: unknown argument '" << a << "'\n";
      return usage(std::cerr, 2);
    }
  }
  using namespace kintsugi;
  nlohmann::ordered_json out = {{"sizes", nlohmann::ordered_json::array()}};
  std::vector<double> faces, detect_s, beautify_s;
  bool failed = false;
  for (long long n : sizes) {
    std::cerr << "kintsugi-bench beautify: " << n << " faces...\n";
    nlohmann::ordered_json r = json_in_child([&] {
      auto t0 = std::chrono::steady_clock::now();
      zoo::ZooModel m = zoo::family(std::size_t(n), rate, std::uint64_t(seed));
      nlohmann::ordered_json j;
      if (on_plate > 0) j["on_plate"] = inject_on_plate(m, on_plate);
      j["faces"] = m.body.counts().faces;
      j["build_seconds"] = seconds_since(t0);
      j["model_rss_bytes"] = current_rss_bytes();
      const geo::Tolerances tol = geo::Tolerances::for_model(m.tolerance, model_size(m.body));
      t0 = std::chrono::steady_clock::now();
      const Detection d = detect(m.body, tol);
      j["detect_seconds"] = seconds_since(t0);
      j["problems"] = d.problems.size();
      if (detect_only) return j;
      // The CLI's own path (apps/api.h): the validity gate with OpenCASCADE's half where
      // it is built, the whole-body check once at the end; its report's seconds.
      api::Model model{std::move(m.body), m.meta(), "mm", "json"};
      const nlohmann::json rep = api::beautify(model, m.tolerance);
      j["beautify_seconds"] = rep["seconds"]["beautify"];
      j["passes"] = rep["seconds"]["passes"];
      j["repaired"] = api::repaired_count(rep);
      j["not_repaired"] = api::not_repaired_count(rep);
      const bool valid = check_topology(model.body).empty();
      if (!valid) j["error"] = "the beautified body fails the topology check";
      return j;
    });
    if (r.contains("error")) {
      std::cout << n << " faces: " << r["error"].get<std::string>() << "\n";
      failed = true;
      continue;
    }
    if (detect_only) {
      std::cout << r["faces"] << " faces: detect " << r["detect_seconds"] << " s (" << r["problems"]
                << " problems), peak RSS " << r["peak_rss_bytes"].get<double>() / 1e6 << " MB (model "
                << r["model_rss_bytes"].get<double>() / 1e6 << " MB)\n";
      faces.push_back(r["faces"].get<double>());
      detect_s.push_back(r["detect_seconds"].get<double>());
      out["sizes"].push_back(r);
      continue;
    }
    if (r.contains("on_plate")) std::cout << r["on_plate"] << " defects on the plate; ";
    std::cout << r["faces"] << " faces: detect " << r["detect_seconds"] << " s (" << r["problems"]
              << " problems), beautify " << r["beautify_seconds"] << " s (" << r["repaired"] << " repaired, "
              << r["not_repaired"] << " not), peak RSS " << r["peak_rss_bytes"].get<double>() / 1e6 << " MB (model "
              << r["model_rss_bytes"].get<double>() / 1e6 << " MB)\n  passes:";
    for (const auto& [name, s] : r["passes"].items()) std::cout << " " << name << " " << s.get<double>();
    std::cout << "\n";
    faces.push_back(r["faces"].get<double>());
    detect_s.push_back(r["detect_seconds"].get<double>());
    beautify_s.push_back(r["beautify_seconds"].get<double>());
    out["sizes"].push_back(r);
  }
  if (faces.size() >= 2 && detect_only) {
    out["exponent"] = {{"detect", loglog_slope(faces, detect_s)}};
    std::cout << "exponent (least squares of log s on log faces): detect " << out["exponent"]["detect"] << "\n";
  } else if (faces.size() >= 2) {
    out["exponent"] = {{"detect", loglog_slope(faces, detect_s)}, {"beautify", loglog_slope(faces, beautify_s)}};
    std::cout << "exponent (least squares of log s on log faces): detect " << out["exponent"]["detect"] << ", beautify "
              << out["exponent"]["beautify"] << "\n";
  }
  std::cout << out.dump() << "\n";
  return failed ? 1 : 0;
}

int bench_occt_heal(int argc, char** argv) {
  long long faces = 10'000, seed = 1;
  double rate = 0.01;
  std::string dir = std::filesystem::temp_directory_path().string();
  for (int i = 2; i < argc; ++i) {
    const std::string a = argv[i];
    const std::string v = i + 1 < argc ? argv[i + 1] : "";
    char* end = nullptr;
    if (a == "--help") return usage(std::cout, 0);
    if (a != "--faces" && a != "--rate" && a != "--seed" && a != "--dir") {
      std::cerr << "kintsugi-bench: unknown argument '" << a << "'\n";
      return usage(std::cerr, 2);
    }
    ++i;
    if (a == "--dir") {
      dir = v;
      if (!std::filesystem::is_directory(dir)) {
        std::cerr << "kintsugi-bench occt-heal: --dir '" << dir << "' is not a folder\n";
        return 2;
      }
    } else if (a == "--rate") {
      rate = std::strtod(v.c_str(), &end);
      if (v.empty() || *end != '\0' || !(rate >= 0 && rate <= 1)) {
        std::cerr << "kintsugi-bench occt-heal: --rate needs a number from 0 to 1\n";
        return 2;
      }
    } else {
      const long long n = std::strtoll(v.c_str(), &end, 10);
      if (v.empty() || *end != '\0' || (a == "--faces" && (n < 10 || n > 10'000'000))) {
        std::cerr << "kintsugi-bench occt-heal: " << a << " needs a whole number"
                  << (a == "--faces" ? " from 10 to 10000000" : "") << "\n";
        return 2;
      }
      (a == "--faces" ? faces : seed) = n;
    }
  }
#ifdef KINTSUGI_HAVE_OCCT
  return kintsugi::bench::bench_occt_heal(faces, rate, seed, dir);
#else
  std::cerr << "kintsugi-bench occt-heal: built without OpenCASCADE\n";
  return 2;
#endif
}

}  // namespace

int main(int argc, char** argv) {
  if (argc >= 2 && (std::strcmp(argv[1], "--help") == 0 || std::strcmp(argv[1], "-h") == 0)) return usage(std::cout, 0);
  if (argc >= 2 && std::strcmp(argv[1], "io") == 0) return bench_io(argc, argv);
  if (argc >= 2 && std::strcmp(argv[1], "read") == 0) return bench_read(argc, argv);
  if (argc >= 2 && std::strcmp(argv[1], "beautify") == 0) return bench_beautify(argc, argv);
  if (argc >= 2 && std::strcmp(argv[1], "occt-heal") == 0) return bench_occt_heal(argc, argv);
  if (argc == 2 && std::strcmp(argv[1], "solvers") == 0) return kintsugi::bench::bench_solvers();
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

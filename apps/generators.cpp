#include "apps/generators.h"

#include "kernel/builders.h"
#include "zoo/zoo.h"

#include <stdexcept>

namespace kintsugi::cli {

namespace {

double num(const Args& a, const std::string& name, double fallback) {
  std::string err;
  auto v = a.number(name, fallback, &err);
  if (!v) throw std::invalid_argument(err);
  return *v;
}

long long whole(const Args& a, const std::string& name, long long fallback, long long lo, long long hi) {
  std::string err;
  auto v = a.integer(name, fallback, lo, hi, &err);
  if (!v) throw std::invalid_argument(err);
  return *v;
}

Model plain(Body b) {
  Model m;
  m.body = std::move(b);
  return m;
}

Model from_zoo(zoo::ZooModel z) {
  Model m;
  m.body = std::move(z.body);
  m.meta = z.meta();
  return m;
}

// paper-1 .. paper-10: the paper's test objects (section 6.1).
Generator paper(int n) {
  return {"paper-" + std::to_string(n),
          "  [--clean]   the paper's test object " + std::to_string(n) +
              " with its defects in meta.defects; --clean: the model it should become",
          {},
          {"--clean"},
          [n](const Args& a) { return from_zoo(zoo::paper_object(n, a.has("--clean"))); }};
}

}  // namespace

// A million faces makes a native file of about 870 MB: larger would pass the reader's
// 1 GiB limit (io/native_json.h), and a model written that could not be read back is
// no use as a benchmark.
constexpr long long kMaxGeneratedFaces = 1'000'000;

const std::vector<Generator>& generators() {
  static const std::vector<Generator> table = {
      {"box", "  --sx X --sy Y --sz Z   edge lengths (default 1 1 1)", {"--sx", "--sy", "--sz"}, {},
       [](const Args& a) { return plain(build::box(num(a, "--sx", 1), num(a, "--sy", 1), num(a, "--sz", 1))); }},
      {"prism", "  --sides N (3..1000, default 6) --radius R (1) --height H (1)   prism over a regular polygon",
       {"--sides", "--radius", "--height"}, {},
       [](const Args& a) {
         return plain(build::prism(build::regular_polygon(int(whole(a, "--sides", 6, 3, 1000)), num(a, "--radius", 1)),
                                   num(a, "--height", 1)));
       }},
      {"pyramid", "  --sides N (3..1000, default 4) --radius R (1) --height H (1)   pyramid over a regular polygon",
       {"--sides", "--radius", "--height"}, {},
       [](const Args& a) {
         return plain(build::pyramid(build::regular_polygon(int(whole(a, "--sides", 4, 3, 1000)), num(a, "--radius", 1)),
                                     num(a, "--height", 1)));
       }},
      {"cylinder", "  --radius R (1) --height H (2)", {"--radius", "--height"}, {},
       [](const Args& a) { return plain(build::cylinder(num(a, "--radius", 1), num(a, "--height", 2))); }},
      {"cone", "  --radius R (1) --height H (2)", {"--radius", "--height"}, {},
       [](const Args& a) { return plain(build::cone(num(a, "--radius", 1), num(a, "--height", 2))); }},
      {"sphere", "  --radius R (1)", {"--radius"}, {},
       [](const Args& a) { return plain(build::sphere(num(a, "--radius", 1))); }},
      {"torus", "  --major R (3) --minor r (1), r < R", {"--major", "--minor"}, {},
       [](const Args& a) { return plain(build::torus(num(a, "--major", 3), num(a, "--minor", 1))); }},
      {"grid", "  --faces N (6..1000000, default 600)   a unit box whose sides are cut into k x k quads, 6k^2 ~ N",
       {"--faces", "--size"}, {},
       [](const Args& a) {
         return plain(build::grid_box(std::size_t(whole(a, "--faces", 600, 6, kMaxGeneratedFaces)), num(a, "--size", 1)));
       }},
      {"family",
       "  --faces N (10..1000000, default 1000) --defect-rate R (0..1, default 0.1) --seed S (default 1)\n"
       "  a plate with a k x k grid of blocks, pyramids and cylindrical bosses, R x (features) defects injected",
       {"--faces", "--defect-rate", "--seed"}, {},
       [](const Args& a) {
         double rate = num(a, "--defect-rate", 0.1);
         if (!(rate >= 0 && rate <= 1)) throw std::invalid_argument("--defect-rate must be between 0 and 1");
         return from_zoo(zoo::family(std::size_t(whole(a, "--faces", 1000, 10, kMaxGeneratedFaces)), rate,
                                     std::uint64_t(whole(a, "--seed", 1, 0, (1LL << 62) + ((1LL << 62) - 1)))));
       }},
  };
  static const std::vector<Generator> all = [] {
    std::vector<Generator> v = table;
    for (int n = 1; n <= 10; ++n) v.push_back(paper(n));
    return v;
  }();
  return all;
}

}  // namespace kintsugi::cli

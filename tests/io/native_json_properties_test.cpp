// rapidcheck properties of the native format over random solids and random operator
// sequences (tests/support/random_ops.h):
//   * write → read gives an equal body, with the same meta and units;
//   * write(read(write(b))) == write(b), byte for byte;
//   * any double survives exactly.
#include "io/native_json.h"
#include "kernel/builders.h"
#include "tests/support/random_ops.h"

#include <gtest/gtest.h>
#include <rapidcheck.h>
#include <rapidcheck/gtest.h>

#include <cmath>
#include <cstring>

namespace kintsugi::io {
namespace {

// A positive size with an untidy binary expansion, in (0, 50].
double size_from(int k) { return double(k) / 97.0; }

Body random_solid() {
  const int which = *rc::gen::inRange(0, 9);
  auto size = [] { return size_from(*rc::gen::inRange(1, 5000)); };
  switch (which) {
    case 0: return build::box(size(), size(), size());
    case 1: return build::prism(build::regular_polygon(*rc::gen::inRange(3, 12), size()), size());
    case 2: return build::pyramid(build::regular_polygon(*rc::gen::inRange(3, 12), size()), size());
    case 3: return build::cylinder(size(), size());
    case 4: return build::cone(size(), size());
    case 5: return build::sphere(size());
    case 6: {
      double minor = size();
      return build::torus(minor + size(), minor);
    }
    case 7: return build::grid_box(std::size_t(*rc::gen::inRange(6, 200)), size());
    default: {
      Body b;
      (void)euler::mvfs(b, geo::Vec3(size(), -size(), size()));
      return b;
    }
  }
}

Body random_body() {
  Body b = random_solid();
  testing::Numbers n(*rc::gen::container<std::vector<std::uint32_t>>(*rc::gen::inRange(0, 120),
                                                                     rc::gen::arbitrary<std::uint32_t>()));
  int applied = 0;
  for (int steps = 0; !n.empty() && steps < 40; ++steps) applied += testing::apply_random_op(b, n).ok;
  RC_CLASSIFY(applied == 0, "no operator applied");
  RC_CLASSIFY(applied >= 5, "5+ operators applied");
  RC_CLASSIFY(b.counts().border_cycles > 0, "has a border cycle");
  return b;
}

RC_GTEST_PROP(NativeJsonProperties, WriteThenReadGivesAnEqualBody, ()) {
  Body b = random_body();
  std::string text = write_native(b);
  std::string error;
  auto doc = read_native(text, &error);
  if (!doc) RC_FAIL("refused its own output: " + error);
  std::string why;
  RC_ASSERT(doc->body.equals(b, &why));
  RC_ASSERT(write_native(doc->body) == text);
}

RC_GTEST_PROP(NativeJsonProperties, MetaAndUnitsSurvive, (std::string note, std::vector<int> numbers)) {
  nlohmann::json meta = {{"note", note}, {"numbers", numbers}, {"tolerance", size_from(*rc::gen::inRange(1, 1000))}};
  const char* units[] = {"mm", "m", "in"};
  std::string u = units[*rc::gen::inRange(0, 3)];
  std::string text = write_native(random_solid(), meta, u);
  std::string error;
  auto doc = read_native(text, &error);
  // rapidcheck strings may not be UTF-8: the writer replaces what is not, so compare
  // against what was written rather than the input.
  if (!doc) RC_FAIL("refused its own output: " + error);
  RC_ASSERT(doc->units == u);
  RC_ASSERT(doc->meta["numbers"] == meta["numbers"]);
  RC_ASSERT(doc->meta["tolerance"] == meta["tolerance"]);
  RC_ASSERT(write_native(doc->body, doc->meta, doc->units) == text);
}

RC_GTEST_PROP(NativeJsonProperties, EveryFiniteDoubleSurvivesExactly, (double x, double y, double z)) {
  RC_PRE(std::isfinite(x) && std::isfinite(y) && std::isfinite(z));
  Body b;
  (void)euler::mvfs(b, geo::Vec3(x, y, z));
  auto doc = read_native(write_native(b), nullptr);
  RC_ASSERT(doc.has_value());
  const geo::Vec3& p = doc->body.point(VertexH(0));
  RC_ASSERT(std::memcmp(p.data(), b.point(VertexH(0)).data(), sizeof(double) * 3) == 0);  // bit for bit, -0.0 too
}

RC_GTEST_PROP(NativeJsonProperties, EveryBitPatternSurvivesExactly, (std::uint64_t bits)) {
  double x;
  std::memcpy(&x, &bits, sizeof x);
  RC_PRE(std::isfinite(x));
  Body b;
  (void)euler::mvfs(b, geo::Vec3(x, -x, x));
  auto doc = read_native(write_native(b), nullptr);
  RC_ASSERT(doc.has_value());
  double back = doc->body.point(VertexH(0)).x();
  RC_ASSERT(std::memcmp(&back, &x, sizeof x) == 0);
}

}  // namespace
}  // namespace kintsugi::io

// Property: random builder solids of random sizes under random rigid motions survive
// export -> import in both formats (counts equal, geometry equal, OpenCASCADE valid).
#include "invariants/topology_check.h"
#include "io/occt/exchange.h"
#include "kernel/builders.h"
#include "tests/occt/compare.h"

#include <gtest/gtest.h>
#include <rapidcheck.h>
#include <rapidcheck/gtest.h>

#include <cmath>

namespace kintsugi {
namespace {

using io::CadFormat;

// A size in [0.1, 100).
rc::Gen<double> size() {
  return rc::gen::map(rc::gen::inRange(0, 1000), [](int k) { return 0.1 * std::pow(1000.0, k / 1000.0); });
}

Body random_solid() {
  int kind = *rc::gen::inRange(0, 7);
  double a = *size(), b = *size(), c = *size();
  switch (kind) {
    case 0: return build::box(a, b, c);
    case 1: return build::prism(build::regular_polygon(*rc::gen::inRange(3, 9), a), b);
    case 2: return build::pyramid(build::regular_polygon(*rc::gen::inRange(3, 9), a), b);
    case 3: return build::cylinder(a, b);
    case 4: return build::cone(a, b);
    case 5: return build::sphere(a);
    default: return build::torus(a + b, b * (0.1 + 0.8 * (*rc::gen::inRange(0, 100)) / 100.0));
  }
}

void random_motion(Body& b) {
  double ax = *rc::gen::inRange(-1000, 1001) / 1000.0, ay = *rc::gen::inRange(-1000, 1001) / 1000.0,
         az = *rc::gen::inRange(-1000, 1001) / 1000.0;
  double angle = *rc::gen::inRange(0, 6283) / 1000.0;
  Eigen::Vector3d axis(ax, ay, az);
  if (axis.norm() < 1e-3) axis = Eigen::Vector3d::UnitZ();
  Eigen::Matrix3d r = Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
  Eigen::Vector3d t(*rc::gen::inRange(-1000, 1001) / 10.0, *rc::gen::inRange(-1000, 1001) / 10.0,
                    *rc::gen::inRange(-1000, 1001) / 10.0);
  test::transform(b, r, t);
}

RC_GTEST_PROP(ExchangeProperty, RigidlyMovedBuilderSolidsSurviveARoundTrip, ()) {
  Body b = random_solid();
  random_motion(b);
  RC_ASSERT(check_topology(b).empty());
  io::OcctVerdict v = io::occt_check(b);
  RC_ASSERT(v.valid);
  for (CadFormat f : {CadFormat::step, CadFormat::brep}) {
    std::string path = test::temp_path(f == CadFormat::step ? "prop.step" : "prop.brep");
    std::string err;
    RC_ASSERT(io::export_cad(b, path, f, &err));
    std::optional<io::CadImport> in = io::import_cad(path, f, &err);
    if (!in) RC_FAIL(err);
    RC_ASSERT(in->body.counts() == b.counts());
    RC_ASSERT(check_topology(in->body).empty());
    // Coordinates up to ~170 after the motion: STEP writes 15 significant digits.
    std::string diff = test::compare_bodies(b, in->body, 1e-7);
    if (!diff.empty()) RC_FAIL(diff);
    RC_ASSERT(io::occt_check(in->body).valid);
  }
}

}  // namespace
}  // namespace kintsugi

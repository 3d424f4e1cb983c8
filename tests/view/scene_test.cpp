// view/: tessellation within the chordal tolerance, the scene's marks, determinism and
// the page's escaping. The page itself is tested in a browser (browser_test.py).
#include "geometry/surface.h"
#include "invariants/element_geometry.h"
#include "kernel/builders.h"
#include "view/html_page.h"
#include "view/scene.h"
#include "view/tessellate.h"

#include <gtest/gtest.h>

#include <cmath>

namespace kintsugi::view {
namespace {

// Every mesh vertex lies on the face's surface, and every triangle's centre (where a
// flat triangle strays furthest from a convex surface) within the chordal tolerance.
void expect_within_chordal(const Body& b, double chordal) {
  for (FaceH f : b.faces()) {
    const FaceMesh m = tessellate_face(b, f, chordal);
    ASSERT_TRUE(m.problem.empty()) << f << ": " << m.problem;
    ASSERT_FALSE(m.triangles.empty()) << f;
    const geo::Surface& s = b.surface(f);
    for (const geo::Vec3& p : m.vertices) EXPECT_LT(std::abs(geo::signed_distance(s, p)), 1e-9) << f;
    double worst = 0, area = 0;
    for (const auto& t : m.triangles) {
      const geo::Vec3 &a = m.vertices[t[0]], &c = m.vertices[t[1]], &d = m.vertices[t[2]];
      worst = std::max(worst, std::abs(geo::signed_distance(s, (a + c + d) / 3)));
      area += 0.5 * (c - a).cross(d - a).norm();
    }
    EXPECT_LE(worst, chordal) << f;
    // The mesh's area approaches the face's: chords are shorter than arcs by ~chordal/r.
    const double exact = face_measure(b, f, 1e-4).area;
    EXPECT_NEAR(area, exact, 0.005 * exact) << f;
  }
}

TEST(Tessellate, CurvedFacesWithinTheChordalTolerance) {
  expect_within_chordal(build::sphere(2.0), 1e-3);
  expect_within_chordal(build::cylinder(1.0, 3.0), 1e-3);
  expect_within_chordal(build::cone(1.5, 2.0), 1e-3);
  expect_within_chordal(build::torus(3.0, 1.0), 1e-2);
}

TEST(Tessellate, FinerToleranceMoreTriangles) {
  const Body b = build::sphere(1.0);
  const FaceH f = b.faces().front();
  EXPECT_GT(tessellate_face(b, f, 1e-4).triangles.size(), 2 * tessellate_face(b, f, 1e-2).triangles.size());
}

TEST(Tessellate, PlanarFacesNeedNoSteinerPoints) {
  const Body b = build::box(1, 2, 3);
  for (FaceH f : b.faces()) {
    const FaceMesh m = tessellate_face(b, f, 1e-3);
    EXPECT_EQ(m.vertices.size(), 4u) << f;
    EXPECT_EQ(m.triangles.size(), 2u) << f;
  }
}

TEST(Tessellate, AngleStep) {
  for (double r : {0.1, 1.0, 10.0}) {
    const double a = angle_step(r, 1e-3 * r);
    EXPECT_NEAR(r * (1 - std::cos(a / 2)), 1e-3 * r, 1e-12 * r);
  }
  EXPECT_EQ(angle_step(1.0, 10.0), 0.8);     // coarser than an octagon is never taken
  EXPECT_EQ(angle_step(1.0, 1e-12), 0.01);  // nor finer than 629 segments a turn
  EXPECT_EQ(angle_step(0.0, 1e-3), 0.8);
}

nlohmann::json box_scene(const Body& b, std::vector<ProblemEntry> problems) {
  PageInput in;
  in.title = "box <1>";
  in.tolerance = 1e-3;
  in.models.push_back({"model", &b, true});
  in.problems = std::move(problems);
  return scene_json(in);
}

TEST(Scene, MarksWhatEachElementIs) {
  const Body b = build::box();
  ProblemEntry p;
  p.type = "small_face";
  p.elements = {b.faces()[2].str(), b.edges()[3].str(), b.vertices()[1].str(), "f999", "q1"};
  p.measure = 1e-7;
  const nlohmann::json s = box_scene(b, {p});
  ASSERT_EQ(s["problems"].size(), 1u);
  const auto& mark = s["problems"][0]["marks"][0];
  EXPECT_EQ(mark["faces"], nlohmann::json::array({2}));
  EXPECT_EQ(mark["lines"].size(), 6u);        // a straight edge: one segment
  EXPECT_EQ(mark["points"].size(), 3u * 3u);  // its two ends and the vertex
  EXPECT_EQ(mark["missing"], nlohmann::json::array({"f999", "q1"}));
  EXPECT_EQ(s["models"][0]["faces"], 6);
}

TEST(Scene, GapsAreOutlinedNotTinted) {
  const Body b = build::box();
  ProblemEntry p;
  p.type = "face_gap";
  p.elements = {b.faces()[0].str()};
  const nlohmann::json s = box_scene(b, {p});
  EXPECT_TRUE(s["problems"][0]["marks"][0]["faces"].empty());
}

TEST(Scene, RepairedProblemsAreNotMarkedAfter) {
  const Body before = build::box(), after = build::box();
  PageInput in;
  in.models = {{"before", &before, true}, {"after", &after, false}};
  ProblemEntry fixed, left;
  fixed.type = left.type = "short_edge";
  fixed.elements = {"e1"};
  left.elements = {"e2"};
  fixed.action = "repaired";
  fixed.resolved = true;
  left.action = "not repaired";
  in.problems = {fixed, left};
  const nlohmann::json s = scene_json(in);
  EXPECT_EQ(s["problems"][0]["marks"].size(), 1u);
  EXPECT_EQ(s["problems"][1]["marks"].size(), 2u);
}

TEST(Scene, SameInputSameBytes) {
  const Body b = build::torus(3, 1);
  ProblemEntry p;
  p.type = "sliver_face";
  p.elements = {b.faces().front().str()};
  EXPECT_EQ(html_page(box_scene(b, {p})), html_page(box_scene(b, {p})));
}

// The scene's base64 arrays read back.
std::vector<std::uint8_t> unbase64(const std::string& s) {
  static const std::string abc = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::vector<std::uint8_t> out;
  std::uint32_t acc = 0;
  int bits = 0;
  for (char c : s) {
    if (c == '=') break;
    acc = acc << 6 | std::uint32_t(abc.find(c));
    bits += 6;
    if (bits >= 8) {
      bits -= 8;
      out.push_back(std::uint8_t(acc >> bits));
    }
  }
  return out;
}
std::vector<std::uint32_t> little_endian(const std::string& b64, int size) {
  const std::vector<std::uint8_t> b = unbase64(b64);
  std::vector<std::uint32_t> out;
  for (std::size_t i = 0; i + std::size_t(size) <= b.size(); i += std::size_t(size)) {
    std::uint32_t v = 0;
    for (int k = 0; k < size; ++k) v |= std::uint32_t(b[i + std::size_t(k)]) << (8 * k);
    out.push_back(v);
  }
  return out;
}

// What the page draws, read back from the scene: every face's vertices within half a
// grid step of the tessellation's (each axis), its triangles the same, the chunks'
// 16-bit indices counted from their first vertex, and the edges' points on the grid too.
nlohmann::json expect_scene_is_the_tessellation(const Body& b, double chordal) {
  PageInput in;
  in.models.push_back({"model", &b, true});
  in.chordal = chordal;
  const nlohmann::json s = scene_json(in);
  const BodyMesh mesh = tessellate(b, chordal);
  const geo::Vec3 origin(s["origin"][0], s["origin"][1], s["origin"][2]);
  const geo::Vec3 low(s["grid"]["low"][0], s["grid"]["low"][1], s["grid"]["low"][2]);
  const double step = s["grid"]["step"];
  const double size = s["size"];
  if (!(step > 0)) {
    ADD_FAILURE() << "grid step " << step;
    return {};
  }
  EXPECT_LE(step, size / 65535);
  const auto& m = s["models"][0];
  const std::vector<std::uint32_t> q = little_endian(m["mesh"]["positions"], 2);
  const std::vector<std::uint32_t> lq = little_endian(m["lines"]["positions"], 2);
  auto expect_on_grid = [&](const std::vector<std::uint32_t>& grid, std::size_t i, const geo::Vec3& p) {
    ASSERT_LT(3 * i + 2, grid.size());
    for (int k = 0; k < 3; ++k) {
      const double drawn = low[k] + step * grid[3 * i + std::size_t(k)];
      EXPECT_LE(std::abs(drawn - (p[k] - origin[k])), 0.5 * step * (1 + 1e-9)) << "point " << i << " axis " << k;
    }
  };
  std::vector<std::array<std::uint32_t, 3>> expected, drawn;
  std::size_t nv = 0;
  for (const FaceMesh& f : mesh.faces) {
    for (std::size_t i = 0; i < f.vertices.size(); ++i) expect_on_grid(q, nv + i, f.vertices[i]);
    for (const auto& t : f.triangles) expected.push_back({t[0] + std::uint32_t(nv), t[1] + std::uint32_t(nv), t[2] + std::uint32_t(nv)});
    nv += f.vertices.size();
  }
  EXPECT_EQ(q.size(), 3 * nv);
  std::uint32_t first = 0;
  for (const auto& c : m["mesh"]["chunks"]) {
    const std::uint32_t n = c["vertices"];
    const int bytes = c["index_bytes"];
    const std::vector<std::uint32_t> idx = little_endian(c["indices"], bytes);
    if (bytes == 2) {
      EXPECT_LT(n, 65536u);
    }
    for (std::size_t i = 0; i + 2 < idx.size(); i += 3) {
      for (std::size_t k = 0; k < 3; ++k) {
        EXPECT_LT(idx[i + k], n);
        if (bytes == 2) {
          EXPECT_NE(idx[i + k], 65535u);  // WebGL 2's primitive restart
        }
      }
      drawn.push_back({first + idx[i], first + idx[i + 1], first + idx[i + 2]});
    }
    first += n;
  }
  EXPECT_EQ(first, nv);
  EXPECT_EQ(drawn, expected);
  std::size_t np = 0;
  for (const EdgePolyline& e : mesh.edges)
    for (const geo::Vec3& p : e.points) expect_on_grid(lq, np++, p);
  EXPECT_EQ(lq.size(), 3 * np);
  return m["mesh"]["chunks"];
}

TEST(Scene, PositionsOnAGridWithinHalfAStep) {
  EXPECT_EQ(expect_scene_is_the_tessellation(build::torus(3, 1), 1e-3).size(), 1u);
  EXPECT_EQ(expect_scene_is_the_tessellation(build::box(1, 2, 3), 1e-3).size(), 1u);
}

TEST(Scene, ChunksOfFewerThan65536Vertices) {
  // 20,000 quadrilaterals: 80,000 vertices in two chunks of 16-bit indices.
  const nlohmann::json grid = expect_scene_is_the_tessellation(build::grid_box(20000), 1e-3);
  ASSERT_EQ(grid.size(), 2u);
  EXPECT_EQ(grid[0]["index_bytes"], 2);
  EXPECT_EQ(grid[1]["index_bytes"], 2);
}

TEST(Scene, AFaceOf65536VerticesOrMoreHas32BitIndices) {
  // One face with more vertices than 16 bits count (a torus, about 315 x 315): its own chunk, 32-bit.
  const nlohmann::json ball = expect_scene_is_the_tessellation(build::torus(3.0, 1.0), 4e-4);
  ASSERT_EQ(ball.size(), 1u);
  EXPECT_EQ(ball[0]["index_bytes"], 4);
  EXPECT_GT(ball[0]["vertices"], 65535);
}

TEST(Scene, NeedsAModel) {
  EXPECT_THROW(scene_json(PageInput{}), std::invalid_argument);
}

TEST(Page, TextCannotEndTheScriptEarly) {
  const Body b = build::box();
  ProblemEntry p;
  p.type = "</script><script>alert(1)</script>";
  p.elements = {"f0"};
  const nlohmann::json scene = box_scene(b, {p});
  const std::string page = html_page(scene);
  // The browser ends the element at the first "</script>": what is before it must be
  // the whole scene.
  const std::string open = "id=\"scene\">";
  const auto start = page.find(open);
  ASSERT_NE(start, std::string::npos);
  const auto end = page.find("</script>", start);
  const std::string inlined = page.substr(start + open.size(), end - start - open.size());
  EXPECT_EQ(inlined.find('<'), std::string::npos);
  ASSERT_TRUE(nlohmann::json::accept(inlined));
  EXPECT_EQ(nlohmann::json::parse(inlined), scene);
  EXPECT_NE(page.find("<title>box &lt;1&gt; - kintsugi</title>"), std::string::npos);
}

}  // namespace
}  // namespace kintsugi::view

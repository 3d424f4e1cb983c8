#include "audit/recipe.h"

#include "kernel/builders.h"
#include "zoo/zoo.h"

#include <Eigen/Geometry>
#include <cmath>
#include <stdexcept>

namespace kintsugi::audit {

namespace {

Body make_base(const std::string& base) {
  if (base == "box") return build::box(1, 1.3, 0.8);
  if (base == "prism5") return build::prism(build::regular_polygon(5, 1), 2);
  if (base == "prism6") return build::prism(build::regular_polygon(6, 1), 1);
  if (base == "pyramid4") return build::pyramid(build::regular_polygon(4, 1), 1);
  if (base == "pyramid5") return build::pyramid(build::regular_polygon(5, 1), 1.5);
  if (base == "cylinder") return build::cylinder(1, 2);
  if (base == "cone") return build::cone(1, 2);
  if (base == "sphere") return build::sphere(1);
  if (base == "torus") return build::torus(3, 1);
  if (base == "grid24") return build::grid_box(24);
  if (base.rfind("paper", 0) == 0) {
    int n = std::stoi(base.substr(5));
    return zoo::paper_object(n, true).body;
  }
  throw std::invalid_argument("unknown audit base solid: " + base);
}

// Tolerance of a recipe relative to the base's size: the zoo's defects are made below it.
double base_size(const Body& b) {
  geo::Vec3 lo = geo::Vec3::Constant(1e300), hi = geo::Vec3::Constant(-1e300);
  for (VertexH v : b.vertices()) lo = lo.cwiseMin(b.point(v)), hi = hi.cwiseMax(b.point(v));
  return b.vertices().empty() ? 1.0 : (hi - lo).norm();
}

}  // namespace

const std::vector<std::string>& base_names() {
  static const std::vector<std::string> names = {"box",      "prism5", "prism6", "pyramid4", "pyramid5",
                                                 "cylinder", "cone",   "sphere", "torus",    "grid24",
                                                 "paper1",   "paper4", "paper5", "paper6",   "paper10"};
  return names;
}

std::size_t base_faces(const std::string& base) { return make_base(base).counts().faces; }

nlohmann::json Recipe::to_json() const {
  nlohmann::json inj = nlohmann::json::array();
  for (const Injection& i : injections) inj.push_back({{"type", problem_name(i.type)}, {"seed", i.seed}});
  return {{"base", base},           {"tolerance", tolerance}, {"injections", inj},
          {"rotation", rotation},   {"translation", translation},
          {"scale", scale},         {"pass", problem_name(pass)}};
}

Recipe Recipe::from_json(const nlohmann::json& j) {
  Recipe r;
  try {
    r.base = j.at("base").get<std::string>();
    r.tolerance = j.at("tolerance").get<double>();
    for (const auto& i : j.at("injections")) {
      auto t = problem_from_name(i.at("type").get<std::string>());
      if (!t) throw std::invalid_argument("unknown problem type " + i.at("type").dump());
      r.injections.push_back({*t, i.at("seed").get<std::uint64_t>()});
    }
    r.rotation = j.at("rotation").get<std::array<double, 4>>();
    r.translation = j.at("translation").get<std::array<double, 3>>();
    r.scale = j.at("scale").get<double>();
    auto p = problem_from_name(j.at("pass").get<std::string>());
    if (!p) throw std::invalid_argument("unknown pass " + j.at("pass").dump());
    r.pass = *p;
  } catch (const nlohmann::json::exception& e) {
    throw std::invalid_argument(std::string("audit recipe: ") + e.what());
  }
  if (!(r.tolerance > 0) || !(r.scale > 0)) throw std::invalid_argument("audit recipe: tolerance and scale must be positive");
  return r;
}

geo::Similarity Recipe::motion() const {
  Eigen::Quaterniond q(rotation[0], rotation[1], rotation[2], rotation[3]);
  if (!(q.norm() > 0)) throw std::invalid_argument("audit recipe: zero rotation quaternion");
  q.normalize();
  geo::Similarity s;
  s.rotation = q.toRotationMatrix();
  s.scale = scale;
  s.translation = geo::Vec3(translation[0], translation[1], translation[2]);
  return s;
}

std::optional<Built> build(const Recipe& r) {
  Built out;
  out.body = make_base(r.base);
  const double t = r.tolerance * base_size(out.body);
  for (const Injection& i : r.injections) {
    std::string err;
    if (auto inj = zoo::inject(out.body, i.type, i.seed, std::nullopt, t, &err)) {
      out.applied.push_back(i);
      out.description += std::string(problem_name(i.type)) + ": " + inj->description + "\n";
    }
  }
  if (out.applied.empty()) return std::nullopt;
  const geo::Similarity s = r.motion();
  Body& b = out.body;
  const bool journaling = b.journaling();
  b.set_journaling(false);
  for (VertexH v : b.vertices()) b.set_point(v, s.point(b.point(v)));
  for (EdgeH e : b.edges()) b.set_curve(e, geo::transformed(b.curve(e), s));
  for (FaceH f : b.faces()) b.set_surface(f, geo::transformed(b.surface(f), s), b.same_sense(f));
  b.set_journaling(journaling);
  b.clear_journal();
  out.tolerance = t * s.scale;
  return out;
}

Recipe random_recipe(ProblemType pass, std::mt19937_64& rng) {
  auto uniform = [&](double lo, double hi) { return lo + (hi - lo) * double(rng() >> 11) * 0x1.0p-53; };
  Recipe r;
  r.pass = pass;
  const auto& bases = base_names();
  r.base = bases[rng() % bases.size()];
  r.tolerance = uniform(0.004, 0.03);  // of the base's size
  r.injections.push_back({pass, rng()});
  const int more = int(rng() % 4);
  for (int i = 0; i < more; ++i) r.injections.push_back({kAllProblemTypes[rng() % kAllProblemTypes.size()], rng()});
  Eigen::Quaterniond q(uniform(-1, 1), uniform(-1, 1), uniform(-1, 1), uniform(-1, 1));
  if (q.norm() < 1e-3) q = Eigen::Quaterniond::Identity();
  q.normalize();
  r.rotation = {q.w(), q.x(), q.y(), q.z()};
  r.translation = {uniform(-100, 100), uniform(-100, 100), uniform(-100, 100)};
  r.scale = std::pow(10.0, uniform(-2, 2));
  return r;
}

}  // namespace kintsugi::audit

// A Table 1 audit trial as data: which solid, which defects (type and seed, injected in
// order), which tolerance, which rigid motion, and which pass is audited. The recipe is
// the trial's "operation script": it rebuilds the exact model (the zoo is deterministic
// per seed), so a saved counterexample or witness is a few lines of JSON next to the
// native model it makes.
#pragma once

#include "geometry/transform.h"
#include "kernel/body.h"
#include "problems/problem_type.h"

#include <nlohmann/json.hpp>

#include <cstdint>
#include <optional>
#include <random>
#include <string>
#include <vector>

namespace kintsugi::audit {

struct Injection {
  ProblemType type;
  std::uint64_t seed;
  bool operator==(const Injection&) const = default;
};

struct Recipe {
  std::string base;        // one of base_names()
  double tolerance = 0.02; // before the motion's scale
  std::vector<Injection> injections;
  // Rigid motion (rotation as a unit quaternion w, x, y, z) and uniform scale; the
  // tolerance is scaled with the model, so no decision may change.
  std::array<double, 4> rotation{1, 0, 0, 0};
  std::array<double, 3> translation{0, 0, 0};
  double scale = 1.0;
  ProblemType pass = ProblemType::face_gap;

  nlohmann::json to_json() const;
  // Throws std::invalid_argument naming what is wrong.
  static Recipe from_json(const nlohmann::json& j);
  geo::Similarity motion() const;
};

// The base solids the audit draws from: builder solids of every surface kind and the
// clean paper objects.
const std::vector<std::string>& base_names();
// Faces of the base (for shrinking: fewer is simpler).
std::size_t base_faces(const std::string& base);

// The defective model of a recipe, and the tolerance that goes with it (scaled). The
// injections that found no place are dropped from `applied` (nullopt when none did).
struct Built {
  Body body;
  double tolerance = 0.0;
  std::vector<Injection> applied;
  std::string description;  // one line per injected defect
};
std::optional<Built> build(const Recipe& r);

// A random recipe for auditing `pass`: the first defect is of the pass's own type, then
// 0-3 more of any type, some next to each other by chance; random base, tolerance,
// rotation, translation and scale.
Recipe random_recipe(ProblemType pass, std::mt19937_64& rng);

}  // namespace kintsugi::audit

// The defect zoo: models whose defects and right answers are known (issue 5).
//
// Defects are made the way reverse engineering makes them (spec/defects.md): each face
// is fitted on its own and the fitted surfaces are intersected, so a pyramid whose
// sloping planes are each turned a little no longer meets in one point, a face fitted
// twice gives two nearly coplanar faces, a scanner that missed a region leaves a gap.
// Topology is always built with Euler operators; vertices are then placed at the
// actual intersections of the (perturbed) surfaces, so the geometry is consistent to
// modelling precision everywhere except where a gap is made on purpose (a gap is a
// border cycle, not a crack).
//
// Everything is deterministic per seed: random numbers come from zoo/random.h, which
// draws from std::mt19937_64 (fully specified by the standard) through its own
// distributions, so the same seed gives the same model with every standard library.
#pragma once

#include "kernel/body.h"
#include "problems/problem_type.h"

#include <nlohmann/json.hpp>

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace kintsugi::zoo {

// One defect: its type, the printed handles of the elements it concerns ("f3", "e7",
// "v2", "l1": loops for border cycles), and its size (the measure the paper compares
// with the tolerance: a length, or an area for small faces; see spec/defects.md).
struct KnownDefect {
  ProblemType type;
  std::vector<std::string> elements;
  double size = 0.0;
};

struct ZooModel {
  Body body;
  double tolerance = 0.0;
  std::vector<KnownDefect> defects;
  std::string source;  // e.g. "paper object 3", "family faces=1000 rate=0.1 seed=7"
  // {"tolerance": t, "defects": [{"type", "elements", "size"}...], "source": "..."}
  nlohmann::json meta() const;
};

nlohmann::json defect_json(const KnownDefect& d);

// The paper's test objects 1..10 (section 6.1, Figures 26-30): `clean` gives the model
// the beautification should produce. Face and edge counts: docs/paper-objects.md.
// Throws std::invalid_argument for n outside 1..10.
ZooModel paper_object(int n, bool clean);

// A plate with a k x k grid of blocks, pyramids and cylindrical bosses, k chosen so the
// body has about `faces` faces (10 .. 10^7), with about `defect_rate` x (number of
// features) defects injected on the features. Linear time.
ZooModel family(std::size_t faces, double defect_rate, std::uint64_t seed);

struct Injected {
  KnownDefect defect;
  std::string description;
};

// Inserts one defect of type t, of size below `tolerance`, at a random suitable place
// (or at the element named by `at`: a face, edge or vertex handle, as the type needs).
// On success the body passes check_topology and its geometry is consistent except at
// the gap a gap type makes. Returns nullopt and sets *error (if given) when no place in
// b suits the type; the body is then unchanged.
// `clean` (if given) is set to the designer's model the defect stands for where that is
// not b before the defect: a pinched face's block, which the designer made flush with the
// edge it nearly touches (zoo/defects_pinch.h's clean twin). Otherwise it is left alone.
std::optional<Injected> inject(Body& b, ProblemType t, std::uint64_t seed, const std::optional<std::string>& at,
                               double tolerance, std::string* error, Body* clean = nullptr);

// Geometric consistency as the zoo promises it: every vertex on the surfaces of its
// faces and the curves of its edges, every straight edge's midpoint on both faces'
// surfaces, within `precision`; every planar face's outer loop counter-clockwise about
// its outward normal. Returns one line per offence ("v3 is 2e-05 off f2").
std::vector<std::string> geometry_offences(const Body& b, double precision);

}  // namespace kintsugi::zoo

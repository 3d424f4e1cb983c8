// One repair pass: the problem type it repairs and how. Every pass is one file
// repair/pass_<name>.cpp that defines its Pass with KINTSUGI_PASS(<name>); the build
// lists those files into the registry (repair/CMakeLists.txt), so adding a pass is that
// file plus its row in spec/ (spec/table1.json says which types its repairs may create).
// A type with no pass is simply absent: its problems are reported as not repaired.
//
// The pipeline (repair/beautify.cpp) runs the registered passes in the paper's order
// (Table 1), each over a queue of the problems of its type; what each repair touched is
// detected again locally (detect_near), never the whole model once per pass.
#pragma once

#include "geometry/tolerance.h"
#include "kernel/body.h"
#include "problems/problem.h"
#include "repair/detect.h"
#include "repair/touched.h"

#include <string>
#include <vector>

namespace kintsugi {

// What a repair gets: the body (inside an open Transaction), the problem, the
// tolerances. It records in `touched` every element it created, moved or re-shaped (the
// pipeline checks the geometry there and detects again around it) and returns "" on
// success or why it cannot repair (the pipeline then rolls the transaction back).
struct RepairContext {
  Body& b;
  const Problem& problem;
  const geo::Tolerances& tol;
  Touched& touched;
  std::string note = {};  // how the repair was made, for the report (e.g. a new face's surface kind)
  // The validity gate's limit for two points being one (its lies-on limit: the modelling
  // precision, or the input's own accuracy when that is coarser); see coinciding_ends.
  double coincide = 0.0;
};

using RepairFn = std::string (*)(RepairContext&);
using DetectAllFn = std::vector<Problem> (*)(const Body&, const geo::Tolerances&);
using DetectNearFn = std::vector<Problem> (*)(const Body&, const geo::Tolerances&, const Neighbourhood&);

struct Pass {
  ProblemType type;
  const char* title;    // "short-edge chains": for --help, demo and docs
  const char* summary;  // one line: what the repair does
  RepairFn repair;
  // Detectors: over the whole body, and in the neighbourhood of a repair. Null: the shared
  // detectors (repair/detect.h) filtered to `type`, which is what every pass uses today.
  DetectAllFn detect_all = nullptr;
  DetectNearFn detect_near = nullptr;
};

// The registered passes in the paper's order.
const std::vector<const Pass*>& passes();
// The pass for t, or null when none is built.
const Pass* find_pass(ProblemType t);

// The problem types that repairing t may create, read from spec/table1.json (the paper's
// Table 1, column t). Every one lies after t in the order.
const std::vector<ProblemType>& may_create(ProblemType t);

// The pass's detectors, defaulting to the shared ones.
std::vector<Problem> detect_for(const Pass& p, const Body& b, const geo::Tolerances& tol);
std::vector<Problem> detect_near_for(const Pass& p, const Body& b, const geo::Tolerances& tol, const Neighbourhood& n);

}  // namespace kintsugi

// Defines the pass of the file repair/pass_<name>.cpp:
//   KINTSUGI_PASS(short_edge_chain) = {ProblemType::short_edge_chain, "...", "...", repair_fn};
#define KINTSUGI_PASS(name)                                \
  namespace kintsugi::registered_passes {                  \
  extern const ::kintsugi::Pass name;                      \
  }                                                        \
  const ::kintsugi::Pass kintsugi::registered_passes::name

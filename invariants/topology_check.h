// Topological invariants of a body (spec/invariants.md), checked in layers:
//   references in range and alive → twin/next/prev reciprocity → bounded walks of
//   loops and vertex rotations, with orbit counts → ownership (loops of faces, faces of
//   shells, shells connected) → Euler–Poincaré per shell.
// Each check returns every violation it finds, never a bare bool.
#pragma once

#include "invariants/violation.h"
#include "kernel/body.h"

#include <vector>

namespace kintsugi {

// The full check: everything, O(size of the body).
std::vector<Violation> check_topology(const Body& b);

}  // namespace kintsugi

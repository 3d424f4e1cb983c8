// Test helpers for the exchange tests: geometric body comparison up to renumbering,
// rigid motions, and temporary files.
#pragma once

#include "io/occt/exchange.h"
#include "kernel/body.h"

#include <Eigen/Geometry>

#include <filesystem>
#include <string>

namespace kintsugi::test {

// Empty when `b` is `a` up to renumbering: equal counts, faces matched one to one by
// their surfaces (sample points of a's surface on b's within tol, outward normals
// agreeing; among several faces on the same surface, the one whose loops have the same
// vertex positions), every vertex of a at a vertex of b (among coincident vertices, as
// where two solids touch, the one with the matched faces around it), and every edge of
// a matched to an edge of b between the same faces, from and to the matched vertices,
// through the same points. Otherwise, the first difference found.
std::string compare_bodies(const Body& a, const Body& b, double tol = 1e-7);

// Applies x -> r·x + t to every point, curve and surface frame.
void transform(Body& b, const Eigen::Matrix3d& r, const Eigen::Vector3d& t);

// A fresh file path in a per-process temporary directory.
std::string temp_path(const std::string& name);

// Writes `text` to a temporary file and returns its path.
std::string temp_file(const std::string& name, const std::string& text);

// Exports, imports and returns the imported body (fails the test on error).
Body round_trip(const Body& b, io::CadFormat f, const std::string& name);

// Expected element counts, in the order tests write them.
inline Counts counts(std::size_t v, std::size_t e, std::size_t f, std::size_t l, std::size_t s = 1, std::size_t bc = 0) {
  Counts c;
  c.vertices = v;
  c.edges = e;
  c.faces = f;
  c.loops = l;
  c.shells = s;
  c.border_cycles = bc;
  return c;
}

}  // namespace kintsugi::test

// A detected topological problem as a typed value: its type, the elements it is made of
// (typed handles, in a fixed order per type: spec/problems.md), how big it is, and the
// subcase where the type has one. Text appears only where a report or the CLI prints it
// (element_name, measure_name, subcase_name).
#pragma once

#include "kernel/handles.h"
#include "problems/problem_type.h"

#include <string>
#include <variant>
#include <vector>

namespace kintsugi {

// One element a problem is made of. A LoopH here is always a border cycle (a gap's far
// side); faces, edges and vertices are the body's own.
using Element = std::variant<VertexH, EdgeH, LoopH, FaceH>;

// "f3", "e7", "v2", "l1": the printed handle, which is also the id in the native file.
std::string element_name(const Element& e);

enum class Measure { length, area, width, distance, diameter };
const char* measure_name(Measure m);

// Where a face is pinched and how the edges there lie (paper 4.2).
enum class PinchLocation { necking, spiking, bossing };
enum class PinchConfiguration { straight, complex };

struct Subcase {
  // pinched_face only.
  PinchLocation location = PinchLocation::necking;
  PinchConfiguration configuration = PinchConfiguration::straight;
  // Gaps only: the border cycle passes a vertex twice; this gap is one of its simple cycles.
  bool shares_vertex = false;
  bool operator==(const Subcase&) const = default;
};

struct Problem {
  ProblemType type = ProblemType::face_gap;
  // In the order of spec/problems.md: gaps — the border cycle, then the faces across it;
  // pinched_face — the face, then the two closest edges; chains — their faces or edges;
  // same_geometry_faces — the two faces; mergeable_edges — the vertex, then its two edges.
  std::vector<Element> elements;
  double measure = 0.0;  // in model units (area for faces, length otherwise)
  Measure measure_kind = Measure::length;
  Subcase subcase;

  // The elements of one kind, in order.
  template <class H>
  std::vector<H> all() const {
    std::vector<H> out;
    for (const Element& e : elements)
      if (const H* h = std::get_if<H>(&e)) out.push_back(*h);
    return out;
  }
  // The first element of that kind, or an invalid handle.
  template <class H>
  H first() const {
    for (const Element& e : elements)
      if (const H* h = std::get_if<H>(&e)) return *h;
    return H{};
  }

  // Identity: the type and the elements (what the Table 1 audit and the pipeline's queues
  // compare), not the measure.
  bool same_identity(const Problem& o) const { return type == o.type && elements == o.elements; }
};

// Printed names of the elements, in order.
std::vector<std::string> element_names(const Problem& p);
// "necking/straight", "shares a vertex with another gap", or "" where the type has none.
std::string subcase_name(const Problem& p);

}  // namespace kintsugi

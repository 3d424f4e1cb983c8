// The data a report page draws (view/html_page.h), as one JSON document: each model
// tessellated (view/tessellate.h) into compact binary arrays, and each problem with
// what the page marks for it in each model (tinted faces, thick edges, dots) and
// where to look (an anchor point and a radius).
//
// The document is deterministic: the same models and problems give the same bytes
// (handles in order, objects with sorted keys, fixed binary layouts; no time, no paths
// beyond the title the caller gives).
//
// Layout (format "kintsugi-view/2"):
//   {"format", "title", "units", "tolerance", "chordal", "origin": [x,y,z], "size",
//    "grid": {"low": [x,y,z], "step"},
//    "colors": {type: "#rrggbb"},
//    "models": [{"name", "faces", "edges", "vertices",
//                "mesh": {"positions": q16, "face_vertices": u32,
//                         "chunks": [{"vertices", "index_bytes": 2 or 4, "indices": u16 or u32}]},
//                "lines": {"positions": q16, "edge_points": u32},
//                "untessellated": [{"face", "reason"}]}],
//    "problems": [{"type", "elements", "measure", "measure_name", "subcase", "action",
//                  "resolved", "operators", "reason", "deviation", "anchor": [x,y,z], "radius",
//                  "marks": [{"model", "faces": [face positions in that model's mesh],
//                             "lines": [x,y,z, x,y,z, ...  segment pairs], "points": [x,y,z, ...],
//                             "missing": [elements not alive in that model]}]}]}
//   u16/u32: base64 of little-endian uint16/uint32 arrays. Coordinates are relative to
//   "origin" (the centre of the models' bounds). q16: positions as uint16 triples q on a
//   grid, the point being low + step * q (within half a step of the tessellation's;
//   the marks, anchors and radii are exact).
//   Chunks: consecutive runs of whole faces, in order, whose indices count from the
//   chunk's first vertex; 16 bits unless one face has more than 65535 vertices.
//   face_vertices/edge_points: offsets, one per face/edge plus the end.
#pragma once

#include "kernel/body.h"

#include <nlohmann/json.hpp>

#include <optional>
#include <string>
#include <vector>

namespace kintsugi::view {

// One problem as the page lists it. The fields after `subcase` are those of a
// beautify report (empty for a page of detected problems only).
struct ProblemEntry {
  std::string type;                   // a problem name (repair/problem_type.h)
  std::vector<std::string> elements;  // printed handles: "f3", "e7", "v2", "l1"
  std::optional<double> measure;      // in model units; nullopt when not known
  std::string measure_name;           // "length", "area", ...
  std::string subcase;
  std::string action;                 // what beautify did ("repaired", "not repaired", ...), or empty
  bool resolved = false;              // gone after beautify (repaired, or removed by another repair)
  std::vector<std::string> operators;
  std::string reason;
  std::optional<double> deviation;
};

struct ModelInput {
  std::string name;  // "model", "before", "after"
  const Body* body = nullptr;
  // Which problems are marked in this model: all of them, or (the model after a
  // repair) only those not resolved, whose elements are still there.
  bool mark_repaired = true;
};

struct PageInput {
  std::string title;  // shown on the page, e.g. the input file's name
  std::string units = "mm";
  double tolerance = 0.0;
  double chordal = 0.0;  // 0: view::default_chordal of the first model
  std::vector<ModelInput> models;  // one, or two (before, after: drawn side by side)
  std::vector<ProblemEntry> problems;
};

// "#rrggbb" for each problem type; the eleven types have distinct colours, anything
// else is grey.
std::string problem_colour(const std::string& type);

// Throws std::invalid_argument when there is no model or a model has no body.
nlohmann::json scene_json(const PageInput& in);

}  // namespace kintsugi::view

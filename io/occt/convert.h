// Internal to io/occt: conversion between our Body and OpenCASCADE's TopoDS shapes.
// exchange.cpp adds files, units and messages on top (spec/exchange.md).
#pragma once

#include "kernel/body.h"

#include <TopoDS_Shape.hxx>

#include <algorithm>
#include <functional>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <unordered_map>
#include <vector>

namespace kintsugi::io::occt {

// Sub-shapes by element index: a vector for a whole body, a hash map for a few faces (a
// repair's region), so that converting a region costs what the region holds however large
// the body. An index never set reads as a null shape.
class ShapeSlots {
 public:
  // Dense storage for `n` slots (a whole body); until then, sparse.
  void make_dense(std::size_t n) {
    dense_.resize(n);
    sparse_mode_ = false;
  }
  TopoDS_Shape& operator[](std::size_t i) { return sparse_mode_ ? sparse_[i] : dense_[i]; }
  const TopoDS_Shape& operator[](std::size_t i) const {
    if (!sparse_mode_) return dense_[i];
    auto it = sparse_.find(i);
    return it == sparse_.end() ? null_ : it->second;
  }
  // f(index, shape) for each slot holding a shape, by increasing index.
  template <class F>
  void for_each(F f) const {
    if (!sparse_mode_) {
      for (std::size_t i = 0; i < dense_.size(); ++i)
        if (!dense_[i].IsNull()) f(i, dense_[i]);
      return;
    }
    std::vector<std::size_t> keys;
    for (const auto& [i, shape] : sparse_)
      if (!shape.IsNull()) keys.push_back(i);
    std::sort(keys.begin(), keys.end());
    for (std::size_t i : keys) f(i, sparse_.at(i));
  }

 private:
  bool sparse_mode_ = true;
  std::vector<TopoDS_Shape> dense_;
  std::unordered_map<std::size_t, TopoDS_Shape> sparse_;
  TopoDS_Shape null_;
};

// The shape made from a body, and which sub-shape came from which element (for
// BRepCheck messages), by handle index; dead or unconverted slots hold null shapes.
struct BuiltShape {
  TopoDS_Shape shape;   // a solid or shell, or a compound of them
  ShapeSlots vertex;    // TopoDS_Vertex per VertexH
  ShapeSlots edge;      // TopoDS_Edge per EdgeH (FORWARD = half-edge 2e)
  ShapeSlots face;      // TopoDS_Face per FaceH, oriented outward
  ShapeSlots loop_wire; // TopoDS_Wire per LoopH (face loops only)
  ShapeSlots shell;     // TopoDS_Shell per ShellH
  ShapeSlots solid;     // TopoDS_Solid per closed ShellH
};

// Builds the shape with one shared TopoDS_Edge per edge and one TopoDS_Vertex per
// vertex, so OpenCASCADE sees exactly our topology. Refuses (nullopt, *error) a body
// with a face or edge without geometry, or geometry OpenCASCADE rejects.
// With `only`, just those faces and their edges, as a compound of faces (no shells);
// with `loops` as well, a face that has an entry there is made with those loops alone
// (and only their edges are made). Vertices, edges and faces get the tolerance
// `precision` (the model's modelling precision, geo::Tolerances::precision), or
// OpenCASCADE's default 1e-7 when that is larger or none is given.
using LoopSubsets = std::map<FaceH, std::vector<LoopH>>;
std::optional<BuiltShape> to_shape(const Body& b, std::string* error, const std::set<FaceH>* only = nullptr,
                                   const LoopSubsets* loops = nullptr, double precision = 0);

// Names a face for messages ("face #12 (STEP entity #345)"); given the face's 1-based
// index in the shape's face map.
using FaceLocator = std::function<std::string(const TopoDS_Shape& face, int index)>;

// Builds a body from a shape's faces: solids and shells, free edges as border cycles.
// Faces on surfaces we cannot represent, non-manifold edges and inconsistent wires are
// refused with *error listing every offending face.
std::optional<Body> from_shape(const TopoDS_Shape& s, const FaceLocator& locate, std::vector<std::string>* warnings,
                               std::string* error);

// Sews a shape of unconnected faces (IGES trimmed surfaces) into shells, with
// `tolerance` (the file's resolution); a shape that already has shells is returned as is.
TopoDS_Shape sew_faces(const TopoDS_Shape& shape, double tolerance, std::vector<std::string>* warnings);

}  // namespace kintsugi::io::occt

// Internal to io/occt: conversion between our Body and OpenCASCADE's TopoDS shapes.
// exchange.cpp adds files, units and messages on top (spec/exchange.md).
#pragma once

#include "kernel/body.h"

#include <TopoDS_Shape.hxx>

#include <functional>
#include <optional>
#include <set>
#include <string>
#include <vector>

namespace kintsugi::io::occt {

// The shape made from a body, and which sub-shape came from which element (for
// BRepCheck messages). Sub-shape lists are indexed by handle; dead slots hold null shapes.
struct BuiltShape {
  TopoDS_Shape shape;                    // a solid or shell, or a compound of them
  std::vector<TopoDS_Shape> vertex;      // TopoDS_Vertex per VertexH
  std::vector<TopoDS_Shape> edge;        // TopoDS_Edge per EdgeH (FORWARD = half-edge 2e)
  std::vector<TopoDS_Shape> face;        // TopoDS_Face per FaceH, oriented outward
  std::vector<TopoDS_Shape> loop_wire;   // TopoDS_Wire per LoopH (face loops only)
  std::vector<TopoDS_Shape> shell;       // TopoDS_Shell per ShellH
  std::vector<TopoDS_Shape> solid;       // TopoDS_Solid per closed ShellH
};

// Builds the shape with one shared TopoDS_Edge per edge and one TopoDS_Vertex per
// vertex, so OpenCASCADE sees exactly our topology. Refuses (nullopt, *error) a body
// with a face or edge without geometry, or geometry OpenCASCADE rejects.
// With `only`, just those faces and their edges, as a compound of faces (no shells).
std::optional<BuiltShape> to_shape(const Body& b, std::string* error, const std::set<FaceH>* only = nullptr);

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

// Assembling a body from a description of its elements, for readers (native JSON,
// OpenCASCADE import). Readers do not replay Euler operators: they describe the final
// incidences. Readers call assemble() (invariants/assemble.h), which checks them —
// references in range, each element named once (here, in the kernel, which alone may
// fill a body's storage), then the whole-body topology check (invariants/) — before
// handing out a body. A description is refused with an error naming the element, never
// with undefined behaviour.
//
// Ids are the handles the body will have (so names survive write → read); gaps between
// ids become dead slots. To bound memory, ids must be below 2·count + 1024 for each kind.
#pragma once

#include "geometry/types.h"
#include "kernel/body.h"

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace kintsugi {

struct VertexDesc {
  std::uint32_t id;
  geo::Vec3 point;
};
struct HalfedgeDesc {
  std::uint32_t origin;  // vertex id
  std::uint32_t next;    // half-edge id (2·edge + side)
  std::uint32_t loop;    // loop id
};
struct EdgeDesc {
  std::uint32_t id;
  HalfedgeDesc he[2];  // half-edges 2·id and 2·id + 1; the curve runs along he[0]
  geo::Curve curve;
};
struct LoopDesc {
  std::uint32_t id;
  std::optional<std::uint32_t> face;   // none: a border cycle
  std::optional<std::uint32_t> first;  // none: a lone-vertex loop
  std::optional<std::uint32_t> lone;   // the lone vertex
};
struct FaceDesc {
  std::uint32_t id;
  std::uint32_t shell;
  std::vector<std::uint32_t> loops;  // outer first
  geo::Surface surface;
  bool same_sense = true;
};
struct ShellDesc {
  std::uint32_t id;
  std::uint32_t genus = 0;
};

struct BodyDescription {
  std::vector<VertexDesc> vertices;
  std::vector<EdgeDesc> edges;
  std::vector<LoopDesc> loops;
  std::vector<FaceDesc> faces;
  std::vector<ShellDesc> shells;
};

// Where in the input an element came from, for error messages (e.g. a JSON pointer).
struct AssembleError {
  std::string element;  // "edge 3", "loop 2", ... or "" for the whole body
  std::string message;
};

// The first half of assemble(): builds the body after checking ids and references only,
// or says what is wrong. Its loops and rotations are NOT yet known to close: only
// assemble() (invariants/assemble.h) hands out a body fit for the operators. The body
// takes the description's geometry: pass it with std::move where it is not needed again.
std::optional<Body> assemble_references(BodyDescription d, AssembleError* error);

// The description of a body (live elements only, ids = handles): what writers write.
BodyDescription describe(const Body& b);

}  // namespace kintsugi

#include "view/scene.h"

#include "view/tessellate.h"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <map>
#include <stdexcept>

namespace kintsugi::view {

namespace {

// Distinct, saturated colours, far from the grey of the model and the black of its
// edges (after Sasha Trubetskoy's list of distinct colours, chosen by hand).
const std::map<std::string, std::string, std::less<>>& colour_table() {
  static const std::map<std::string, std::string, std::less<>> table = {
      {"face_gap", "#e6194b"},         {"edge_gap", "#f58231"},         {"multi_face_gap", "#ffe119"},
      {"pinched_face", "#911eb4"},     {"small_face_chain", "#42d4f4"}, {"sliver_face", "#f032e6"},
      {"short_edge_chain", "#3cb44b"}, {"same_geometry_faces", "#4363d8"}, {"small_face", "#bfef45"},
      {"mergeable_edges", "#9a6324"},  {"short_edge", "#469990"},
  };
  return table;
}

std::string base64(const std::uint8_t* data, std::size_t n) {
  static const char* abc = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((n + 2) / 3 * 4);
  std::size_t i = 0;
  for (; i + 2 < n; i += 3) {
    const std::uint32_t v = std::uint32_t(data[i]) << 16 | std::uint32_t(data[i + 1]) << 8 | data[i + 2];
    for (int s = 18; s >= 0; s -= 6) out += abc[(v >> s) & 63];
  }
  if (i < n) {
    const std::uint32_t v = std::uint32_t(data[i]) << 16 | (i + 1 < n ? std::uint32_t(data[i + 1]) << 8 : 0);
    out += abc[(v >> 18) & 63];
    out += abc[(v >> 12) & 63];
    out += i + 1 < n ? abc[(v >> 6) & 63] : '=';
    out += '=';
  }
  return out;
}

// Little-endian bytes whatever the machine, so the page (typed arrays on a
// little-endian browser) and the bytes of the file do not depend on it.
void put16(std::vector<std::uint8_t>& out, std::uint32_t v) {
  for (int i = 0; i < 2; ++i) out.push_back(std::uint8_t(v >> (8 * i)));
}
void put32(std::vector<std::uint8_t>& out, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) out.push_back(std::uint8_t(v >> (8 * i)));
}

// Positions as 16-bit integers on a grid over the scene's bounds, the same step on
// every axis: half the bytes of float32, and the page draws them as they are (a
// normalised attribute and the mesh's scale and offset undo the grid on the GPU), so
// nothing is decoded in JavaScript. The error is at most half a step, 1/131070 of the
// model's largest extent: a step is below a pixel of a 1,000-pixel view until the view
// is about 1/65 of the model across (docs/benchmarks.md).
struct Grid {
  geo::Vec3 low = geo::Vec3::Zero();  // relative to the scene's origin
  double step = 1.0;
  static Grid over(const geo::Box& b, const geo::Vec3& origin) {
    Grid g;
    if (b.empty()) return g;
    g.low = b.min - origin;
    const double extent = (b.max - b.min).maxCoeff();
    if (extent > 0) g.step = extent / kGridMax;
    return g;
  }
  static constexpr double kGridMax = 65535.0;
};
struct Q16 {
  std::vector<std::uint8_t> bytes;
  void add(const geo::Vec3& p, const geo::Vec3& origin, const Grid& g) {
    for (int i = 0; i < 3; ++i) {
      const double q = std::round((p[i] - origin[i] - g.low[i]) / g.step);
      put16(bytes, std::uint32_t(std::clamp(q, 0.0, Grid::kGridMax)));
    }
  }
  std::string str() const { return base64(bytes.data(), bytes.size()); }
};
struct U32 {
  std::vector<std::uint8_t> bytes;
  void add(std::uint32_t v) { put32(bytes, v); }
  std::string str() const { return base64(bytes.data(), bytes.size()); }
};

// A handle's printed name, split: 'f' and 12 for "f12".
struct ElementName {
  char kind = 0;
  std::uint32_t index = 0;
};
std::optional<ElementName> parse_element(const std::string& s) {
  if (s.size() < 2) return std::nullopt;
  ElementName n{s[0], 0};
  auto [end, ec] = std::from_chars(s.data() + 1, s.data() + s.size(), n.index);
  if (ec != std::errc() || end != s.data() + s.size()) return std::nullopt;
  return n;
}

// One model, tessellated, with where each face sits in the mesh.
struct Drawn {
  const Body* body;
  BodyMesh mesh;
  std::vector<std::int64_t> face_position;  // by face index; -1: not a live face
  std::vector<std::int64_t> edge_position;
};

Drawn draw(const Body& b, double chordal) {
  Drawn d{&b, tessellate(b, chordal), {}, {}};
  d.face_position.assign(b.face_slots(), -1);
  d.edge_position.assign(b.edge_slots(), -1);
  for (std::size_t i = 0; i < d.mesh.faces.size(); ++i) d.face_position[d.mesh.faces[i].face.idx()] = std::int64_t(i);
  for (std::size_t i = 0; i < d.mesh.edges.size(); ++i) d.edge_position[d.mesh.edges[i].edge.idx()] = std::int64_t(i);
  return d;
}

// The faces' triangles in chunks of whole faces with at most 65535 vertices each, so
// their indices are 16 bits (0 to 65534), counted from the chunk's first vertex (WebGL 1 draws 16-bit
// indices natively, and 65535 is kept free: WebGL 2 reads it as a primitive restart).
// A face with more vertices than that is a chunk of its own with 32-bit indices.
constexpr std::size_t kChunkVertices = 65535;

nlohmann::json model_json(const Drawn& d, const std::string& name, const geo::Vec3& origin, const Grid& grid) {
  Q16 positions, line_positions;
  U32 face_vertices, edge_points;
  nlohmann::json chunks = nlohmann::json::array();
  nlohmann::json untessellated = nlohmann::json::array();
  std::uint32_t nv = 0, np = 0;
  std::size_t chunk_start = 0;  // first vertex of the chunk being filled
  std::vector<std::uint8_t> chunk_indices;
  bool wide = false;
  auto close_chunk = [&] {
    if (nv > chunk_start)
      chunks.push_back({{"vertices", nv - chunk_start},
                        {"index_bytes", wide ? 4 : 2},
                        {"indices", base64(chunk_indices.data(), chunk_indices.size())}});
    chunk_start = nv;
    chunk_indices.clear();
    wide = false;
  };
  for (const FaceMesh& f : d.mesh.faces) {
    face_vertices.add(nv);
    if (nv + f.vertices.size() - chunk_start > kChunkVertices) close_chunk();
    if (f.vertices.size() > kChunkVertices) wide = true;
    for (const geo::Vec3& p : f.vertices) positions.add(p, origin, grid);
    const std::uint32_t base = nv - std::uint32_t(chunk_start);
    for (const auto& t : f.triangles)
      for (std::uint32_t i : t) {
        if (wide) put32(chunk_indices, base + i);
        else put16(chunk_indices, base + i);
      }
    nv += std::uint32_t(f.vertices.size());
    if (wide) close_chunk();
    if (!f.problem.empty()) untessellated.push_back({{"face", f.face.str()}, {"reason", f.problem}});
  }
  close_chunk();
  face_vertices.add(nv);
  for (const EdgePolyline& e : d.mesh.edges) {
    edge_points.add(np);
    for (const geo::Vec3& p : e.points) line_positions.add(p, origin, grid);
    np += std::uint32_t(e.points.size());
  }
  edge_points.add(np);
  const Counts c = d.body->counts();
  return {{"name", name},
          {"faces", c.faces},
          {"edges", c.edges},
          {"vertices", c.vertices},
          {"mesh", {{"positions", positions.str()}, {"face_vertices", face_vertices.str()}, {"chunks", chunks}}},
          {"lines", {{"positions", line_positions.str()}, {"edge_points", edge_points.str()}}},
          {"untessellated", untessellated}};
}

void add_xyz(nlohmann::json& a, const geo::Vec3& p, const geo::Vec3& origin) {
  for (int i = 0; i < 3; ++i) a.push_back(p[i] - origin[i]);
}

// What the page draws for one problem in one model; `box` grows around it.
nlohmann::json mark_json(const Drawn& d, std::size_t model, const ProblemEntry& p, const geo::Vec3& origin,
                         geo::Box& box) {
  const Body& b = *d.body;
  nlohmann::json faces = nlohmann::json::array(), lines = nlohmann::json::array(), points = nlohmann::json::array(),
                 missing = nlohmann::json::array();
  // Gaps are outlined (their border cycle); the faces around them are only context.
  const bool gap = p.type.size() > 4 && p.type.compare(p.type.size() - 4, 4, "_gap") == 0;
  auto polyline = [&](const std::vector<geo::Vec3>& pts) {
    for (std::size_t i = 0; i + 1 < pts.size(); ++i) {
      add_xyz(lines, pts[i], origin);
      add_xyz(lines, pts[i + 1], origin);
    }
    for (const geo::Vec3& q : pts) box.add(q);
  };
  auto point = [&](const geo::Vec3& q) {
    add_xyz(points, q, origin);
    box.add(q);
  };
  for (const std::string& name : p.elements) {
    const auto e = parse_element(name);
    bool found = false;
    if (e && e->kind == 'f' && b.alive(FaceH(e->index)) && d.face_position[e->index] >= 0) {
      found = true;
      const FaceMesh& f = d.mesh.faces[std::size_t(d.face_position[e->index])];
      if (!gap) faces.push_back(d.face_position[e->index]);
      if (!gap || f.vertices.empty())
        for (const geo::Vec3& q : f.vertices) box.add(q);
      if (f.vertices.empty() && !gap)  // not tessellated: outline it instead
        for (LoopH l : b.loops_of(FaceH(e->index)))
          for (HalfedgeH h : b.loop_halfedges(l)) polyline(d.mesh.edges[std::size_t(d.edge_position[edge_of(h).idx()])].points);
    } else if (e && e->kind == 'e' && b.alive(EdgeH(e->index))) {
      found = true;
      const EdgeH edge(e->index);
      polyline(d.mesh.edges[std::size_t(d.edge_position[e->index])].points);
      // Dots at the ends: a short edge is a few pixels long at the scale of the model.
      point(b.point(b.origin(halfedge_of(edge, 0))));
      point(b.point(b.target(halfedge_of(edge, 0))));
    } else if (e && e->kind == 'v' && b.alive(VertexH(e->index))) {
      found = true;
      point(b.point(VertexH(e->index)));
    } else if (e && e->kind == 'l' && b.alive(LoopH(e->index))) {
      found = true;
      const LoopH l(e->index);
      if (b.is_lone(l)) point(b.point(b.lone_vertex(l)));
      for (HalfedgeH h : b.loop_halfedges(l)) polyline(d.mesh.edges[std::size_t(d.edge_position[edge_of(h).idx()])].points);
    }
    if (!found) missing.push_back(name);
  }
  return {{"model", model}, {"faces", faces}, {"lines", lines}, {"points", points}, {"missing", missing}};
}

nlohmann::json optional_number(const std::optional<double>& v) { return v ? nlohmann::json(*v) : nlohmann::json(); }
nlohmann::json optional_string(const std::string& s) { return s.empty() ? nlohmann::json() : nlohmann::json(s); }

}  // namespace

std::string problem_colour(const std::string& type) {
  const auto& t = colour_table();
  auto it = t.find(type);
  return it == t.end() ? "#808080" : it->second;
}

nlohmann::json scene_json(const PageInput& in) {
  if (in.models.empty()) throw std::invalid_argument("a page needs at least one model");
  for (const ModelInput& m : in.models)
    if (!m.body) throw std::invalid_argument("model '" + m.name + "' has no body");
  const double chordal = in.chordal > 0 ? in.chordal : default_chordal(*in.models.front().body);
  std::vector<Drawn> drawn;
  geo::Box all;
  for (const ModelInput& m : in.models) {
    drawn.push_back(draw(*m.body, chordal));
    const geo::Box& bx = drawn.back().mesh.bounds;
    if (!bx.empty()) all.add(bx.min), all.add(bx.max);
  }
  const geo::Vec3 origin = all.empty() ? geo::Vec3::Zero() : all.centre();
  nlohmann::json j;
  j["format"] = "kintsugi-view/2";
  j["title"] = in.title;
  j["units"] = in.units;
  j["tolerance"] = in.tolerance;
  j["chordal"] = chordal;
  j["origin"] = {origin.x(), origin.y(), origin.z()};
  j["size"] = all.diagonal();
  const Grid grid = Grid::over(all, origin);
  j["grid"] = {{"low", {grid.low.x(), grid.low.y(), grid.low.z()}}, {"step", grid.step}};
  j["colors"] = nlohmann::json::object();
  for (const auto& [type, colour] : colour_table()) j["colors"][type] = colour;
  j["models"] = nlohmann::json::array();
  for (std::size_t i = 0; i < drawn.size(); ++i) j["models"].push_back(model_json(drawn[i], in.models[i].name, origin, grid));
  j["problems"] = nlohmann::json::array();
  for (const ProblemEntry& p : in.problems) {
    nlohmann::json e = {{"type", p.type},
                        {"elements", p.elements},
                        {"measure", optional_number(p.measure)},
                        {"measure_name", optional_string(p.measure_name)},
                        {"subcase", optional_string(p.subcase)},
                        {"action", optional_string(p.action)},
                        {"resolved", p.resolved},
                        {"operators", p.operators},
                        {"reason", optional_string(p.reason)},
                        {"deviation", optional_number(p.deviation)},
                        {"marks", nlohmann::json::array()}};
    geo::Box box;
    for (std::size_t i = 0; i < drawn.size(); ++i) {
      if (!in.models[i].mark_repaired && p.resolved) continue;
      geo::Box mbox;
      e["marks"].push_back(mark_json(drawn[i], i, p, origin, mbox));
      // The anchor is where the problem is in the first model that has it.
      if (box.empty()) box = mbox;
    }
    const geo::Vec3 anchor = box.empty() ? origin : box.centre();
    e["anchor"] = nlohmann::json::array();
    add_xyz(e["anchor"], anchor, origin);
    e["radius"] = box.empty() ? 0.0 : 0.5 * box.diagonal();
    j["problems"].push_back(std::move(e));
  }
  return j;
}

}  // namespace kintsugi::view

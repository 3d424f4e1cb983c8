#include "geometry/curve.h"
#include "geometry/surface.h"
#include "zoo/zoo.h"

#include <cmath>
#include <sstream>

namespace kintsugi::zoo {

using geo::Vec3;

namespace {
std::string offence(const std::string& what, double d, const std::string& where) {
  std::ostringstream os;
  os << what << " is " << d << " off " << where;
  return os.str();
}
}  // namespace

std::vector<std::string> geometry_offences(const Body& b, double precision) {
  std::vector<std::string> out;
  for (VertexH v : b.vertices()) {
    const Vec3& p = b.point(v);
    for (HalfedgeH h : b.outgoing(v)) {
      const geo::Curve& c = b.curve(edge_of(h));
      if (!std::holds_alternative<std::monostate>(c)) {
        double d = geo::closest_point(c, p).distance;
        if (!(d <= precision)) out.push_back(offence(v.str(), d, edge_of(h).str()));
      } else {
        out.push_back(edge_of(h).str() + " has no curve");
      }
      FaceH f = b.face(h);
      if (!f.valid()) continue;
      const geo::Surface& s = b.surface(f);
      if (std::holds_alternative<std::monostate>(s)) {
        out.push_back(f.str() + " has no surface");
        continue;
      }
      double d = std::abs(geo::signed_distance(s, p));
      if (!(d <= precision)) out.push_back(offence(v.str(), d, f.str()));
    }
  }
  for (EdgeH e : b.edges()) {
    if (!std::holds_alternative<geo::Line>(b.curve(e))) continue;
    Vec3 m = (b.point(b.origin(halfedge_of(e, 0))) + b.point(b.target(halfedge_of(e, 0)))) / 2;
    for (unsigned s = 0; s < 2; ++s) {
      FaceH f = b.face(halfedge_of(e, s));
      if (!f.valid() || std::holds_alternative<std::monostate>(b.surface(f))) continue;
      double d = std::abs(geo::signed_distance(b.surface(f), m));
      if (!(d <= precision)) out.push_back(offence("midpoint of " + e.str(), d, f.str()));
    }
  }
  // Planar faces: the outer loop turns counter-clockwise about the outward normal.
  for (FaceH f : b.faces()) {
    const auto* plane = std::get_if<geo::Plane>(&b.surface(f));
    LoopH l = b.outer_loop(f);
    if (!plane || b.is_lone(l)) continue;
    std::vector<VertexH> vs = b.loop_vertices(l);
    if (vs.size() < 3) continue;
    Vec3 n = Vec3::Zero();
    for (std::size_t i = 0; i < vs.size(); ++i) n += b.point(vs[i]).cross(b.point(vs[(i + 1) % vs.size()]));
    Vec3 outward = b.same_sense(f) ? plane->frame.z : Vec3(-plane->frame.z);
    if (!(n.dot(outward) > 0)) out.push_back(f.str() + "'s outer loop turns clockwise about its outward normal");
  }
  return out;
}

}  // namespace kintsugi::zoo

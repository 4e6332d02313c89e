#include "mesh/float_safe.hpp"

#include <CGAL/Polygon_mesh_processing/repair_degeneracies.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Polygon_mesh_processing/shape_predicates.h>

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "mesh/cgal_mesh.hpp"

namespace steady {

namespace PMP = CGAL::Polygon_mesh_processing;

namespace {
// Through memory: at -O3 with -frounding-math, GCC 12 vectorized the three narrowings of a Vec3 and dropped two
// of them (seen in the disassembly: x and y came back unrounded).
double to_float(double d) {
  volatile float f = static_cast<float>(d);
  return f;
}
}  // namespace

Vec3 float_rounded(const Vec3& p) { return Vec3(to_float(p.x), to_float(p.y), to_float(p.z)); }

void round_to_floats(TriangleMesh& mesh) {
  for (Vec3& v : mesh.vertices) v = float_rounded(v);
}

std::int64_t make_float_safe(TriangleMesh& band, const std::string& what) {
  if (band.triangles.empty()) return 0;
  // A float converts to a double exactly, so the inexact-constructions kernel's predicates are exact on these points.
  CgalMesh m = to_half_edge_mesh<CgalMesh>(band);
  for (const auto v : m.vertices()) {
    const auto& p = m.point(v);
    const Vec3 r = float_rounded(Vec3(p.x(), p.y(), p.z()));
    m.point(v) = CgalKernel::Point_3(r.x, r.y, r.z);
  }
  bool degenerate = false;
  for (const auto f : m.faces()) degenerate = degenerate || PMP::is_degenerate_triangle_face(f, m);
  const std::int64_t before = static_cast<std::int64_t>(m.number_of_faces());
  if (degenerate) {
    if (!PMP::remove_degenerate_faces(m))
      throw std::runtime_error("mesh: a triangle of " + what + " made flat by rounding to floats cannot be removed");
    m.collect_garbage();
  }
  if (PMP::does_self_intersect(m))
    throw std::runtime_error("mesh: " + what + " intersects itself once rounded to floats");
  // Back as an indexed mesh of the vertices still in a triangle (a removal can leave one isolated).
  band.vertices.clear(), band.triangles.clear();
  std::vector<std::uint32_t> number(m.number_of_vertices() + m.number_of_removed_vertices(), UINT32_MAX);
  for (const auto f : m.faces()) {
    Triangle t;
    int k = 0;
    for (const auto v : CGAL::vertices_around_face(m.halfedge(f), m)) {
      if (number[v] == UINT32_MAX) {
        number[v] = static_cast<std::uint32_t>(band.vertices.size());
        band.vertices.emplace_back(m.point(v).x(), m.point(v).y(), m.point(v).z());
      }
      t[k++] = number[v];
    }
    band.triangles.push_back(t);
  }
  return before - static_cast<std::int64_t>(m.number_of_faces());
}

}  // namespace steady

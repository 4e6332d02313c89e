#include "mesh/cgal_mesh.hpp"

#include <cstdint>
#include <set>

#include "mesh/vertex_key.hpp"

namespace steady {

TriangleMesh without_kept_caps(const ExactMesh& m, const std::vector<Vec3>& centers, bool flip, const char* cap_gone) {
  std::set<VertexKey> center_keys;
  for (const Vec3& c : centers) center_keys.insert(vertex_key(c));
  const std::size_t slots = m.number_of_vertices() + m.number_of_removed_vertices();
  std::vector<Vec3> point(slots);
  std::vector<char> is_center(slots, 0), dropped(m.number_of_faces() + m.number_of_removed_faces(), 0);
  std::size_t found = 0;
  for (const auto v : m.vertices()) {
    const auto& p = m.point(v);
    point[v] = Vec3(CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z()));
    if (center_keys.empty() || !center_keys.count(vertex_key(point[v]))) continue;
    is_center[v] = 1, ++found;
    for (const auto f : CGAL::faces_around_target(m.halfedge(v), m)) {
      if (f == ExactMesh::null_face()) throw std::runtime_error("mesh: a cap kept by the Boolean was opened by it");
      dropped[f] = 1;
    }
  }
  if (found != center_keys.size()) throw std::runtime_error(cap_gone);
  TriangleMesh out;
  std::vector<std::uint32_t> number(slots, UINT32_MAX);
  for (const auto f : m.faces()) {
    if (dropped[f]) continue;
    Triangle t;
    int k = 0;
    for (const auto v : CGAL::vertices_around_face(m.halfedge(f), m)) {
      if (is_center[v]) throw std::runtime_error("mesh: a cap's center is left in the Boolean's result");
      if (number[v] == UINT32_MAX) number[v] = static_cast<std::uint32_t>(out.vertices.size()), out.vertices.push_back(point[v]);
      t[k++] = number[v];
    }
    if (flip) std::swap(t[1], t[2]);
    out.triangles.push_back(t);
  }
  return out;
}

}  // namespace steady

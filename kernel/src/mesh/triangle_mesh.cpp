#include "steady/mesh/triangle_mesh.hpp"

#include <algorithm>
#include <unordered_map>

namespace steady {

double mesh_volume(const TriangleMesh& mesh) {
  // Sum of signed tetrahedra from a point near the mesh (its first vertex): less cancellation than the origin.
  if (mesh.vertices.empty()) return 0.0;
  const Vec3 o = mesh.vertices[0];
  double six = 0.0;
  for (const Triangle& t : mesh.triangles)
    six += glm::dot(mesh.vertices[t[0]] - o, glm::cross(mesh.vertices[t[1]] - o, mesh.vertices[t[2]] - o));
  return six / 6.0;
}

double mesh_area(const TriangleMesh& mesh) {
  double twice = 0.0;
  for (const Triangle& t : mesh.triangles)
    twice += glm::length(glm::cross(mesh.vertices[t[1]] - mesh.vertices[t[0]], mesh.vertices[t[2]] - mesh.vertices[t[0]]));
  return 0.5 * twice;
}

MeshEdgeReport mesh_edge_report(const TriangleMesh& mesh) {
  // Per undirected edge: how often it is used each way.
  std::unordered_map<std::uint64_t, std::pair<int, int>> uses;
  uses.reserve(mesh.triangles.size() * 2);
  for (const Triangle& t : mesh.triangles)
    for (int i = 0; i < 3; ++i) {
      const std::uint32_t a = t[i], b = t[(i + 1) % 3];
      const std::uint64_t k = (static_cast<std::uint64_t>(std::min(a, b)) << 32) | std::max(a, b);
      auto& u = uses[k];
      (a < b ? u.first : u.second) += 1;
    }
  MeshEdgeReport r;
  for (const auto& [k, u] : uses) {
    const int total = u.first + u.second;
    if (total == 1) ++r.border_edges;
    else if (total > 2) ++r.non_manifold_edges;
    else if (u.first != 1) ++r.misoriented_edges;
  }
  return r;
}

}  // namespace steady

#pragma once
// A flat cap on a loop of a mesh: the fan around the centroid of the loop's vertices. The trimmed mesh closes the
// band's pieces with these, and the groups close their members; two fans on one loop, from the same vertices in
// the same order, are the same triangles bit for bit (the centroid is summed in the loop's order).
#include <cstdint>
#include <vector>

#include "steady/mesh/triangle_mesh.hpp"

namespace steady {

// Appends the fan on `loop` (indices of mesh's vertices) to `mesh`, wound in the loop's order (`reversed`: against
// it), and returns its center (the new vertex).
inline Vec3 append_fan(TriangleMesh& mesh, const std::vector<std::uint32_t>& loop, bool reversed) {
  Vec3 centroid(0.0);
  for (std::uint32_t i : loop) centroid += mesh.vertices[i];
  centroid /= static_cast<double>(loop.size());
  const auto c = static_cast<std::uint32_t>(mesh.vertices.size());
  mesh.vertices.push_back(centroid);
  for (std::size_t i = 0; i < loop.size(); ++i) {
    const std::uint32_t a = loop[i], b = loop[(i + 1) % loop.size()];
    mesh.triangles.push_back(reversed ? Triangle{c, b, a} : Triangle{c, a, b});
  }
  return centroid;
}

}  // namespace steady

#pragma once
// The CGAL side of trimmed meshes: a TriangleMesh as CGAL's half-edge mesh, with inexact constructions (queries:
// distances, sides, self-intersection) or exact ones (the band's Boolean).
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>

#include <stdexcept>
#include <vector>

#include "steady/mesh/triangle_mesh.hpp"

namespace steady {

using CgalKernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using CgalMesh = CGAL::Surface_mesh<CgalKernel::Point_3>;
using ExactKernel = CGAL::Exact_predicates_exact_constructions_kernel;
using ExactMesh = CGAL::Surface_mesh<ExactKernel::Point_3>;

// `m` as a half-edge mesh of either kernel; std::runtime_error if a triangle cannot join it (not a 2-manifold).
template <class M>
M to_half_edge_mesh(const TriangleMesh& m) {
  using P = typename M::Point;
  M out;
  std::vector<typename M::Vertex_index> v;
  v.reserve(m.vertices.size());
  for (const Vec3& p : m.vertices) v.push_back(out.add_vertex(P(p.x, p.y, p.z)));
  for (const Triangle& t : m.triangles)
    if (out.add_face(v[t[0]], v[t[1]], v[t[2]]) == M::null_face())
      throw std::runtime_error("mesh: a triangle could not join the half-edge mesh (not a 2-manifold)");
  return out;
}

// A Boolean's result rounded once to doubles, without the caps it was asked to keep (fans around the given
// centers, which no other operand touched), as an indexed mesh; `flip` turns every triangle over.
// std::runtime_error with `cap_gone` when a center is missing (an operand cut into its cap).
TriangleMesh without_kept_caps(const ExactMesh& m, const std::vector<Vec3>& centers, bool flip, const char* cap_gone);

}  // namespace steady

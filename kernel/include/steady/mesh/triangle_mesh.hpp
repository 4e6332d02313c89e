#pragma once
// An indexed triangle mesh: what the lattice tessellation returns and the mesh writers take. Triangles are
// counterclockwise seen from outside (outward normals); a closed mesh bounds the solid on their inner side.
#include <array>
#include <cstdint>
#include <vector>

#include "steady/core/vec.hpp"

namespace steady {

using Triangle = std::array<std::uint32_t, 3>;

struct TriangleMesh {
  std::vector<Vec3> vertices;
  std::vector<Triangle> triangles;
};

// Signed volume enclosed (divergence theorem; exact for a closed, consistently oriented mesh).
double mesh_volume(const TriangleMesh& mesh);
// Sum of the triangles' areas.
double mesh_area(const TriangleMesh& mesh);

// The undirected edges used by exactly one triangle, and by more than two: both empty for a closed 2-manifold.
// Also counts directed edges used twice (two neighbouring triangles with opposite orientations).
struct MeshEdgeReport {
  std::int64_t border_edges = 0;
  std::int64_t non_manifold_edges = 0;
  std::int64_t misoriented_edges = 0;
  bool closed_manifold() const { return border_edges == 0 && non_manifold_edges == 0 && misoriented_edges == 0; }
};
MeshEdgeReport mesh_edge_report(const TriangleMesh& mesh);

}  // namespace steady

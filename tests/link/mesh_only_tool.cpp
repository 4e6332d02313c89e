// A mesh-only tool, linked against steady_mesh alone: lattice meshes and printer files need no OpenCASCADE (test
// `link_mesh_without_occ` checks its shared libraries).
#include <cstdio>

#include "steady/mesh.hpp"  // the umbrella header: it must not pull OpenCASCADE in

int main() {
  using namespace steady;
  const Lattice lattice = Lattice::incremental({{Vec3(0.0), 0.2}}, {{0, 1, 0, 0, 0, 0.1, 0.1}, {0, 0, 1, 0, 0, 0.1, 0.1}},
                                               {3, 3, 1}, Similarity::translation({1, 0, 0}),
                                               Similarity::translation({0, 1, 0}), Similarity::translation({0, 0, 1}));
  const TriangleMesh mesh = lattice_mesh(lattice, {0.01});
  const MeshEdgeReport edges = mesh_edge_report(mesh);
  std::printf("triangles %zu, closed %d, volume %g\n", mesh.triangles.size(), edges.closed_manifold(), mesh_volume(mesh));
  return edges.closed_manifold() && mesh_volume(mesh) > 0.0 ? 0 : 1;
}

#pragma once
// A lattice straight to a triangle mesh, without a B-rep and without a global Boolean.
//
// Every hub is the sphere of its ball with one hole per beam, and every beam a strip of triangles between the
// hole of its hub at one end and the hole of its hub at the other: neighbouring pieces share the vertices of the
// circles where they meet, so the whole lattice is one closed, consistently oriented 2-manifold. A hub whose exit
// circles overlap (crowded, or the hull model) is the union of its ball and its stumps up to their collars
// (hub_collars.hpp), tessellated as a radial graph around its center (no Boolean); beyond the collars the beams
// run free. Each distinct hub shape (hub_catalog.hpp) is tessellated once per scale octave and placed as similar
// copies, so the cost of the geometry grows with the number of distinct hubs, the placing with the elements.
//
// Accuracy: `tolerance` bounds, in model units, the distance from every triangle to the exact surface of its
// ball or cone (chord error); every vertex lies on the exact surface (the mesh is inscribed).
#include <cstdint>
#include <string>

#include "steady/core/progress.hpp"
#include "steady/lattice/flat_lattice.hpp"
#include "steady/lattice/lattice.hpp"
#include "steady/mesh/triangle_mesh.hpp"

namespace steady {

struct MeshOptions {
  double tolerance = 0.01;  // model units; > 0 and below a quarter of the smallest ball radius
};

struct LatticeMeshStats {
  std::int64_t hubs = 0;
  std::int64_t crowded_hubs = 0;     // hubs whose exit circles overlap (radial graphs up to their collars)
  std::int64_t beams = 0;            // strips
  std::int64_t distinct_hubs = 0;    // distinct hub shapes up to similarity
  std::int64_t templates = 0;        // (shape, scale level) pairs tessellated
  std::int64_t vertices = 0;
  std::int64_t triangles = 0;
  std::int64_t foreign_groups = 0;   // groups of hubs united: their elements meet foreign ones, or a short beam
  std::int64_t foreign_hubs = 0;     // hubs in those groups
  std::int64_t short_beams = 0;      // beams too short for their hubs' collars, whose two hubs join a group
  double template_seconds = 0.0;     // tessellating the templates
  double group_seconds = 0.0;        // uniting the groups (CGAL's exact corefinement)
  double placing_seconds = 0.0;      // placing copies and strips
};

// An estimate of the mesh lattice_mesh makes, from the tolerance, the balls' radii and the beams alone (no
// template is made; linear in the elements): an upper bound of the counts for clean hubs (crowded hubs, tessellated
// by refinement, may exceed it; tests/kernel/test_mesh_estimate.cpp measures it against real meshes).
struct MeshEstimate {
  double vertices = 0.0, triangles = 0.0;  // double: a tiny tolerance gives counts beyond any integer type
  double bytes = 0.0;                      // of the indexed mesh (vertices and triangles)
};
MeshEstimate estimate_lattice_mesh(const FlatLattice& lattice, double tolerance);
// Throws ResourceLimit when the estimate exceeds the memory budget, with the estimate, the tolerance that would fit
// and what to do instead (streamed STL, a 3MF beam lattice); `what` names the call.
void require_mesh_memory(const FlatLattice& lattice, double tolerance, const std::string& what);

// InvalidInput: tolerance not finite or not positive ("tolerance"), tolerance of a quarter of a ball's radius or
// more, a lattice whose elements meet foreign ones ("lattice"), a crowded hub whose collars do not fit ("hub").
// ResourceLimit: a mesh beyond the memory budget, refused from the estimate before any work (names the triangle
// count and a tolerance that fits), then from the exact count once the templates are made.
TriangleMesh lattice_mesh(const FlatLattice& lattice, const MeshOptions& options, LatticeMeshStats* stats = nullptr,
                          Progress& progress = no_progress());
TriangleMesh lattice_mesh(const Lattice& lattice, const MeshOptions& options, LatticeMeshStats* stats = nullptr,
                          Progress& progress = no_progress());

}  // namespace steady

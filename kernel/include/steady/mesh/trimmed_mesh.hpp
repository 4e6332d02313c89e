#pragma once
// A lattice trimmed into a body as a mesh, optionally with a skin: the mesh counterpart of a LatticePart.
//
// Hubs (a ball and its half-beams) are classified against the surface the lattice is trimmed to: inside hubs are
// placed whole, outside hubs dropped, and only the crossing ones go through a Boolean: the band of crossing hubs
// and the beams that cross (capped where they meet a hub that is not in the band) is intersected with the body by
// CGAL's corefinement, the caps at inside hubs are removed again, and the band is joined to the inside part along
// those hubs' own circles. With a skin, the band (cut at the body where it reaches the body's surface) is then
// united with the skin (the body minus its inner offset), so that the skin and the lattice are one closed mesh.
#include <cstdint>

#include "steady/core/progress.hpp"
#include "steady/lattice/flat_lattice.hpp"
#include "steady/mesh/lattice_mesh.hpp"
#include "steady/mesh/triangle_mesh.hpp"

namespace steady {

struct TrimmedMeshRequest {
  const TriangleMesh* body = nullptr;   // closed, outward, not self-intersecting: the part's surface
  const TriangleMesh* inner = nullptr;  // with a skin: the body's inner offset (closed, outward), inside `body`
};

struct TrimmedMeshStats {
  LatticeMeshStats mesh;
  std::int64_t inside_hubs = 0, crossing_hubs = 0, outside_hubs = 0;
  std::int64_t band_triangles = 0;  // triangles that went through the Boolean
  double boolean_seconds = 0.0;
};

// InvalidInput naming "body" or "inner" for a mesh that is not closed, not outward or self-intersecting, and the
// errors of lattice_mesh. std::runtime_error when CGAL's corefinement fails on the band.
TriangleMesh trimmed_lattice_mesh(const FlatLattice& lattice, const MeshOptions& options, const TrimmedMeshRequest& request,
                                  TrimmedMeshStats* stats = nullptr, Progress& progress = no_progress());

}  // namespace steady

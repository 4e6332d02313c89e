#pragma once
// A lattice trimmed into a body as a mesh, optionally with a skin: the mesh counterpart of a LatticePart.
//
// The mesh's elements (hub sphere patches, beam strips) are classified against the surface the lattice is trimmed
// to (the body, or with a skin its inner offset): elements clear inside are placed whole, those clear outside
// dropped, and only the band of elements that may cross goes through one Boolean (CGAL's exact corefinement),
// closed by caps where it meets the others. The caps at inside elements are removed again, and the band joins the
// inside part along their own circles. With a skin the band is cut at the inner surface, and the rest of that
// surface and the body's surface bound the skin (see band_boolean in trimmed_mesh.cpp).
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
  std::int64_t band_triangles = 0;           // triangles that went through the Boolean
  std::int64_t moved_clear = 0;              // band vertices within float resolution of the wall, moved off it
  std::int64_t float_removed_triangles = 0;  // of its result, made degenerate by rounding to floats and removed
  // Phases: checking the body's meshes, planning the hubs, classifying, placing the pieces, the Boolean (with its
  // rounding to double), rounding to floats with the band's repair, joining.
  double check_seconds = 0.0, plan_seconds = 0.0, classify_seconds = 0.0, pieces_seconds = 0.0;
  double boolean_seconds = 0.0, float_seconds = 0.0, join_seconds = 0.0;
};

// InvalidInput naming "body" or "inner" for a mesh that is not closed, not outward or self-intersecting, and the
// errors of lattice_mesh. std::runtime_error when CGAL's corefinement fails on the band.
TriangleMesh trimmed_lattice_mesh(const FlatLattice& lattice, const MeshOptions& options, const TrimmedMeshRequest& request,
                                  TrimmedMeshStats* stats = nullptr, Progress& progress = no_progress());

}  // namespace steady

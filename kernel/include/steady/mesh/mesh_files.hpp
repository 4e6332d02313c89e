#pragma once
// Mesh files for printers and other tools: binary STL, OBJ, 3MF (core mesh, through lib3mf) and 3MF with the Beam
// Lattice extension v1.2 (written here: Debian's lib3mf 1.8.1 writes a non-standard clipping attribute, no
// representation mesh and no balls). Every writer writes to a temporary file renamed into place when complete,
// and refuses a bad path with InvalidInput naming "path".
#include <cstdint>
#include <string>

#include "steady/core/progress.hpp"
#include "steady/lattice/flat_lattice.hpp"
#include "steady/mesh/lattice_mesh.hpp"
#include "steady/mesh/triangle_mesh.hpp"

namespace steady {

// The name goes into the STL header (80 bytes, cut to fit) and the 3MF object.
void write_stl(const TriangleMesh& mesh, const std::string& path, const std::string& name = "lattice");
void write_obj(const TriangleMesh& mesh, const std::string& path, const std::string& name = "lattice");

// A binary STL read back (tests, tools): vertices welded where their coordinates agree exactly.
TriangleMesh read_stl(const std::string& path);

// The lattice's mesh streamed to a binary STL chunk by chunk: the whole mesh is never held, so lattices beyond
// the memory an indexed mesh would need still go to a printer. Returns the stats of the mesh written.
LatticeMeshStats write_lattice_stl(const FlatLattice& lattice, const MeshOptions& options, const std::string& path,
                                   const std::string& name = "lattice", Progress& progress = no_progress());

struct ThreeMfOptions {
  std::string name = "lattice";
  std::string unit = "millimeter";  // micron, millimeter, centimeter, inch, foot or meter (3MF's units)
};

// A core 3MF of one mesh object (lib3mf; coordinates as 32-bit floats, as 3MF readers hold them).
void write_3mf(const TriangleMesh& mesh, const std::string& path, const ThreeMfOptions& options = {});

struct BeamLatticeOptions : ThreeMfOptions {
  // Optional: a mesh shown by viewers without beam-lattice support (never used for manufacturing), and a closed
  // mesh of the body the lattice is clipped to (clippingmode "inside").
  const TriangleMesh* representation = nullptr;
  const TriangleMesh* clipping = nullptr;
};

// A 3MF beam lattice: one vertex per ball, one beam per beam with its two end radii (a conical frustum between
// the ball centers with sphere caps, which is the convex hull of the end balls exactly when the radii are equal;
// otherwise within r (1 / cos(phi) - 1) of it, phi the cone's half-angle), one ball per ball with a beam
// (balls extension). Balls without beams go into the object's triangles (tessellated at 1e-3 of their radius).
struct BeamLatticeStats {
  std::int64_t vertices = 0, beams = 0, balls = 0, lone_balls = 0;
  std::uint64_t bytes = 0;  // file size
};
BeamLatticeStats write_3mf_beam_lattice(const FlatLattice& lattice, const std::string& path,
                                        const BeamLatticeOptions& options = {}, Progress& progress = no_progress());

}  // namespace steady

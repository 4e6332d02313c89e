#pragma once
// The Boolean-free B-rep of a clean lattice (see clean_check.hpp for "clean").
//
// Per ball, one spherical face with one hole per beam; per beam, one conical face (cylindrical for equal radii)
// between its two exit circles. Every circle is ONE set of TopoDS_Edges carrying both its pcurve on the sphere
// and its pcurve on the cone, so the faces form closed shells directly: no Boolean, no sewing. The expensive part
// of a spherical face (where its seam and poles go, and the (u, v) curves of its circles) is computed once per
// distinct hub shape and shared by its similar copies (hub_catalog.hpp); the rest is linear in the elements and
// runs in parallel.
//
// Building pieces of a lattice to glue them (what trimming does) is internal: src/brep/brep_pieces.hpp.
#include <TopoDS_Face.hxx>
#include <TopoDS_Shape.hxx>

#include <cstdint>
#include <vector>

#include "steady/lattice/flat_lattice.hpp"
#include "steady/lattice/lattice.hpp"
#include "steady/core/progress.hpp"

namespace steady {

// OpenCASCADE's confusion tolerance (Precision::Confusion()): the tolerance of exact edges and of faces.
constexpr double kBrepTolerance = 1e-7;
// The smallest ball radius and beam radius a B-rep is built for: 100 tolerances. Below about 3 tolerances a ball's
// sphere came out invalid (not closed); a feature within a few tolerances of its own size is not a shape.
constexpr double kMinimumBrepRadius = 100.0 * kBrepTolerance;

struct BrepBuildStats {
  std::int64_t balls = 0;          // spherical faces built
  std::int64_t beams = 0;          // beams built (whole or half)
  std::int64_t faces = 0;
  std::int64_t distinct_hubs = 0;  // distinct hub shapes (each laid out once)
  std::int64_t cut_caps = 0;       // planar disks closing cuts
  std::int64_t seam_crossing_circles = 0;  // circles of distinct hub shapes crossed by their sphere's seam
  std::int64_t core_hubs = 0;      // hubs whose exit circles overlap, built from a core (hub_core.hpp)
  std::int64_t distinct_cores = 0;
  std::int64_t fused_cores = 0;    // of those, built by a Boolean Fuse (stumps of unequal end radii, tangent caps)
  std::int64_t tight_cores = 0;    // of those, built with tight collars for beams too short for roomy ones
  std::int64_t hub_groups = 0;     // groups of crowded hubs joined by beams too short for them, built as one
  std::int64_t grouped_hubs = 0;   // the hubs in those groups
  std::int64_t foreign_groups = 0; // groups of hubs whose elements meet elements of other nodes, built as one
  std::int64_t foreign_hubs = 0;   // the hubs in those groups
  std::int64_t joints = 0;         // circles added inside beams to join two fixed seams
  double layout_seconds = 0.0;     // catalog, sphere layouts and (u, v) curves
  double topology_seconds = 0.0;   // vertices, edges, faces
};

// Among frames whose margin reaches kGoodLayoutMargin, which to prefer. Fewest crossings gives the simplest faces
// (holes are inner wires); most crossings exercises every role of the general topology (tests, and a check that
// the builder does not depend on the choice).
enum class SeamPreference { FewestCrossings, MostCrossings };

// Groups faces into connected shells (faces sharing an edge), one solid per shell: a TopoDS_Solid when there is
// one, otherwise a compound of solids (a lattice may have several components, lone balls for instance).
TopoDS_Shape solids_from_faces(const std::vector<TopoDS_Face>& faces, Progress& progress = no_progress());

struct LatticeBrep {
  TopoDS_Shape shape;
  BrepBuildStats stats;
};

// The whole lattice. Hubs whose exit circles overlap (the hull model, crowded hubs) are built from cores; hubs
// joined by beams too short for their collars get tight collars, or are built as one, and so are the hubs of
// elements meeting foreign ones (brep/foreign_groups.hpp; groups of up to 256 hubs, larger ones throw
// InvalidInput naming the contacts).
LatticeBrep build_lattice_brep(const FlatLattice& lattice, SeamPreference seams = SeamPreference::FewestCrossings,
                               Progress& progress = no_progress());
LatticeBrep build_lattice_brep(const Lattice& lattice);

}  // namespace steady

#pragma once
// Never an invalid shape handed out (issue 17): whatever path built a lattice's B-rep (Boolean-free hubs, crowded
// cores, groups of hubs fused as one, the trim's Booleans and its union with the skin), the result is checked before
// it is returned, and a failed check is an error naming the hubs nearest the trouble, never a silent part.

#include <TopoDS_Shape.hxx>

#include <cstdint>
#include <vector>

#include <utility>
#include <vector>

#include "steady/brep/brep_builder.hpp"
#include "steady/lattice/flat_lattice.hpp"

namespace steady {

// Connected components of the lattice: balls joined by beams (a degenerate beam joins a ball to the one it is
// nested in) or by foreign contacts (`touching`: pairs of balls whose elements meet, foreign_groups.hpp). A built
// lattice has one solid for each.
std::int64_t component_count(const FlatLattice& f,
                             const std::vector<std::pair<std::int64_t, std::int64_t>>& touching = {});

// Balls nearest to the invalid faces of `shape` (at most `limit` of them), to name the hubs in an error.
std::vector<std::int64_t> balls_near_invalid_faces(const FlatLattice& f, const TopoDS_Shape& shape, int limit);

// The whole lattice built without a body: one solid per connected component, and valid as it reads back from its
// BREP text where crowded hubs were built from cores. Throws InvalidInput (the design's business: thin the beams).
void check_built_lattice(const FlatLattice& f, const LatticeBrep& built,
                         const std::vector<std::pair<std::int64_t, std::int64_t>>& touching = {});

// A trimmed part (the lattice, or the lattice united with its skin) as assembled from its faces: valid, as it reads
// back from its BREP text where crowded hubs were built from cores. Throws std::runtime_error, so that the trim
// tries its next way (another layout of the boundary hubs' spheres) before it gives up.
void check_trimmed_part(const FlatLattice& f, const TopoDS_Shape& part, std::int64_t core_hubs);

}  // namespace steady

#pragma once
// Equal geometry written once in a STEP file (issue 14, item 3: compact files).
//
// OpenCASCADE's STEP writer writes every curve of every edge on its own, with its own points, directions and, for
// each curve on a face (pcurve), its own 2D representation context. In a steady lattice most of them are equal:
// a pcurve lies in its sphere's or cone's own frame, so similar hubs have the same pcurves, and its points, its
// context and the directions of the lattice's few beam axes repeat thousands of times. Sharing them is ordinary
// STEP (an entity may be referred to by any number of others); the shapes a reader builds are the same.
#include <cstddef>
#include <string>

namespace steady {

struct StepSharing {
  std::size_t entities_before = 0, entities_after = 0;
  std::size_t bytes_before = 0, bytes_after = 0;
};

// The same exchange structure (ISO 10303-21) with each set of equal geometric entities (points, directions,
// placements, curves, pcurves and their 2D contexts: values, not topology) written once and referred to by all that
// referred to one of them; entities renumbered from 1 in their order, whitespace outside strings dropped (one space
// kept between the records of a complex entity), lines wrapped after a comma past 80 characters. Topology
// (vertices, edges, loops, faces, shells, solids), surfaces, products, representations and presentation are kept
// one for one. A value entity that something other than geometry or topology refers to (the placements of an
// assembly's components) is kept too. Throws std::runtime_error when `text` is not the DATA section's
// `#n=...;` records this writer reads (OpenCASCADE's writer always gives them).
std::string share_equal_geometry(std::string text, StepSharing* sharing = nullptr);

}  // namespace steady

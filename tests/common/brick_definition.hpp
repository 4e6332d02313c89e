#pragma once
// Tests and benchmarks describe most lattices by the fields of a steady brick: template, counts, U V W and G.
// This builder keeps those fixtures readable; it converts to the kernel's LatticeDefinition (whose layout is a
// SteadyBrickLayout) wherever a Lattice is constructed from it.
#include <vector>

#include "steady/lattice/lattice.hpp"

namespace steady::test {

struct BrickDefinition {
  std::vector<TemplateNode> nodes;
  std::vector<BeamPattern> beams;
  Counts counts;
  DirectionControl u, v, w;
  Similarity placement;
  std::vector<NodeId> omitted;

  operator LatticeDefinition() const {  // NOLINT(google-explicit-constructor): a fixture builder
    return {nodes, beams, SteadyBrickLayout::make(counts, u, v, w, placement), omitted};
  }
};

}  // namespace steady::test

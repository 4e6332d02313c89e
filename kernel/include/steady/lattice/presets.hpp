#pragma once
// Preset unit cells (cubic, BCC, FCC, octet, diamond, Kelvin, honeycomb): node positions in cell units and the
// beam patterns that join nearest neighbours, shared by the C++ tools, the benchmarks and the workbench
// (steadylattice.preset, latticewb.kernel.presets).
//
// A preset of (cu, cv, cw) cells is a steady lattice of (cu+1, cv+1, cw+1) groups, one per cell corner; the nodes
// of the last layers that would lie outside the box of whole cells are omitted with their beams.
#include <array>
#include <string>
#include <vector>

#include "steady/lattice/lattice.hpp"

namespace steady {

struct PresetCell {
  std::string name;
  std::vector<Vec3> basis;         // node positions as fractions of the cell, in [0, 1)
  Vec3 aspect{1.0};                // cell edge along each axis, in units of the cell size
  double neighbour_distance = 1.0; // in cell-size units: the beams join nodes this far apart
  bool corner_beams_only = false;  // FCC: only the pairs with the cell corner (node 0) at one end
};

// The names of every preset, in a fixed order.
const std::vector<std::string>& preset_names();
// InvalidInput naming `field` for an unknown name (the message lists the known ones).
const PresetCell& preset_cell(const std::string& name, const std::string& field = "preset");
// Patterns (n1, di, dj, dk, n2) joining basis nodes at the neighbour distance, each pair once, with a
// non-negative offset (lexicographically): what the workbench's presets build.
std::vector<BeamPattern> preset_beam_patterns(const PresetCell& cell);
// The nodes (i, j, k, n) of groups 0..cells that lie outside the box of `cells` whole cells.
std::vector<NodeId> preset_outside_nodes(const PresetCell& cell, const std::array<std::int64_t, 3>& cells);

// A regular lattice of a preset: `cells` cells of `cell_size` (times the aspect), node radius and beam radius
// (0: each beam the hull of its balls), translations as steps; the building block of the benchmarks and tools.
Lattice preset_lattice(const std::string& name, const std::array<std::int64_t, 3>& cells, double cell_size,
                       double node_radius, double beam_radius);

}  // namespace steady

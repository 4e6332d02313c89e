#pragma once
// BeCOTS lattices (Kurzeja's dissertation, 4.5 and 6.3): balls and beams laid on a BeCOTS map, one group per tile,
// in one layer (a slab) or in counts.w layers (a stack). The layers share the map's field; each next one only moves
// corner A, and the template group with it, by a constant step: along the axis (6.3 (a), `layer_raise`: its group
// origins lie on the raised map M_kz(x, y) = S(x, y)(A + k z T)) and/or along the range's normal at A (6.3 (b),
// `layer_offset`: A_k = A + k d N, on the line of A corners the dissertation's O(1) stack query maps points onto).
// They are steady bricks: group (i, j, k) is placed by V^j o U^i o W^k, with U = field(1/nu, 0) and V = field(0,
// 1/nv) the map's commuting per-tile similarities and W the translation by z T + d N, applied first. So the result
// is an ordinary Lattice (layout "any-order-brick", order W U V) and every consumer (queries, properties, B-rep,
// meshes, files) takes it as it is. The template moves rigidly with A: a node away from A (kagome, honeycomb) is
// moved by the same step as A, not by the step scaled and turned to its own place.
#include <string>
#include <vector>

#include "steady/cots/becots_map.hpp"
#include "steady/lattice/lattice.hpp"

namespace steady {

// The nodes of one group as points (s, t) of its parameter cell [0,1)^2, and the beam patterns between them.
struct BecotsConnectivity {
  std::vector<Vec2> nodes;
  std::vector<BeamPattern> beams;
};

// The connectivities of the dissertation's figure 4.13: "triangle" (one node, six beams per inner hub),
// "kagome" (three nodes at the edge midpoints of the triangle mesh, four beams per hub) and "honeycomb" (two nodes,
// three beams per hub). InvalidInput naming the choices otherwise.
BecotsConnectivity becots_connectivity(const std::string& name);

// The lattice of `cells` on the nu x nv tiles of `map` (counts.u = nu, counts.v = nv), in counts.w layers, each
// moved from the one before by `layer_raise` along the axis plus `layer_offset` along the normal at A
// (BecotsMap::normal). Node n of group (0, 0) sits at map(s / nu, t / nv) with the radius
// `radius` m_u^{s/nu} m_v^{t/nv} (so every node is a copy of one ball, scaled with the map); beams are the hull of
// their balls, or, with beam_ratio in (0, 1], cones of beam_ratio times their nodes' radii.
Lattice becots_lattice(const BecotsMap& map, const BecotsConnectivity& cells, const Counts& counts, double radius,
                       double layer_raise = 0.0, double beam_ratio = 0.0, double layer_offset = 0.0);

}  // namespace steady

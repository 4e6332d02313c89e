#include "steady/cots/becots_lattice.hpp"

#include <cmath>
#include <string>

#include "steady/core/errors.hpp"

namespace steady {

BecotsConnectivity becots_connectivity(const std::string& name) {
  auto beam = [](int from, int di, int dj, int to) {
    BeamPattern b;
    b.from = from, b.di = di, b.dj = dj, b.dk = 0, b.to = to;
    return b;
  };
  if (name == "triangle")  // the grid's edges along x, y and one diagonal
    return {{{0.0, 0.0}}, {beam(0, 1, 0, 0), beam(0, 0, 1, 0), beam(0, 1, 1, 0)}};
  if (name == "kagome") {
    // Nodes at the midpoints of the triangle mesh's edges (A on x, B on y, C on the diagonal); each triangle of the
    // mesh joins the midpoints of its three edges.
    const int A = 0, B = 1, C = 2;
    return {{{0.5, 0.0}, {0.0, 0.5}, {0.5, 0.5}},
            {beam(A, 1, 0, B), beam(C, 1, 0, B), beam(C, 0, 0, A),    // lower triangle of cell (i, j)
             beam(B, 0, 1, A), beam(C, 0, 1, A), beam(C, 0, 0, B)}};  // upper triangle
  }
  if (name == "honeycomb") {
    // The two nodes of each triangle pair; node P joins Q of its own group and of the groups before it.
    const int P = 0, Q = 1;
    return {{{1.0 / 3.0, 1.0 / 3.0}, {2.0 / 3.0, 2.0 / 3.0}}, {beam(P, 0, 0, Q), beam(Q, 1, 0, P), beam(Q, 0, 1, P)}};
  }
  fail_input("connectivity", "unknown connectivity '" + name + "' (expected triangle, kagome or honeycomb)");
}

Lattice becots_lattice(const BecotsMap& map, const BecotsConnectivity& cells, const Counts& counts, double radius,
                       double layer_raise, double beam_ratio, double layer_offset) {
  if (counts.u < 1 || counts.v < 1 || counts.w < 1) fail_input("counts", "each count must be >= 1");
  require_positive(radius, "radius");
  require_finite(layer_raise, "layer_raise");
  require_finite(layer_offset, "layer_offset");
  require_finite(beam_ratio, "beam_ratio");
  if (beam_ratio < 0.0 || beam_ratio > 1.0) fail_input("beam_ratio", "must be 0 (hull beams) or in (0, 1]");
  if (counts.w > 1 && layer_raise == 0.0 && layer_offset == 0.0)
    fail_input("layer_raise", "or layer_offset must be non-zero for more than one layer");
  if (cells.nodes.empty()) fail_input("cells.nodes", "a group needs at least one node");
  const double du = 1.0 / static_cast<double>(counts.u), dv = 1.0 / static_cast<double>(counts.v);
  std::vector<TemplateNode> nodes;
  for (std::size_t n = 0; n < cells.nodes.size(); ++n) {
    const Vec2& st = cells.nodes[n];
    require_finite(st.x, "cells.nodes[" + std::to_string(n) + "].s");
    require_finite(st.y, "cells.nodes[" + std::to_string(n) + "].t");
    const double x = st.x * du, y = st.y * dv;
    nodes.push_back({map.map(x, y), radius * std::exp(x * map.log_u().real() + y * map.log_v().real())});
  }
  std::vector<BeamPattern> beams = cells.beams;
  if (beam_ratio > 0.0)
    for (BeamPattern& b : beams) {
      if (b.from < 0 || b.to < 0 || b.from >= static_cast<int>(nodes.size()) || b.to >= static_cast<int>(nodes.size()))
        fail_input("cells.beams", "a beam pattern names a node the group does not have");
      b.from_radius = beam_ratio * nodes[static_cast<std::size_t>(b.from)].radius;
      b.to_radius = beam_ratio * nodes[static_cast<std::size_t>(b.to)].radius;
    }
  const DirectionControl U{map.field(du, 0.0), StepControl::Incremental};
  const DirectionControl V{map.field(0.0, dv), StepControl::Incremental};
  const DirectionControl W{Similarity::translation(layer_raise * map.axis() + layer_offset * map.normal()), StepControl::Incremental};
  return Lattice::ordered(std::move(nodes), std::move(beams), counts, U, V, W, Similarity::identity(), {2, 0, 1});
}

}  // namespace steady

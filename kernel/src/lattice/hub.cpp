#include "steady/lattice/hub.hpp"

#include <cmath>

#include "steady/core/errors.hpp"

namespace steady {

BeamCone beam_cone(const Ball& a, const Ball& b) {
  BeamCone c;
  c.a = a.center;
  c.b = b.center;
  c.ra = a.radius;
  c.rb = b.radius;
  const Vec3 d = b.center - a.center;
  c.length = glm::length(d);
  if (c.length > 0.0) c.axis = d / c.length;
  if (c.has_lateral_surface()) {
    c.sin_phi = (c.ra - c.rb) / c.length;
    c.cos_phi = std::sqrt((1.0 - c.sin_phi) * (1.0 + c.sin_phi));
  }
  return c;
}

Circle BeamCone::tangent_circle_a() const {
  return {a + (ra * sin_phi) * axis, axis, ra * cos_phi};
}

Circle BeamCone::tangent_circle_b() const {
  return {b + (rb * sin_phi) * axis, axis, rb * cos_phi};
}

double cone_exit_position(const BeamCone& cone, bool at_a, double node_radius) {
  const double r = at_a ? cone.ra : cone.rb;
  const double s = at_a ? cone.sin_phi : -cone.sin_phi;  // seen from the other end the cone widens
  // Roots of x^2 + radius_at(x)^2 = R^2: x = r s +- cos(phi) sqrt(R^2 - r^2); the beam leaves at the larger.
  const double excess = std::max(0.0, (node_radius - r) * (node_radius + r));
  return r * s + cone.cos_phi * std::sqrt(excess);
}

std::vector<std::pair<BeamId, bool>> incident_beams(const Lattice& lattice, const NodeId& node) {
  std::vector<std::pair<BeamId, bool>> out;
  const auto& patterns = lattice.definition().beams;
  for (int p = 0; p < static_cast<int>(patterns.size()); ++p) {
    const BeamPattern& b = patterns[p];
    if (b.from == node.n) {
      const BeamId id{node.i, node.j, node.k, p};
      if (lattice.beam_exists(id)) out.emplace_back(id, true);
    }
    if (b.to == node.n) {
      const BeamId id{node.i - b.di, node.j - b.dj, node.k - b.dk, p};
      if (lattice.beam_exists(id)) out.emplace_back(id, false);
    }
  }
  return out;
}

void move_cut(Stump& stump, double position) {
  stump.cut_position = position;
  stump.cut = {stump.cone.a + position * stump.cone.axis, stump.cone.axis, stump.cone.radius_at(position)};
}

Hub hub(const Lattice& lattice, const NodeId& node) {
  if (!lattice.node_exists(node)) fail_input("hub", "the node does not exist");
  Hub h;
  h.node = node;
  h.ball_index = lattice.ball_index(node);
  h.ball = lattice.ball(node);
  for (const auto& [id, at_start] : incident_beams(lattice, node)) {
    const BeamGeometry g = lattice.beam(id);
    Stump s;
    s.beam = id;
    s.beam_index = lattice.beam_index(id);
    s.at_start = at_start;
    s.cone = at_start ? beam_cone(g.start, g.end) : beam_cone(g.end, g.start);
    s.exit_position = cone_exit_position(s.cone, true, h.ball.radius);
    const Vec3& n = s.cone.axis;
    s.on_node = {s.cone.a + s.exit_position * n, n,
                 std::sqrt(std::max(0.0, h.ball.radius * h.ball.radius - s.exit_position * s.exit_position))};
    move_cut(s, 0.5 * s.cone.length);
    h.stumps.push_back(s);
  }
  return h;
}

}  // namespace steady

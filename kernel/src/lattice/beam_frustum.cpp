#include "steady/lattice/beam_frustum.hpp"

#include <tbb/parallel_for.h>

#include <cmath>

#include "steady/lattice/flat_lattice.hpp"
#include "steady/core/progress.hpp"

namespace steady {

BeamFrustum beam_frustum(const Ball& node_a, const Ball& node_b, double ra, double rb) {
  BeamFrustum f;
  f.cone = beam_cone({node_a.center, ra}, {node_b.center, rb});
  if (!f.cone.has_lateral_surface()) return f;
  f.exit_a = cone_exit_position(f.cone, true, node_a.radius);
  f.exit_b = cone_exit_position(f.cone, false, node_b.radius);
  if (!(f.exit_a + f.exit_b < f.cone.length)) return f;
  const Vec3& n = f.cone.axis;
  const auto rim = [](double R, double x) { return std::sqrt(std::max(0.0, (R - x) * (R + x))); };
  f.circle_a = {node_a.center + f.exit_a * n, n, rim(node_a.radius, f.exit_a)};
  f.circle_b = {node_b.center - f.exit_b * n, -n, rim(node_b.radius, f.exit_b)};
  f.exists = true;
  return f;
}

Circle BeamFrustum::cut_circle() const {
  const double x = cut_position();
  return {cone.a + x * cone.axis, cone.axis, cone.radius_at(x)};
}

std::vector<BeamFrustum> beam_frustums(const FlatLattice& f) {
  std::vector<BeamFrustum> out(f.beam_count());
  Progress* const caller = current_progress();  // cancellable (Ctrl-C) on large lattices
  tbb::parallel_for(std::int64_t(0), f.beam_count(), [&](std::int64_t e) {
    const ProgressScope scope(caller);
    if ((e & 4095) == 0) poll_progress();
    const FlatBeam& b = f.beams[e];
    out[e] = beam_frustum(f.balls[b.a], f.balls[b.b], b.ra, b.rb);
  });
  return out;
}

double frustum_volume(const BeamFrustum& f) {
  if (!f.exists) return 0.0;
  const double r1 = f.circle_a.radius, r2 = f.circle_b.radius;
  return M_PI * f.length() * (r1 * r1 + r1 * r2 + r2 * r2) / 3.0;
}

double spherical_cap_volume(double radius, double plane_position) {
  const double h = radius - plane_position;
  return M_PI * h * h * (3.0 * radius - h) / 3.0;
}

}  // namespace steady
